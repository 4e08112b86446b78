# `cmake --install`: headers, the versioned shared library, a CMake package
# (find_package(macrocon CONFIG) -> macrocon::macrocon) and a pkg-config file; CPack builds a
# .tar.gz and a .deb from the same install tree.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS macrocon EXPORT macrocon-targets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT development
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES include/macrocon/macrocon.h include/macrocon/macrocon.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/macrocon COMPONENT development OPTIONAL)
install(TARGETS macrocon_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(EXPORT macrocon-targets NAMESPACE macrocon::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/macrocon COMPONENT development)
configure_package_config_file(packaging/macrocon-config.cmake.in
  ${PROJECT_BINARY_DIR}/packaging/macrocon-config.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/macrocon)
# Same major version = compatible (the C ABI is stable within a major version).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/packaging/macrocon-config-version.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/packaging/macrocon-config.cmake
  ${PROJECT_BINARY_DIR}/packaging/macrocon-config-version.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/macrocon COMPONENT development)
file(RELATIVE_PATH MACROCON_PC_TO_PREFIX "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
configure_file(packaging/macrocon.pc.in ${PROJECT_BINARY_DIR}/packaging/macrocon.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/packaging/macrocon.pc
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT development)
# The starter constraint library, generated at build time (tools/starter_library); the CLI's
# `macrocon demo` finds it at bin/../share/macrocon/starter.mclb.
install(FILES ${MACROCON_STARTER_LIBRARY} DESTINATION ${CMAKE_INSTALL_DATADIR}/macrocon COMPONENT runtime)
install(FILES README.md CHANGELOG.md samples/data/NOTICE.md
  DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT development)
# The licence (Apache-2.0) and the third-party notices go with the runtime: every install tree and
# package (share/doc/macrocon/), the wheel and the nupkg (build_wheel.py, nuget.pack.cmake).
install(FILES LICENSE THIRD_PARTY_NOTICES DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)

set(CPACK_PACKAGE_NAME macrocon)
set(CPACK_PACKAGE_VENDOR "Macrocon")
set(CPACK_PACKAGE_CONTACT "Macrocon engineering <eng@macrocon.dev>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Retrieval and re-embedding of macro constraints for quad meshing (SDK)")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR "TGZ;DEB")
set(CPACK_PACKAGE_FILE_NAME "macrocon-${PROJECT_VERSION}-Linux-${CMAKE_SYSTEM_PROCESSOR}")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
# Depends computed by dpkg-shlibdeps from the packaged ELF files (libc6, libstdc++6, libgcc-s1,
# libtbb12, zlib1g with the versions the symbols need); the CLI's RUNPATH $ORIGIN/../lib resolves
# libmacrocon inside the package. No hand-written list.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The .deb's ELF files are stripped (objcopy --strip-unneeded) and their debug info goes to
# macrocon-dbgsym_<version>_<arch>.ddeb (usr/lib/debug/.build-id/<id>.debug, with a gnu-debuglink).
set(CPACK_DEBIAN_DEBUGINFO_PACKAGE ON)
# The .tar.gz: per-generator settings (stripped too; its debug info in a separate
# -dbgsym.tar.gz), cmake/CPackOptions.cmake.in.
configure_file(${PROJECT_SOURCE_DIR}/cmake/CPackOptions.cmake.in ${PROJECT_BINARY_DIR}/CPackOptions.cmake @ONLY)
set(CPACK_PROJECT_CONFIG_FILE ${PROJECT_BINARY_DIR}/CPackOptions.cmake)
set(CPACK_DEBIAN_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
include(CPack)
