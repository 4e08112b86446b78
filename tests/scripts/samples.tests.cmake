# The vendor samples (samples/), each built and run on the bundled MakeHuman body against the
# starter library, and their output checked (samples/check_transfer_output.py):
#   samples.c_transfer_fields     plain C against the C API (samples/c)
#   samples.cpp_transfer_guides   the C++ wrapper, guides and .rosy (samples/cpp)
#   samples.python_transfer       the Python binding (samples/python)
#   samples.csharp_transfer       the C# binding under Mono (samples/csharp)
#   samples.python_dask_library   a library built on a Dask cluster (samples/python), if Dask is found
#   samples.blender_headless      the Blender script, registered only if blender is found
#   samples.blender_author        the add-on's authoring operator, headless (same condition)
#   samples.build_without_tests   the sample binaries are targets with -DMACROCON_BUILD_TESTS=OFF
# The region is not one the library was built from (another radius), so the map is not trivial.
set(MACROCON_SAMPLE_BODY ${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz)
set(MACROCON_SAMPLE_OUT ${PROJECT_BINARY_DIR}/samples-out)
set(MACROCON_SAMPLE_REGION 8021 0.55)  # the left eye, radius 0.55 (the library's eye_l has 0.6)
file(MAKE_DIRECTORY ${MACROCON_SAMPLE_OUT})
# Debian's interpreter (numpy comes from python3-numpy), as for the binding tests.
set(MACROCON_PYTHON /usr/bin/python3 CACHE FILEPATH "Python with numpy and pytest for the binding tests")

# Runs a sample (COMMAND ...), then the output checker on the PLY it wrote (CHECK_ARGS: more
# checker options).
function(macrocon_sample_test name ply)
  cmake_parse_arguments(arg "" "" "COMMAND;CHECK_ARGS" ${ARGN})
  add_test(NAME samples.${name} COMMAND ${arg_COMMAND})
  set_tests_properties(samples.${name} PROPERTIES TIMEOUT 900 FIXTURES_SETUP sample_${name})
  if(MACROCON_PYTHON)
    add_test(NAME samples.${name}_output
      COMMAND ${MACROCON_PYTHON} ${PROJECT_SOURCE_DIR}/samples/check_transfer_output.py ${ply} ${arg_CHECK_ARGS})
    set_tests_properties(samples.${name}_output PROPERTIES FIXTURES_REQUIRED sample_${name})
  endif()
endfunction()

# The binaries come from samples/CMakeLists.txt (MACROCON_BUILD_SAMPLES).
if(NOT TARGET sample_transfer_fields)
  message(STATUS "samples.c_transfer_fields and samples.cpp_transfer_guides NOT registered: "
                 "the samples are off (-DMACROCON_BUILD_SAMPLES=ON builds them)")
else()
  macrocon_sample_test(c_transfer_fields ${MACROCON_SAMPLE_OUT}/c_transfer_fields.ply COMMAND
    $<TARGET_FILE:sample_transfer_fields> ${MACROCON_STARTER_LIBRARY} ${MACROCON_SAMPLE_BODY}
    ${MACROCON_SAMPLE_REGION} ${MACROCON_SAMPLE_OUT}/c_transfer_fields.ply)

  macrocon_sample_test(cpp_transfer_guides ${MACROCON_SAMPLE_OUT}/cpp_transfer.ply COMMAND
    $<TARGET_FILE:sample_transfer_guides> ${MACROCON_STARTER_LIBRARY} ${MACROCON_SAMPLE_BODY}
    ${MACROCON_SAMPLE_REGION} ${MACROCON_SAMPLE_OUT}/cpp_transfer
    CHECK_ARGS --guides ${MACROCON_SAMPLE_OUT}/cpp_transfer_guides.obj
               --rosy ${MACROCON_SAMPLE_OUT}/cpp_transfer_region.rosy --region ${MACROCON_SAMPLE_OUT}/cpp_transfer_region.obj)
endif()

# -DMACROCON_BUILD_TESTS=OFF still gives the sample binaries; MACROCON_BUILD_SAMPLES=OFF drops them.
add_test(NAME samples.build_without_tests
  COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DWORK=${PROJECT_BINARY_DIR}/samples-without-tests
          -DGENERATOR=${CMAKE_GENERATOR} -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_samples_without_tests.cmake)
set_tests_properties(samples.build_without_tests PROPERTIES TIMEOUT 300)

# The bindings load libmacrocon into an uninstrumented interpreter / Mono, which an ASan library
# cannot be: not in the sanitizer build (as the binding tests).
if(NOT MACROCON_SANITIZE)
  macrocon_sample_test(python_transfer ${MACROCON_SAMPLE_OUT}/python_transfer.ply COMMAND
    ${MACROCON_PYTHON} ${PROJECT_SOURCE_DIR}/samples/python/transfer_fields.py ${MACROCON_STARTER_LIBRARY}
    ${MACROCON_SAMPLE_BODY} ${MACROCON_SAMPLE_REGION} ${MACROCON_SAMPLE_OUT}/python_transfer.ply
    --guides ${MACROCON_SAMPLE_OUT}/python_transfer_guides.obj --rosy ${MACROCON_SAMPLE_OUT}/python_transfer.rosy
    CHECK_ARGS --guides ${MACROCON_SAMPLE_OUT}/python_transfer_guides.obj)
  set_tests_properties(samples.python_transfer PROPERTIES
    ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;PYTHONPATH=${PROJECT_SOURCE_DIR}/bindings/python")

  # The Dask sample (samples/python/dask_build_library.py): a library built on 4 LocalCluster worker
  # processes must answer queries as a single-process build does. Registered only if the
  # interpreter imports Dask's `distributed` (Debian's python3-distributed, in
  # tools/debian-packages-extra.txt); otherwise the configuration says that it is not.
  execute_process(COMMAND ${MACROCON_PYTHON} -c "import distributed"
                  RESULT_VARIABLE macrocon_dask_rc OUTPUT_QUIET ERROR_QUIET)
  if(macrocon_dask_rc EQUAL 0)
    add_test(NAME samples.python_dask_library
      COMMAND ${MACROCON_PYTHON} -m pytest -q -s -p no:cacheprovider
              ${PROJECT_SOURCE_DIR}/samples/python/test_dask_build_library.py)
    set_tests_properties(samples.python_dask_library PROPERTIES TIMEOUT 600
      ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;PYTHONPATH=${PROJECT_SOURCE_DIR}/bindings/python")
  else()
    message(STATUS "samples.python_dask_library NOT registered: ${MACROCON_PYTHON} cannot import distributed "
                   "(apt-get install python3-distributed, see tools/debian-packages-extra.txt)")
  endif()

  find_program(MACROCON_SAMPLE_MCS mcs)
  find_program(MACROCON_SAMPLE_MONO mono)
  if(MACROCON_SAMPLE_MCS AND MACROCON_SAMPLE_MONO)
    # The sample compiles with the binding's sources (one assembly), as a plugin might vendor them.
    file(GLOB MACROCON_CSHARP_BINDING_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/bindings/csharp/*.cs)
    set(cs_sample ${PROJECT_BINARY_DIR}/samples-csharp/TransferFields.exe)
    add_custom_command(OUTPUT ${cs_sample}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/samples-csharp
      COMMAND ${MACROCON_SAMPLE_MCS} -langversion:7.2 -unsafe -warnaserror -out:${cs_sample}
              ${MACROCON_CSHARP_BINDING_SOURCES} ${PROJECT_SOURCE_DIR}/samples/csharp/TransferFields.cs
      DEPENDS ${MACROCON_CSHARP_BINDING_SOURCES} ${PROJECT_SOURCE_DIR}/samples/csharp/TransferFields.cs
      COMMENT "Building the C# sample with mcs")
    add_custom_target(macrocon_csharp_sample ALL DEPENDS ${cs_sample})
    macrocon_sample_test(csharp_transfer ${MACROCON_SAMPLE_OUT}/csharp_transfer.ply COMMAND
      ${MACROCON_SAMPLE_MONO} ${cs_sample} ${MACROCON_STARTER_LIBRARY} ${MACROCON_SAMPLE_BODY}
      ${MACROCON_SAMPLE_REGION} ${MACROCON_SAMPLE_OUT}/csharp_transfer.ply)
    set_tests_properties(samples.csharp_transfer PROPERTIES ENVIRONMENT "LD_LIBRARY_PATH=$<TARGET_FILE_DIR:macrocon>")
  endif()

  # Blender (Debian's blender 3.4: Python 3.11 + numpy) headless: registered only if blender is
  # installed at configure time, so the suite has no skipped test either way.
  find_program(MACROCON_BLENDER blender)
  if(MACROCON_BLENDER)
    set(blend ${MACROCON_SAMPLE_OUT}/blender_sample.blend)
    set(blend_json ${MACROCON_SAMPLE_OUT}/blender_sample.json)
    add_test(NAME samples.blender_headless
      COMMAND ${MACROCON_BLENDER} -b --factory-startup --python-exit-code 1
              --python ${PROJECT_SOURCE_DIR}/samples/blender/macrocon_blender.py --
              --library ${MACROCON_STARTER_LIBRARY} --mesh ${MACROCON_SAMPLE_BODY}
              --vertex 8021 --radius 0.55 --out ${blend} --json ${blend_json})
    set_tests_properties(samples.blender_headless PROPERTIES TIMEOUT 900 FIXTURES_SETUP sample_blender
      ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;MACROCON_PYTHON_PATH=${PROJECT_SOURCE_DIR}/bindings/python")
    add_test(NAME samples.blender_headless_output
      COMMAND ${MACROCON_BLENDER} -b ${blend} --factory-startup --python-exit-code 1
              --python ${PROJECT_SOURCE_DIR}/samples/blender/check_blend.py -- ${blend_json})
    set_tests_properties(samples.blender_headless_output PROPERTIES TIMEOUT 300 FIXTURES_REQUIRED sample_blender)
    # The authoring operator headless: selected edges and point attributes into a new library file.
    add_test(NAME samples.blender_author
      COMMAND ${MACROCON_BLENDER} -b --factory-startup --python-exit-code 1
              --python ${PROJECT_SOURCE_DIR}/samples/blender/check_author.py --
              ${MACROCON_SAMPLE_BODY} ${MACROCON_SAMPLE_OUT}/blender_author.mclb)
    set_tests_properties(samples.blender_author PROPERTIES TIMEOUT 600
      ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;MACROCON_PYTHON_PATH=${PROJECT_SOURCE_DIR}/bindings/python")
  else()
    message(STATUS "samples.blender_headless NOT registered: blender was not found "
                   "(apt-get install blender, see tools/debian-packages-extra.txt)")
  endif()
endif()
