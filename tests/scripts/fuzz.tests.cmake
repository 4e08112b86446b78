# libFuzzer run of the constraint library loader (tests/fuzz): builds the standalone clang project
# in <build>/fuzz, seeds it with valid libraries and fuzzes for MACROCON_FUZZ_SECONDS; any crash,
# sanitizer report or timeout fails the test. Registered only where clang++ exists (CI installs
# clang-14 and libclang-rt-14-dev).
# The fuzzer is its own clang ASan build, so the sanitizer suite does not run it a second time.
if(MACROCON_SANITIZE)
  return()
endif()
find_program(MACROCON_FUZZ_CXX NAMES clang++-14 clang++)
if(NOT MACROCON_FUZZ_CXX)
  message(STATUS "clang++ not found: scripts.fuzz_library_loader is not registered")
  return()
endif()
set(MACROCON_FUZZ_SECONDS 60 CACHE STRING "Seconds the library loader fuzz test runs libFuzzer")
add_test(NAME scripts.fuzz_library_loader
  COMMAND ${CMAKE_COMMAND}
    -DSOURCE_DIR=${PROJECT_SOURCE_DIR}/tests/fuzz
    -DBINARY_DIR=${PROJECT_BINARY_DIR}/fuzz
    -DCXX=${MACROCON_FUZZ_CXX}
    -DGENERATOR=${CMAKE_GENERATOR}
    -DSECONDS=${MACROCON_FUZZ_SECONDS}
    -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/run_fuzz.cmake)
# Building the clang project takes a few minutes on a loaded 2-core machine.
math(EXPR _fuzz_timeout "${MACROCON_FUZZ_SECONDS} + 1200")
set_tests_properties(scripts.fuzz_library_loader PROPERTIES TIMEOUT ${_fuzz_timeout} LABELS fuzz)
