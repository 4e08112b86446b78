execute_process(COMMAND ${ABIDIFF} --headers-dir2 ${HEADERS} ${BASELINE} ${LIB}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
# abidiff exit status is a bit field: 1 error, 2 usage error, 4 ABI change, 8 incompatible change.
math(EXPR bad "${rc} & 11")
if(NOT bad EQUAL 0)
  message(FATAL_ERROR "ABI check failed (abidiff status ${rc}):\n${out}\n${err}")
endif()
message(STATUS "ABI compatible with the baseline (abidiff status ${rc})\n${out}")
