# C# binding: compiled with Debian's mcs, run with mono (self-checking: "N passed, N failed").
# Not in the sanitizer build (an ASan library cannot be loaded into an uninstrumented mono).
find_program(MACROCON_MCS mcs)
find_program(MACROCON_MONO mono)
if(NOT MACROCON_SANITIZE AND MACROCON_MCS AND MACROCON_MONO)
  set(cs_dir ${PROJECT_BINARY_DIR}/csharp)
  add_custom_command(OUTPUT ${cs_dir}/Macrocon.dll ${cs_dir}/MacroconTests.exe
    COMMAND ${CMAKE_COMMAND} -E make_directory ${cs_dir}
    COMMAND ${MACROCON_MCS} -langversion:7.2 -unsafe -warnaserror -target:library
            -out:${cs_dir}/Macrocon.dll ${PROJECT_SOURCE_DIR}/bindings/csharp/Macrocon.cs
    COMMAND ${MACROCON_MCS} -langversion:7.2 -warnaserror -r:${cs_dir}/Macrocon.dll -out:${cs_dir}/MacroconTests.exe
            ${PROJECT_SOURCE_DIR}/bindings/csharp/tests/MacroconTests.cs
    DEPENDS ${PROJECT_SOURCE_DIR}/bindings/csharp/Macrocon.cs ${PROJECT_SOURCE_DIR}/bindings/csharp/tests/MacroconTests.cs
    COMMENT "Building the C# binding with mcs")
  add_custom_target(macrocon_csharp ALL DEPENDS ${cs_dir}/MacroconTests.exe)
  add_test(NAME csharp.tests COMMAND ${MACROCON_MONO} ${cs_dir}/MacroconTests.exe WORKING_DIRECTORY ${cs_dir})
  set_tests_properties(csharp.tests PROPERTIES
    ENVIRONMENT "LD_LIBRARY_PATH=$<TARGET_FILE_DIR:macrocon>" TIMEOUT 900)
elseif(NOT MACROCON_SANITIZE)
  message(WARNING "mcs/mono not found: the C# binding is not built or tested (install mono-mcs mono-runtime)")
endif()
