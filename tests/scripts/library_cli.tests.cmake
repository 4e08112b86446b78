# `macrocon library build | add | info` and `macrocon query` on the sample body: every entry's own
# region must find that entry first, info --json must describe the library, errors must fail.
add_test(NAME scripts.library_cli
  COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_cli>
          -DMESH=${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz
          -DWORK=${CMAKE_CURRENT_BINARY_DIR}/library_cli
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_library_cli.cmake)
set_tests_properties(scripts.library_cli PROPERTIES TIMEOUT 600)
