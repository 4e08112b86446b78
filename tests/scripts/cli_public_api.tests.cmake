# The product CLI computes through the public API only (check_cli_public_api.cmake): every file
# of tools/cli, with no exemption left (the last one, embed, moved in issue 13).
add_test(NAME scripts.cli_public_api
  COMMAND ${CMAKE_COMMAND} -DCLI_DIR=${PROJECT_SOURCE_DIR}/tools/cli
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli_public_api.cmake)
add_test(NAME scripts.cli_public_api_catches_a_violation
  COMMAND ${CMAKE_COMMAND} -DCLI_DIR=${CMAKE_CURRENT_SOURCE_DIR}/scripts/cli_public_api_violation
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli_public_api.cmake)
set_tests_properties(scripts.cli_public_api_catches_a_violation PROPERTIES
  PASS_REGULAR_EXPRESSION "cmd_uses_core.cpp:3: includes \"patch/geodesic_disk_patch.h\"")
