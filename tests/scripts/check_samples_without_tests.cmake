# Configures the project without the test suite (-DMACROCON_BUILD_TESTS=OFF) and checks that the
# sample binaries are still targets of the build, and that -DMACROCON_BUILD_SAMPLES=OFF removes
# them (issue 17: a vendor builds the samples without the tests).
#   cmake -DSRC=<source> -DWORK=<scratch> -DGENERATOR=<generator> -P check_samples_without_tests.cmake
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)

file(REMOVE_RECURSE ${WORK})
foreach(samples ON OFF)
  set(dir ${WORK}/samples-${samples})
  run_checked(WHAT "configuring with MACROCON_BUILD_TESTS=OFF MACROCON_BUILD_SAMPLES=${samples}"
              COMMAND ${CMAKE_COMMAND} -S ${SRC} -B ${dir} -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release
                      -DMACROCON_BUILD_TESTS=OFF -DMACROCON_BUILD_SAMPLES=${samples})
  run_checked(OUTPUT_VARIABLE targets COMMAND ${CMAKE_COMMAND} --build ${dir} --target help)
  foreach(target sample_transfer_fields sample_transfer_guides)
    string(REGEX MATCH "(^|[\n ])${target}[:\n ]" found "${targets}")
    if(samples AND NOT found)
      message(FATAL_ERROR "-DMACROCON_BUILD_TESTS=OFF: ${target} is not a target of the build")
    elseif(NOT samples AND found)
      message(FATAL_ERROR "-DMACROCON_BUILD_SAMPLES=OFF: ${target} is still a target of the build")
    endif()
  endforeach()
  if(EXISTS ${dir}/CTestTestfile.cmake)
    message(FATAL_ERROR "-DMACROCON_BUILD_TESTS=OFF still registered tests (${dir}/CTestTestfile.cmake)")
  endif()
endforeach()
message(STATUS "the samples are targets without the tests, and only with MACROCON_BUILD_SAMPLES=ON")
