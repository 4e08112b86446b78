# Runs EXE [ARGS] RUNS times; fails on the first run that does not exit with status 0 (a crash
# at exit shows up as a signal here).
if(NOT RUNS)
  set(RUNS 1)
endif()
separate_arguments(args UNIX_COMMAND "${ARGS}")
foreach(i RANGE 1 ${RUNS})
  execute_process(COMMAND ${EXE} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "run ${i} of ${RUNS}: ${EXE} exited with '${rc}'\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "${RUNS} clean runs of ${EXE}: ${out}")
