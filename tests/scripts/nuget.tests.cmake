# NuGet package of the C# binding (bindings/csharp/Macrocon.nuspec): lib/netstandard2.0/Macrocon.dll
# and runtimes/linux-x64/native/libmacrocon.so (stripped with CMAKE_STRIP), LICENSE at the root, zipped by
# nuget.pack.cmake (no nuget.exe here).
# Needs the C# build of csharp.tests.cmake (included before this file: the glob is sorted).
if(TARGET macrocon_csharp AND NOT MACROCON_SANITIZE)  # the package ships the Release library
  set(nupkg ${cs_dir}/Macrocon.${PROJECT_VERSION}.nupkg)
  set(nuspec ${PROJECT_SOURCE_DIR}/bindings/csharp/Macrocon.nuspec)
  add_custom_command(OUTPUT ${nupkg}
    COMMAND ${CMAKE_COMMAND} -DNUSPEC=${nuspec} -DDLL=${cs_dir}/Macrocon.dll -DLIB=$<TARGET_FILE:macrocon>
            -DVERSION=${PROJECT_VERSION} -DOUT=${nupkg} "-DSTRIP=${CMAKE_STRIP}"
            -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/nuget.pack.cmake
    DEPENDS ${nuspec} ${cs_dir}/Macrocon.dll macrocon ${CMAKE_CURRENT_SOURCE_DIR}/scripts/nuget.pack.cmake
            ${CMAKE_CURRENT_SOURCE_DIR}/scripts/packaged_library.cmake
            ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/THIRD_PARTY_NOTICES
    COMMENT "Packing ${nupkg}")
  add_custom_target(macrocon_nupkg ALL DEPENDS ${nupkg})
  add_dependencies(macrocon_nupkg macrocon_csharp)
  add_test(NAME nuget.package_layout
    COMMAND ${CMAKE_COMMAND} -DNUPKG=${nupkg} -DDLL=${cs_dir}/Macrocon.dll -DLIB=$<TARGET_FILE:macrocon>
            -DVERSION=${PROJECT_VERSION} -DMONO=${MACROCON_MONO} -DCONSUMER=${cs_dir}/CleanExit.exe
            -DWORK=${PROJECT_BINARY_DIR}/nuget-check "-DSTRIP=${CMAKE_STRIP}" "-DREADELF=${CMAKE_READELF}"
            "-DNM=${CMAKE_NM}" -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/nuget.check.cmake)
  set_tests_properties(nuget.package_layout PROPERTIES TIMEOUT 600)
endif()
