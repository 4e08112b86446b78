# The API reference of the public headers (Doxygen, docs/Doxyfile.in): `cmake --build build
# --target api_reference` writes build/docs/api_reference/html. Without doxygen the target is not
# defined (and docs.api_reference not registered); CI installs it (tools/debian-packages.txt).
find_program(MACROCON_DOXYGEN doxygen)
if(MACROCON_DOXYGEN)
  set(MACROCON_DOXYGEN_OUT ${PROJECT_BINARY_DIR}/docs/api_reference)
  configure_file(${PROJECT_SOURCE_DIR}/docs/Doxyfile.in ${PROJECT_BINARY_DIR}/docs/Doxyfile @ONLY)
  add_custom_target(api_reference
    COMMAND ${CMAKE_COMMAND} -E make_directory ${MACROCON_DOXYGEN_OUT}
    COMMAND ${MACROCON_DOXYGEN} ${PROJECT_BINARY_DIR}/docs/Doxyfile
    COMMENT "API reference (Doxygen) into ${MACROCON_DOXYGEN_OUT}/html"
    VERBATIM)
else()
  message(STATUS "doxygen not found: no api_reference target (apt-get install doxygen)")
endif()
