# The product CLI computes through the public API only (check_cli_public_api.cmake); the files
# below still use core stages directly and move next (issue 13).
set(MACROCON_CLI_PENDING "")
string(REPLACE ";" "," _pending "${MACROCON_CLI_PENDING}")
add_test(NAME scripts.cli_public_api
  COMMAND ${CMAKE_COMMAND} -DCLI_DIR=${PROJECT_SOURCE_DIR}/tools/cli "-DPENDING=${_pending}"
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli_public_api.cmake)
add_test(NAME scripts.cli_public_api_catches_a_violation
  COMMAND ${CMAKE_COMMAND} -DCLI_DIR=${CMAKE_CURRENT_SOURCE_DIR}/scripts/cli_public_api_violation
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli_public_api.cmake)
set_tests_properties(scripts.cli_public_api_catches_a_violation PROPERTIES
  PASS_REGULAR_EXPRESSION "cmd_uses_core.cpp:3: includes \"patch/geodesic_disk_patch.h\"")
