// The stages of `macrocon embed` and what each hands to the next: the patches (1), the map (2), the
// source constraints transferred and the target's cross field (3, 4), the files (5, 5b) and the
// summary (6). cmd_embed.cpp runs stages 1-4, embed_outputs.cpp writes 5 and 6.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "embed_constraints.h"
#include "io/mesh_io.h"
#include "json/json.h"
#include "macrocon/macrocon.hpp"

namespace mcon::cli {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The checked options of embed that the stages read.
struct EmbedOptions {
  std::string out_dir;
  long samples = 0, iterations = 0, seed = 0;
  std::string orientation;
  std::optional<std::array<double, 3>> source_up, target_up;
  bool up_from_entry = false;  // the source's up is the library entry's own
  bool cut_guides = false;
  double snap = 0;
  long fair_passes = 0;
};

// A patch's normalized triangles and its frame (host = center + radius * p), read once.
struct PatchGeometry {
  TriMesh mesh;  // normalized positions
  Vec3 center = Vec3::Zero();
  double radius = 1;
  mcon_surface_point center_point{MCON_INVALID_INDEX, {0, 0, 0}};

  Vec3 to_host(const Vec3& x) const { return center + radius * x; }
  // A point of the patch in normalized coordinates (its weights applied to its triangle's corners).
  Vec3 position(const mcon_surface_point& q) const {
    const Tri& t = mesh.triangles[q.face];
    return q.barycentric[0] * mesh.positions[t[0]] + q.barycentric[1] * mesh.positions[t[1]] +
           q.barycentric[2] * mesh.positions[t[2]];
  }
};

// 1. Patches.
struct EmbedPatches {
  macrocon::Context context;
  io::LoadedMesh target_mesh, source_mesh;  // the files (an entry: its own vertices, numbered from 0)
  macrocon::Patch target, source;
  PatchGeometry target_geometry, source_geometry;
  std::optional<macrocon::EntryData> entry;  // --entry: the library entry that is the source
};

// 2. The map.
struct EmbedMap {
  std::size_t landmarks = 0;
  macrocon::Map map;
  mcon_map_info info{};
  double map_seconds = 0;
};

// 3. and 4.: the source constraints, transferred, and the target's cross field.
struct TracedLines {
  macrocon::PolylineSet set;
  std::vector<std::uint32_t> sizes, inputs;
  std::vector<std::uint8_t> closed;
  macrocon::SurfacePoints points;  // xyz in target host units
};

struct EmbedTransfer {
  SourceConstraints source;
  std::vector<macrocon::VertexField> fields;  // on the target's vertices
  std::vector<std::uint8_t> outside;
  TracedLines traced;
  macrocon::SurfacePoints singularities;  // on the target (MCON_INVALID_INDEX: outside the map)
  bool center_on_target = false;
  std::vector<double> cross_field;  // per target triangle
  double source_field_seconds = 0, field_seconds = 0, polyline_seconds = 0, cross_field_seconds = 0,
         transfer_seconds = 0;
};

// 5. Files (target mesh units: host = center + radius * p).
struct EmbedFiles {
  std::string ply, obj, features_obj, src_obj, rosy, singularities_csv, summary_path;
  std::size_t traced_points = 0;
};

// 5b. With --cut-guides: the guides cut into the target patch, its fields, cross field and files.
struct EmbedCut {
  macrocon::CutMesh cut;
  mcon_cut_mesh_info info{};
  TriMesh host_units;  // the cut mesh in target host units
  std::vector<std::vector<std::uint32_t>> guides;
  std::vector<std::array<int, 2>> guide_edges;
  std::vector<Vec3> field;
  std::string obj, ply, sharp, rosy, guides_obj;
  double seconds = 0;
};

// 5. The target patch (PLY with the fields, OBJ), the traced and source polylines, the singularities
// and the target's cross field, in `out_dir`.
EmbedFiles write_embed_files(const std::string& out_dir, const EmbedPatches& e, const EmbedTransfer& x);
// 5b. The guides cut into the target patch and its files for QuadWild.
EmbedCut cut_and_write(const EmbedOptions& o, const EmbedPatches& e, const EmbedTransfer& x);

// 6. The summary (summary.json and --json), without guide_turning and the cut.
tools::Json embed_summary(const EmbedOptions& o, const EmbedPatches& e, const EmbedMap& m, const EmbedTransfer& x,
                          const EmbedFiles& f, double patch_seconds, std::chrono::steady_clock::time_point t_start);
// How much the source's guides, their traces and the cut chains (c may be null) zig-zag.
tools::Json turning_summary(const EmbedPatches& e, const EmbedTransfer& x, const EmbedCut* c);
void add_cut_summary(const EmbedCut& cut, tools::Json& summary);
// The short report on stdout without --json.
void print_report(const EmbedOptions& o, const EmbedMap& m, const EmbedTransfer& x, const EmbedFiles& f,
                  const EmbedCut* cut);

}  // namespace mcon::cli
