# libFuzzer runs of the parsers and the C API (tests/fuzz): each test builds its target in the
# standalone clang project in <build>/fuzz, seeds it (the library loader with valid libraries,
# the others with tests/fuzz/corpus/<target>) and fuzzes for MACROCON_FUZZ_SECONDS (the library
# loader) or MACROCON_FUZZ_TARGET_SECONDS (the others); any crash, sanitizer report or timeout
# fails the test. Registered only where clang++ exists (CI installs clang-14 and
# libclang-rt-14-dev). tools/fuzz.sh runs every target for a given time.
# The fuzzers are their own clang ASan build, so the sanitizer suite does not run them a second time.
if(MACROCON_SANITIZE)
  return()
endif()
find_program(MACROCON_FUZZ_CXX NAMES clang++-14 clang++)
if(NOT MACROCON_FUZZ_CXX)
  message(STATUS "clang++ not found: the scripts.fuzz_* tests are not registered")
  return()
endif()
set(MACROCON_FUZZ_SECONDS 60 CACHE STRING "Seconds the library loader fuzz test runs libFuzzer")
set(MACROCON_FUZZ_TARGET_SECONDS 5 CACHE STRING "Seconds each other fuzz test runs libFuzzer")
function(macrocon_fuzz_test name target seconds)
  add_test(NAME scripts.${name}
    COMMAND ${CMAKE_COMMAND}
      -DSOURCE_DIR=${PROJECT_SOURCE_DIR}/tests/fuzz
      -DBINARY_DIR=${PROJECT_BINARY_DIR}/fuzz
      -DCXX=${MACROCON_FUZZ_CXX}
      -DGENERATOR=${CMAKE_GENERATOR}
      -DSECONDS=${seconds}
      -DFUZZ_TARGET=${target}
      -P ${PROJECT_SOURCE_DIR}/tests/scripts/run_fuzz.cmake)
  # Building the clang project takes a few minutes on a loaded 2-core machine; the tests share
  # its build directory, so they run one at a time.
  math(EXPR timeout "${seconds} + 1200")
  set_tests_properties(scripts.${name} PROPERTIES TIMEOUT ${timeout} LABELS fuzz RESOURCE_LOCK macrocon_fuzz_build)
endfunction()
macrocon_fuzz_test(fuzz_library_loader library_loader_fuzzer ${MACROCON_FUZZ_SECONDS})
macrocon_fuzz_test(fuzz_mesh_reader mesh_reader_fuzzer ${MACROCON_FUZZ_TARGET_SECONDS})
macrocon_fuzz_test(fuzz_field_reader field_reader_fuzzer ${MACROCON_FUZZ_TARGET_SECONDS})
macrocon_fuzz_test(fuzz_capi capi_fuzzer ${MACROCON_FUZZ_TARGET_SECONDS})
