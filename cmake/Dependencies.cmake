# All dependencies come from Debian packages (docs/design.md §8 has the names that work there).
find_package(Eigen3 3.3 REQUIRED CONFIG)
find_package(OpenMesh REQUIRED CONFIG)
find_package(FlatBuffers CONFIG REQUIRED)
find_package(TBB REQUIRED CONFIG)
find_package(spectra CONFIG QUIET)
find_package(ZLIB REQUIRED)
# JSON for the CLI and the tools (tools/json; header-only, MIT), never in libmacrocon.
find_package(nlohmann_json 3.10 REQUIRED CONFIG)
# Argument parsing and generated help of the CLI and the tools (header-only, BSD-3-Clause).
find_package(CLI11 2.1 REQUIRED CONFIG)
find_package(Threads REQUIRED)
if(MACROCON_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()

# OpenMesh's config exports plain targets with non-SYSTEM include dirs: wrap them.
if(NOT TARGET macrocon_openmesh)
  add_library(macrocon_openmesh INTERFACE)
  get_target_property(_om_inc OpenMeshCore INTERFACE_INCLUDE_DIRECTORIES)
  if(_om_inc)
    target_include_directories(macrocon_openmesh SYSTEM INTERFACE ${_om_inc})
  endif()
  target_link_libraries(macrocon_openmesh INTERFACE OpenMeshCore OpenMeshTools)
endif()
