# src/ keeps its dependency rule (check_include_rule.cmake), and the check fails on a violation.
add_test(NAME scripts.include_rule
  COMMAND ${CMAKE_COMMAND} -DSRC_DIR=${PROJECT_SOURCE_DIR}/src -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_include_rule.cmake)
add_test(NAME scripts.include_rule_catches_a_violation
  COMMAND ${CMAKE_COMMAND} -DSRC_DIR=${CMAKE_CURRENT_SOURCE_DIR}/scripts/include_rule_violation
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_include_rule.cmake)
set_tests_properties(scripts.include_rule_catches_a_violation PROPERTIES
  PASS_REGULAR_EXPRESSION "retrieval/uses_map.h:3: retrieval/ includes \"map/surface_map.h\"")
