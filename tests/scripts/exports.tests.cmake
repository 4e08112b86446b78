# The shared library exports mcon_* symbols and nothing else.
add_test(NAME scripts.exported_symbols_are_mcon_only
  COMMAND ${CMAKE_COMMAND} -DLIB=$<TARGET_FILE:macrocon> -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_exports.cmake)
