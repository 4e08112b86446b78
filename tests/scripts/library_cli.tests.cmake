# `macrocon library build | add | info` and `macrocon query` on the sample body: every entry's own
# region must find that entry first, info --json must describe the library, errors must fail.
add_test(NAME scripts.library_cli
  COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_cli>
          -DMESH=${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz
          -DWORK=${CMAKE_CURRENT_BINARY_DIR}/library_cli
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_library_cli.cmake)
set_tests_properties(scripts.library_cli PROPERTIES TIMEOUT 600)

# A library authored from the CLI alone (guides and features as OBJ lines, singularities as a
# table, fields as PLY vertex properties) round-trips through info, the Python binding and
# `embed --source LIB --entry`; bad constraint files are refused with the fix named.
include(${CMAKE_CURRENT_LIST_DIR}/sanitizer_preload.cmake)
if(NOT MACROCON_SANITIZE OR MACROCON_SANITIZER_ENV)
  set(MACROCON_PYTHON /usr/bin/python3 CACHE FILEPATH "Python with numpy and pytest for the binding tests")
  add_test(NAME scripts.cli_authoring
    COMMAND ${MACROCON_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli_authoring.py
            $<TARGET_FILE:macrocon_cli> ${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz
            ${CMAKE_CURRENT_BINARY_DIR}/cli_authoring)
  set_tests_properties(scripts.cli_authoring PROPERTIES TIMEOUT 600
    ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;PYTHONPATH=${PROJECT_SOURCE_DIR}/bindings/python;${MACROCON_SANITIZER_ENV}")
endif()
