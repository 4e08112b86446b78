# `macrocon-eval eval-retrieval` on the smallest real set (1 person, 1 face = 20 patches): the JSON keys
# and value ranges, both SVG plots, bit-identical results on 1 thread and on all, and clear errors
# for bad options. Small enough for the sanitizer build.
add_test(NAME scripts.eval_retrieval
  COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_eval> -DSHARED=${MACROCON_SHARED_DIR}
          -DOUT=${CMAKE_CURRENT_BINARY_DIR}/eval_retrieval
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/eval_retrieval.check.cmake)
set_tests_properties(scripts.eval_retrieval PROPERTIES TIMEOUT 600)
