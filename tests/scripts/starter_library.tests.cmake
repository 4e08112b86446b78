# The generated starter library (tools/starter_library):
#  starter_library.contents      every benchmark class, honest labels, example fields and
#                                constraints, self-retrieval (starter_library.check.c, C API only)
#  starter_library.reproducible  generating it again gives the same bytes
#  starter_library.demo          `macrocon demo` runs on it and writes every result file
add_executable(starter_library_check ${CMAKE_CURRENT_SOURCE_DIR}/scripts/starter_library.check.c)
set_target_properties(starter_library_check PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(starter_library_check PRIVATE -Wall -Wextra -pedantic $<$<BOOL:${MACROCON_WERROR}>:-Werror>)
target_link_libraries(starter_library_check PRIVATE macrocon m)
add_dependencies(starter_library_check macrocon_starter_library)
add_test(NAME starter_library.contents
  COMMAND starter_library_check ${MACROCON_STARTER_LIBRARY} 13 eye nose mouth ear face hand foot arm)
set_tests_properties(starter_library.contents PROPERTIES TIMEOUT 600)

add_test(NAME starter_library.reproducible
  COMMAND ${CMAKE_COMMAND} -DGENERATOR=$<TARGET_FILE:build_starter_library>
          -DENTRIES=${PROJECT_SOURCE_DIR}/samples/starter-library/entries.json
          -DDATA=${PROJECT_SOURCE_DIR}/samples/data -DEXPECTED=${MACROCON_STARTER_LIBRARY}
          -DWORK=${PROJECT_BINARY_DIR}/starter-library-again
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/starter_library.reproducible.cmake)
set_tests_properties(starter_library.reproducible PROPERTIES TIMEOUT 900)

add_test(NAME starter_library.demo
  COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_cli> -DOUT=${PROJECT_BINARY_DIR}/demo-out-test
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/starter_library.demo.cmake)
set_tests_properties(starter_library.demo PROPERTIES TIMEOUT 900)
