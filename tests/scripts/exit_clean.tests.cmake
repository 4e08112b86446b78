# Processes exit cleanly after parallel work and mcon_shutdown (docs/design.md §5): a host linked
# with the library, and a C host that dlopen()s, uses, shuts down and dlclose()s it in a loop.
# Each program runs several times: the crash this guards against showed up 1 run in 5.
add_executable(capi_exit_after_parallel_work ${CMAKE_CURRENT_SOURCE_DIR}/capi/exit_after_parallel_work.cpp)
target_include_directories(capi_exit_after_parallel_work PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
# macrocon_core only for the header-only test meshes (Eigen); the work goes through libmacrocon.
target_link_libraries(capi_exit_after_parallel_work PRIVATE macrocon macrocon_core TBB::tbb Threads::Threads)
macrocon_warnings(capi_exit_after_parallel_work)
add_test(NAME capi.exit_clean_after_parallel_work
  COMMAND ${CMAKE_COMMAND} -DRUNS=5 -DEXE=$<TARGET_FILE:capi_exit_after_parallel_work>
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/run_repeatedly.cmake)

add_executable(capi_dlopen_cycle ${CMAKE_CURRENT_SOURCE_DIR}/capi/dlopen_cycle.c)
set_target_properties(capi_dlopen_cycle PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(capi_dlopen_cycle PRIVATE -Wall -Wextra -pedantic $<$<BOOL:${MACROCON_WERROR}>:-Werror>)
# Headers only: the library is loaded at run time, never linked.
target_include_directories(capi_dlopen_cycle PRIVATE ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(capi_dlopen_cycle PRIVATE ${CMAKE_DL_LIBS})
add_dependencies(capi_dlopen_cycle macrocon)
add_test(NAME capi.dlopen_shutdown_dlclose_cycles
  COMMAND ${CMAKE_COMMAND} -DRUNS=5 -DEXE=$<TARGET_FILE:capi_dlopen_cycle> -DARGS=$<TARGET_FILE:macrocon>
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/run_repeatedly.cmake)
