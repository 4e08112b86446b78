# Runs EXE [ARGS] RUNS times; fails on the first run that does not exit with status 0 (a crash
# at exit shows up as a signal here) or, if EXPECT is given, whose stdout lacks a line containing
# EXPECT (e.g. what an exit hook reports after main returned).
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
if(NOT RUNS)
  set(RUNS 1)
endif()
separate_arguments(args UNIX_COMMAND "${ARGS}")
foreach(i RANGE 1 ${RUNS})
  run_checked(WHAT "run ${i} of ${RUNS}" OUTPUT_VARIABLE out ERROR_VARIABLE err COMMAND ${EXE} ${args})
  if(DEFINED EXPECT)
    string(FIND "${out}" "${EXPECT}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "run ${i} of ${RUNS}: output lacks '${EXPECT}'\n${out}\n${err}")
    endif()
  endif()
endforeach()
message(STATUS "${RUNS} clean runs of ${EXE} ${ARGS}: ${out}")
