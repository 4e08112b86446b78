// Authoring a library entry's constraints from files a DCC exports, for `macrocon library build |
// add`: guide and feature polylines (OBJ `l` lines on or near the mesh surface), singularities
// (a table of x, y, z, index) and per-vertex fields (PLY vertex properties or a CSV, one row per
// file vertex). Everything is given in the mesh file's coordinates and numbering; the parts that
// lie outside the entry's patch are left out and counted, so one file can serve many entries.
#pragma once

#include <string>
#include <vector>

#include <cstdint>

#include "io/mesh_io.h"
#include "json/json.h"
#include "macrocon/macrocon.hpp"

namespace mcon::cli {

// A mesh file as read (file numbering) and the same mesh in the SDK.
struct HostMesh {
  io::LoadedMesh file;
  macrocon::Mesh sdk;
};

struct AuthoringSpec {
  std::vector<std::string> guide_files, feature_files;  // OBJ with `l` statements
  std::string singularity_file;                          // table with columns x, y, z, index
  std::string field_file;                                // PLY or CSV, one row per file vertex
  std::vector<std::string> field_specs;                  // "NAME[=COL,COL...][:KIND]"
  double max_snap_distance = -1;                         // mesh units; < 0: 0.1 x the radius

  bool empty() const {
    return guide_files.empty() && feature_files.empty() && singularity_file.empty() && field_file.empty();
  }
};

// What the authoring did, for the command's output.
struct AuthoringReport {
  std::size_t guides = 0, features = 0, singularities = 0;
  std::size_t points = 0;                  // polyline points kept (snapped onto the patch)
  std::size_t points_outside = 0;          // polyline points left out: outside the patch
  std::size_t lines_outside = 0;           // polylines with no two points on the patch
  std::size_t singularities_outside = 0;
  double max_snap_distance = 0, median_snap_distance = 0;  // mesh units, over kept points
  std::vector<std::string> fields;
  tools::Json json() const;
};

// The entry options' text form: --field "NAME[=COL,COL...][:KIND]", KIND one of scalar, vector3,
// tangent, uv, label (default scalar; vector3 and tangent take 3 columns, uv 2). Without '=' the
// column is NAME itself.
struct FieldSpec {
  std::string name;
  std::vector<std::string> columns;
  std::uint32_t kind = MCON_FIELD_SCALAR;  // mcon_field_kind
};
FieldSpec parse_field_spec(const std::string& text);

// The KIND name of --field (and of `library info --json`) of an mcon_field_kind.
const char* field_kind_name(std::uint32_t kind);

// Fills content.polylines (guides, then features) / singularities / fields from the spec's files
// for the patch cut from `host` (its positions in file coordinates). Throws mcon::Error naming the
// file and line (MCON_ERROR_IO for unreadable files, MCON_ERROR_INVALID_ARGUMENT for a point too
// far from the surface, a table of the wrong length, an unknown column).
AuthoringReport author_constraints(const HostMesh& host, const macrocon::Patch& patch, const AuthoringSpec& spec,
                                   macrocon::EntryData& content);

}  // namespace mcon::cli
