# Driver for the fuzz ctests (see fuzz.tests.cmake) and tools/fuzz.sh: builds the standalone
# clang project and runs one target for SECONDS.
# -D SOURCE_DIR (tests/fuzz) BINARY_DIR CXX GENERATOR SECONDS [FUZZ_TARGET (library_loader_fuzzer)]
# The library loader is seeded by write_library_seeds; every other target by its committed corpus
# tests/fuzz/corpus/<target>. What a run adds accumulates in <build>/corpus[/<target>].
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
if(NOT DEFINED FUZZ_TARGET)
  set(FUZZ_TARGET library_loader_fuzzer)
endif()
if(FUZZ_TARGET STREQUAL "library_loader_fuzzer")
  run(${CMAKE_COMMAND} --build ${BINARY_DIR} -j 2 --target library_loader_fuzzer write_library_seeds)
  # Seeds are rewritten every run (they follow the current writer); the corpus accumulates.
  set(seeds ${BINARY_DIR}/seeds)
  set(corpus ${BINARY_DIR}/corpus)
  file(REMOVE_RECURSE ${seeds})
  file(MAKE_DIRECTORY ${seeds})
  run(${BINARY_DIR}/write_library_seeds ${seeds})
else()
  run(${CMAKE_COMMAND} --build ${BINARY_DIR} -j 2 --target ${FUZZ_TARGET})
  set(seeds ${SOURCE_DIR}/corpus/${FUZZ_TARGET})
  set(corpus ${BINARY_DIR}/corpus/${FUZZ_TARGET})
endif()
file(MAKE_DIRECTORY ${corpus} ${BINARY_DIR}/artifacts)
# Inputs up to the size of real files for the parsers (libFuzzer's default cap is the largest seed,
# a few KB); the C API target consumes a bounded prefix of its input, so it keeps the default.
set(max_len)
if(NOT FUZZ_TARGET STREQUAL "capi_fuzzer")
  set(max_len -max_len=2097152)
endif()

execute_process(
  COMMAND ${BINARY_DIR}/${FUZZ_TARGET}
    -max_total_time=${SECONDS} ${max_len} -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
    -artifact_prefix=${BINARY_DIR}/artifacts/${FUZZ_TARGET}-
    ${corpus} ${seeds}
  RESULT_VARIABLE rc
  ERROR_VARIABLE log)
file(WRITE ${BINARY_DIR}/last_run_${FUZZ_TARGET}.log "${log}")
# The run's summary lines: the last coverage line and the final stats.
string(REGEX MATCHALL "#[0-9]+\t[A-Z]+[^\n]*cov: [^\n]*" progress "${log}")
list(LENGTH progress n)
if(n GREATER 0)
  math(EXPR last "${n} - 1")
  list(GET progress ${last} final_progress)
  message(STATUS "libFuzzer ${FUZZ_TARGET}: ${final_progress}")
endif()
string(REGEX MATCHALL "stat::[^\n]*" stats "${log}")
foreach(line ${stats})
  message(STATUS "libFuzzer ${FUZZ_TARGET}: ${line}")
endforeach()
if(NOT rc EQUAL 0)
  message(STATUS "${log}")
  message(FATAL_ERROR "${FUZZ_TARGET} failed (${rc}); the input is in ${BINARY_DIR}/artifacts, log in "
                      "${BINARY_DIR}/last_run_${FUZZ_TARGET}.log")
endif()
