# Driver for the ctest scripts.fuzz_library_loader (see fuzz.tests.cmake).
# -D SOURCE_DIR (tests/fuzz) BINARY_DIR CXX GENERATOR SECONDS
foreach(var SOURCE_DIR BINARY_DIR CXX GENERATOR SECONDS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_fuzz.cmake needs -D${var}=...")
  endif()
endforeach()

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}")
  endif()
endfunction()

run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=)
run(${CMAKE_COMMAND} --build ${BINARY_DIR} -j 2)

# Seeds are rewritten every run (they follow the current writer); the corpus accumulates.
file(REMOVE_RECURSE ${BINARY_DIR}/seeds)
file(MAKE_DIRECTORY ${BINARY_DIR}/seeds ${BINARY_DIR}/corpus ${BINARY_DIR}/artifacts)
run(${BINARY_DIR}/write_library_seeds ${BINARY_DIR}/seeds)

execute_process(
  COMMAND ${BINARY_DIR}/library_loader_fuzzer
    -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
    -artifact_prefix=${BINARY_DIR}/artifacts/
    ${BINARY_DIR}/corpus ${BINARY_DIR}/seeds
  RESULT_VARIABLE rc
  ERROR_VARIABLE log)
file(WRITE ${BINARY_DIR}/last_run.log "${log}")
# The run's summary lines: the last coverage line and the final stats.
string(REGEX MATCHALL "#[0-9]+\t[A-Z]+[^\n]*cov: [^\n]*" progress "${log}")
list(LENGTH progress n)
if(n GREATER 0)
  math(EXPR last "${n} - 1")
  list(GET progress ${last} final_progress)
  message(STATUS "libFuzzer: ${final_progress}")
endif()
string(REGEX MATCHALL "stat::[^\n]*" stats "${log}")
foreach(line ${stats})
  message(STATUS "libFuzzer: ${line}")
endforeach()
if(NOT rc EQUAL 0)
  message(STATUS "${log}")
  message(FATAL_ERROR "library loader fuzzer failed (${rc}); the input is in ${BINARY_DIR}/artifacts, log in "
                      "${BINARY_DIR}/last_run.log")
endif()
