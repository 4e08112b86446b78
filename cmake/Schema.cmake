# The constraint library schema (schema/macrocon_library.fbs) compiled by flatc at build time into
# <build>/generated/macrocon_library_generated.h. Debian's flatc and headers are both 2.0.8 and the
# generated header static_asserts that version (docs/design.md §8). Generated code and the Verifier
# are header-only: targets get the include dirs, never the non-PIC flatbuffers archive.
# Also included by the standalone fuzz project (tests/fuzz/CMakeLists.txt).
set(MACROCON_SCHEMA_FILE ${CMAKE_CURRENT_LIST_DIR}/../schema/macrocon_library.fbs)
get_filename_component(MACROCON_SCHEMA_FILE ${MACROCON_SCHEMA_FILE} ABSOLUTE)
set(MACROCON_GENERATED_DIR ${PROJECT_BINARY_DIR}/generated)

if(NOT TARGET flatbuffers::flatc)
  find_package(FlatBuffers CONFIG REQUIRED)
endif()

# Generates the header once per project and makes `target` depend on it and see it.
# --gen-object-api adds the mutable *T types the tests use to forge hostile files.
function(macrocon_use_library_schema target)
  set(header ${MACROCON_GENERATED_DIR}/macrocon_library_generated.h)
  if(NOT TARGET macrocon_library_schema)
    add_custom_command(OUTPUT ${header}
      COMMAND flatbuffers::flatc --cpp --scoped-enums --gen-object-api -o ${MACROCON_GENERATED_DIR}
              ${MACROCON_SCHEMA_FILE}
      DEPENDS ${MACROCON_SCHEMA_FILE} flatbuffers::flatc
      COMMENT "flatc: schema/macrocon_library.fbs -> generated/macrocon_library_generated.h"
      VERBATIM)
    add_custom_target(macrocon_library_schema DEPENDS ${header})
  endif()
  add_dependencies(${target} macrocon_library_schema)
  get_target_property(fb_include flatbuffers::flatbuffers INTERFACE_INCLUDE_DIRECTORIES)
  target_include_directories(${target} SYSTEM PUBLIC ${MACROCON_GENERATED_DIR} ${fb_include})
endfunction()

if(TARGET macrocon_core)
  macrocon_use_library_schema(macrocon_core)
endif()
