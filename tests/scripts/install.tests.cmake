# Install into a scratch prefix and build the out-of-tree consumer against it, once with CMake's
# package config and once with pkg-config.
if(NOT MACROCON_SANITIZE)
  add_test(NAME packaging.install_and_consume
    COMMAND ${CMAKE_COMMAND} -DBUILD=${PROJECT_BINARY_DIR} -DSRC=${PROJECT_SOURCE_DIR}
            -DWORK=${PROJECT_BINARY_DIR}/install-test -DGENERATOR=${CMAKE_GENERATOR}
            -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_install.cmake)
  set_tests_properties(packaging.install_and_consume PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)
endif()

# CPack: a .tar.gz and a .deb with the library, headers, LICENSE and notices, stripped, with
# dbgsym companions; the .deb's Depends computed by dpkg-shlibdeps (check_cpack.cmake).
if(NOT MACROCON_SANITIZE)
  add_test(NAME packaging.cpack
    COMMAND ${CMAKE_COMMAND} -DBUILD=${PROJECT_BINARY_DIR} -DVERSION=${PROJECT_VERSION}
            -DARCH=${CMAKE_SYSTEM_PROCESSOR} -DLIB=$<TARGET_FILE:macrocon>
            "-DSTRIP=${CMAKE_STRIP}" "-DREADELF=${CMAKE_READELF}" "-DNM=${CMAKE_NM}"
            -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cpack.cmake)
  set_tests_properties(packaging.cpack PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)
endif()
