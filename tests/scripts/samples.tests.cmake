# The vendor samples (samples/), each built and run on the bundled MakeHuman body against the
# starter library, and their output checked (samples/check_transfer_output.py):
#   samples.c_transfer_fields     plain C against the C API (samples/c)
#   samples.cpp_transfer_guides   the C++ wrapper, guides and .rosy (samples/cpp)
#   samples.python_transfer       the Python binding (samples/python)
#   samples.csharp_transfer       the C# binding under Mono (samples/csharp)
#   samples.blender_headless      the Blender script, registered only if blender is found
# The region is not one the library was built from (another radius), so the map is not trivial.
set(MACROCON_SAMPLE_BODY ${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz)
set(MACROCON_SAMPLE_OUT ${PROJECT_BINARY_DIR}/samples-out)
set(MACROCON_SAMPLE_REGION 8021 0.55)  # the left eye, radius 0.55 (the library's eye_l has 0.6)
file(MAKE_DIRECTORY ${MACROCON_SAMPLE_OUT})
find_program(MACROCON_SAMPLE_PYTHON python3)

# Runs a sample, then the output checker on the PLY it wrote.
function(macrocon_sample_test name ply)
  add_test(NAME samples.${name} COMMAND ${ARGN})
  set_tests_properties(samples.${name} PROPERTIES TIMEOUT 900 FIXTURES_SETUP sample_${name})
  if(MACROCON_SAMPLE_PYTHON)
    add_test(NAME samples.${name}_output
      COMMAND ${MACROCON_SAMPLE_PYTHON} ${PROJECT_SOURCE_DIR}/samples/check_transfer_output.py ${ply})
    set_tests_properties(samples.${name}_output PROPERTIES FIXTURES_REQUIRED sample_${name})
  endif()
endfunction()

add_executable(sample_transfer_fields ${PROJECT_SOURCE_DIR}/samples/c/transfer_fields.c)
set_target_properties(sample_transfer_fields PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(sample_transfer_fields PRIVATE -Wall -Wextra -pedantic $<$<BOOL:${MACROCON_WERROR}>:-Werror>)
target_link_libraries(sample_transfer_fields PRIVATE macrocon macrocon_sample_mesh)
add_dependencies(sample_transfer_fields macrocon_starter_library)
macrocon_sample_test(c_transfer_fields ${MACROCON_SAMPLE_OUT}/c_transfer_fields.ply
  $<TARGET_FILE:sample_transfer_fields> ${MACROCON_STARTER_LIBRARY} ${MACROCON_SAMPLE_BODY}
  ${MACROCON_SAMPLE_REGION} ${MACROCON_SAMPLE_OUT}/c_transfer_fields.ply)
