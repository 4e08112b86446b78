# `macrocon-eval eval-mapping` end to end on a tiny run (two forearm pairs, one of them mirrored, few
# rigid candidates and thesis iterations): the JSON has the documented shape for all three
# methods, every map is flip-free, and bad options fail with a message.
add_test(NAME scripts.eval_mapping
  COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_eval> -DSHARED=${MACROCON_SHARED_DIR}
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_eval_mapping.cmake)
set_tests_properties(scripts.eval_mapping PROPERTIES TIMEOUT 900)
