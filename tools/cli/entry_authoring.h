// Authoring a library entry's constraints from files a DCC exports, for `macrocon library build |
// add`: guide and feature polylines (OBJ `l` lines on or near the mesh surface), singularities
// (a table of x, y, z, index) and per-vertex fields (PLY vertex properties or a CSV, one row per
// file vertex). Everything is given in the mesh file's coordinates and numbering; the parts that
// lie outside the entry's patch are left out and counted, so one file can serve many entries.
#pragma once

#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "json/json.h"
#include "library/constraint_library.h"
#include "patch/geodesic_disk_patch.h"

namespace mcon::cli {

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
  FieldKind kind = FieldKind::scalar;
};
FieldSpec parse_field_spec(const std::string& text);

// The KIND names of --field (and of `library info --json`), one per FieldKind.
inline constexpr FieldKind kFieldKinds[] = {FieldKind::scalar, FieldKind::vector3, FieldKind::tangent_vector,
                                            FieldKind::uv, FieldKind::integer_label};
const char* field_kind_name(FieldKind kind);

// Fills content.guides / features / singularities / fields from the spec's files for the patch
// cut from `host` (its positions in file coordinates). Throws mcon::Error naming the file and line
// (MCON_ERROR_IO for unreadable files, MCON_ERROR_INVALID_ARGUMENT for a point too far from the
// surface, a table of the wrong length, an unknown column).
AuthoringReport author_constraints(const io::LoadedMesh& host, const Patch& patch, const AuthoringSpec& spec,
                                   MacroConstraint& content);

}  // namespace mcon::cli
