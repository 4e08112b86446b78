// Guides cut into a patch (transfer/guide_cutting.h) and QuadWild's inputs written from the result
// (docs/design.md §14).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>

#include "capi/capi_map_handles.h"
#include "io/mesh_io.h"
#include "library/library_file.h"
#include "transfer/cross_field.h"
#include "transfer/guide_cutting.h"
#include "transfer/host_polylines.h"

using namespace mcon;
using namespace mcon::capi;

struct mcon_cut_mesh_t {
  static constexpr std::uint32_t kMagic = 0x4d43435a;  // "MCCZ"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // the patch's or mesh's (not retained: they hold it)
  mcon_patch patch = nullptr;      // retained; or
  mcon_mesh mesh = nullptr;        // retained (mcon_mesh_cut_guides: the whole host)
  mcon::CutMesh cut;               // in the patch's normalized coordinates, or the mesh's
  // Per chain of cut.guides: its guide set and polyline in that set.
  std::vector<std::array<std::uint32_t, 2>> origins;
  std::uint32_t unplaced_points = 0, split_guides = 0;
  // The guide-aligned cross field, solved on first use and kept: the cut never changes, and both
  // mcon_cut_mesh_compute_cross_field and mcon_cut_mesh_write_quadwild need it.
  std::mutex field_mutex;
  std::unique_ptr<const CrossField> field;
  const TriMesh& input() const { return patch ? patch->patch.mesh : mesh->mesh; }
  ~mcon_cut_mesh_t() {
    release_owned(patch);
    release_owned(mesh);
  }
};

namespace {

// First-version struct sizes (docs/api.md "Growing structs"): fields appended later keep defaults.
constexpr std::size_t kCutOptionsMinSize = offsetof(mcon_guide_cut_options, fair_passes);
// An older caller's struct has no tail padding the appended field could be read from (docs/api.md).
static_assert(kCutOptionsMinSize % alignof(mcon_guide_cut_options) == 0);
constexpr std::size_t kCutInfoMinSize = offsetof(mcon_cut_mesh_info, faired_vertices);

mcon_guide_cut_options default_cut_options() {
  auto o = zeroed_struct<mcon_guide_cut_options>();
  const GuideCutOptions core;
  o.snap_fraction = core.snap_fraction;
  o.simplify_fraction = core.simplify_fraction;
  o.fair_passes = static_cast<std::uint32_t>(core.fair_passes);
  o.fair_max_shift = core.fair_max_shift;
  return o;
}

TriMesh host_units(const mcon_cut_mesh_t& c) {
  TriMesh m = c.cut.mesh;
  if (c.patch)
    for (Vec3& x : m.positions) x = to_host(c.patch->patch, x);
  return m;
}

GuideCutOptions cut_options(const mcon_guide_cut_options* options) {
  // Structs from before fairing (ending at simplify_fraction) get the default fairing.
  const auto o = read_options(options, kCutOptionsMinSize, "mcon_guide_cut_options", default_cut_options());
  require(std::isfinite(o.snap_fraction) && std::isfinite(o.simplify_fraction) && std::isfinite(o.fair_max_shift),
          MCON_ERROR_NON_FINITE, "snap_fraction, simplify_fraction and fair_max_shift must be finite");
  require(o.fair_passes <= 100, MCON_ERROR_INVALID_ARGUMENT,
          "fair_passes is " + std::to_string(o.fair_passes) + "; give 0 (off) to 100");
  GuideCutOptions co;
  co.snap_fraction = o.snap_fraction;
  co.simplify_fraction = o.simplify_fraction;
  co.fair_passes = static_cast<int>(o.fair_passes);
  co.fair_max_shift = o.fair_max_shift;
  return co;
}

// Every set's polylines on the host mesh, one list for one cut (docs/design.md §15).
HostPolylines sets_on_host(const mcon_mesh_t& mesh, const mcon_polyline_set* sets, std::size_t count,
                           std::vector<std::array<std::uint32_t, 2>>& origins) {
  HostPolylines all;
  std::vector<mcon_patch> checked;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string what = "guide_sets[" + std::to_string(i) + "]";
    check_handle(sets[i], what.c_str());
    const mcon_patch patch = sets[i]->patch;
    if (std::find(checked.begin(), checked.end(), patch) == checked.end()) {
      try {
        check_patch_of_host(mesh.mesh, patch->patch);
      } catch (const Error& e) {
        fail(e.status(), what + ": " + e.what() + " (give polylines transferred onto patches extracted from this mesh)");
      }
      checked.push_back(patch);
    }
    HostPolylines h = polylines_on_host(mesh.mesh, patch->patch, sets[i]->polylines);
    for (std::size_t j = 0; j < h.lines.size(); ++j) {
      all.lines.push_back(std::move(h.lines[j]));
      all.closed.push_back(h.closed[j]);
      origins.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(h.origin[j])});
    }
    all.dropped_points += h.dropped_points;
    all.split_polylines += h.split_polylines;
  }
  return all;
}

const CrossField& guide_field(mcon_cut_mesh_t& c) {
  const std::lock_guard<std::mutex> lock(c.field_mutex);
  if (!c.field) {
    const TriMesh& mesh = c.cut.mesh;
    CrossField field = run_in_arena(c.context, [&] {
      return compute_cross_field(mesh, constraints_from_edges(mesh, c.cut.guide_edges));
    });
    align_field_to_edges(mesh, c.cut.guide_edges, field);
    c.field = std::make_unique<const CrossField>(std::move(field));
  }
  return *c.field;
}

// A JSON string literal (quotes, backslashes and control characters escaped).
std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// `<prefix>.quadwild.json`: what belongs together (face count, the OBJ's FNV-1a 64 hash, the
// .sharp's edge count) and QuadWild's command lines, so a mismatched field is caught before
// QuadWild silently reads zeros or crashes (docs/design.md §14).
void write_manifest(const std::string& prefix, const TriMesh& mesh, std::size_t sharp_edges) {
  const std::string obj_bytes = io::read_file_maybe_gz(prefix + ".obj");
  char hash[24];
  std::snprintf(hash, sizeof hash, "%016llx",
                static_cast<unsigned long long>(library_content_checksum(
                    reinterpret_cast<const std::uint8_t*>(obj_bytes.data()), obj_bytes.size(), obj_bytes.size())));
  const std::size_t slash = prefix.find_last_of('/');
  const std::string name = slash == std::string::npos ? prefix : prefix.substr(slash + 1);
  std::string j = "{\n";
  j += "  \"mesh\": " + json_string(name + ".obj") + ",\n";
  j += "  \"rosy\": " + json_string(name + ".rosy") + ",\n";
  j += "  \"sharp\": " + json_string(name + ".sharp") + ",\n";
  j += "  \"faces\": " + std::to_string(mesh.triangles.size()) + ",\n";
  j += "  \"vertices\": " + std::to_string(mesh.positions.size()) + ",\n";
  j += "  \"sharp_edges\": " + std::to_string(sharp_edges) + ",\n";
  j += "  \"mesh_fnv1a64\": \"" + std::string(hash) + "\",\n";
  j += "  \"quadwild_commands\": [\n";
  j += "    " + json_string("quadwild " + name + ".obj 2 " + name + ".rosy " + name + ".sharp <quadwild>/config/prep_config/basic_setup.txt") + ",\n";
  j += "    " + json_string("quad_from_patches " + name + "_rem_p0.obj 123 <quadwild>/config/main_config/flow_noalign_lemon.txt") + "\n";
  j += "  ]\n}\n";
  io::write_file_maybe_gz(prefix + ".quadwild.json", j);
}

// A mesh created with MCON_MESH_VALIDATE_LOCALLY: the whole-host cut reads every triangle.
void validate_whole_host(const TriMesh& mesh) {
  std::vector<int> all_triangles(mesh.triangles.size()), all_vertices(mesh.positions.size());
  std::iota(all_triangles.begin(), all_triangles.end(), 0);
  std::iota(all_vertices.begin(), all_vertices.end(), 0);
  validate_mesh_part(mesh, all_triangles, all_vertices,
                     "(mcon_mesh_cut_guides reads the whole mesh: fix it, or cut the guides into a patch with "
                     "mcon_patch_cut_guides)");
}

}  // namespace

extern "C" {

mcon_status mcon_guide_cut_options_init_sized(mcon_guide_cut_options* options, size_t struct_size) {
  return init_struct("mcon_guide_cut_options_init_sized", options, struct_size, kCutOptionsMinSize, "options",
                     default_cut_options());
}

mcon_status mcon_cut_mesh_info_init_sized(mcon_cut_mesh_info* info, size_t struct_size) {
  return init_struct("mcon_cut_mesh_info_init_sized", info, struct_size, kCutInfoMinSize, "info",
                     zeroed_struct<mcon_cut_mesh_info>());
}

mcon_status mcon_patch_cut_guides(mcon_patch patch, mcon_polyline_set guides, const mcon_guide_cut_options* options,
                                  mcon_cut_mesh* out_cut) {
  return guard_create("mcon_patch_cut_guides", out_cut, "out_cut", patch, "patch", [&] {
    check_handle(guides, "polyline set");
    require(guides->patch == patch, MCON_ERROR_INVALID_ARGUMENT,
            "the guides lie on another patch (use polylines transferred onto this patch)");
    const GuideCutOptions co = cut_options(options);
    std::vector<std::vector<SurfacePoint>> lines;
    std::vector<bool> closed;
    for (const TracedPolyline& p : guides->polylines) {
      lines.push_back(p.points);
      closed.push_back(p.closed);
    }
    auto cut = std::make_unique<mcon_cut_mesh_t>();
    cut->cut = run_in_arena(patch->context, [&] { return cut_guides_into_mesh(patch->patch.mesh, lines, closed, co); });
    for (std::size_t i = 0; i < lines.size(); ++i) cut->origins.push_back({0u, static_cast<std::uint32_t>(i)});
    retain_owned(patch);
    cut->patch = patch;
    cut->context = patch->context;
    *out_cut = cut.release();
  });
}

mcon_status mcon_mesh_cut_guides(mcon_mesh mesh, const mcon_polyline_set* guide_sets, size_t set_count,
                                 const mcon_guide_cut_options* options, mcon_cut_mesh* out_cut) {
  return guard_create("mcon_mesh_cut_guides", out_cut, "out_cut", mesh, "mesh", [&] {
    require(set_count == 0 || guide_sets != nullptr, MCON_ERROR_INVALID_ARGUMENT,
            "guide_sets is NULL with set_count " + std::to_string(set_count));
    const GuideCutOptions co = cut_options(options);
    if (mesh->validated_locally) validate_whole_host(mesh->mesh);
    auto cut = std::make_unique<mcon_cut_mesh_t>();
    const HostPolylines lines = sets_on_host(*mesh, guide_sets, set_count, cut->origins);
    cut->cut = run_in_arena(mesh->context, [&] { return cut_guides_into_mesh(mesh->mesh, lines.lines, lines.closed, co); });
    cut->unplaced_points = static_cast<std::uint32_t>(lines.dropped_points);
    cut->split_guides = static_cast<std::uint32_t>(lines.split_polylines);
    retain_owned(mesh);
    cut->mesh = mesh;
    cut->context = mesh->context;
    *out_cut = cut.release();
  });
}

mcon_status mcon_cut_mesh_retain(mcon_cut_mesh cut) {
  return guard("mcon_cut_mesh_retain", [&] { retain(cut, "cut mesh"); });
}

mcon_status mcon_cut_mesh_release(mcon_cut_mesh cut) {
  return guard("mcon_cut_mesh_release", [&] { release(cut, "cut mesh"); });
}

mcon_status mcon_cut_mesh_get_info(mcon_cut_mesh cut, mcon_cut_mesh_info* info) {
  return guard_object("mcon_cut_mesh_get_info", cut, "cut mesh", [&] {
    const CutMesh& c = cut->cut;
    auto v = zeroed_struct<mcon_cut_mesh_info>();
    v.vertex_count = c.mesh.positions.size();
    v.triangle_count = c.mesh.triangles.size();
    v.guide_count = c.guides.size();
    for (const auto& g : c.guides) v.guide_vertex_count += g.size();
    v.guide_edge_count = c.guide_edges.size();
    v.cut_triangle_count = static_cast<std::size_t>(c.input_triangles_cut);
    v.min_angle_created = c.min_angle_created;
    v.min_angle_of_cut_input = c.min_angle_of_cut_input;
    v.snapped_to_vertices = static_cast<std::uint32_t>(c.snapped_to_vertices);
    v.merged_crossings = static_cast<std::uint32_t>(c.merged_crossings);
    v.dropped_points = static_cast<std::uint32_t>(c.dropped_points);
    v.shortcuts = static_cast<std::uint32_t>(c.shortcuts);
    v.moved_vertices = static_cast<std::uint32_t>(c.moved_vertices);
    v.unplaced_points = cut->unplaced_points;
    v.split_guides = cut->split_guides;
    v.faired_vertices = static_cast<std::uint32_t>(c.faired_vertices);
    write_info(info, kCutInfoMinSize, "mcon_cut_mesh_info", v);
  });
}

mcon_status mcon_cut_mesh_get_positions(mcon_cut_mesh cut, double* out_xyz, size_t capacity) {
  return guard_object("mcon_cut_mesh_get_positions", cut, "cut mesh", [&] {
    write_rows<3>(host_units(*cut).positions, out_xyz, capacity, "out_xyz", "out_xyz (capacity in doubles)");
  });
}

mcon_status mcon_cut_mesh_get_triangles(mcon_cut_mesh cut, uint32_t* out_indices, size_t capacity) {
  return guard_object("mcon_cut_mesh_get_triangles", cut, "cut mesh", [&] {
    write_rows<3>(cut->cut.mesh.triangles, out_indices, capacity, "out_indices", "out_indices (capacity in indices)");
  });
}

mcon_status mcon_cut_mesh_get_host_points(mcon_cut_mesh cut, uint32_t* out_patch_triangles, double* out_barycentric,
                                          size_t capacity) {
  return guard_object("mcon_cut_mesh_get_host_points", cut, "cut mesh", [&] {
    if (out_patch_triangles == nullptr && out_barycentric == nullptr) return;
    const auto& host = cut->cut.host;
    require_capacity(capacity, host.size(), "host point arrays (capacity in vertices)");
    for (std::size_t v = 0; v < host.size(); ++v) {
      if (out_patch_triangles) out_patch_triangles[v] = static_cast<uint32_t>(host[v].triangle);
      if (out_barycentric)
        for (int k = 0; k < 3; ++k) out_barycentric[3 * v + k] = host[v].barycentric[k];
    }
  });
}

mcon_status mcon_cut_mesh_get_guide_edges(mcon_cut_mesh cut, uint32_t* out_edges, size_t capacity) {
  return guard_object("mcon_cut_mesh_get_guide_edges", cut, "cut mesh", [&] {
    write_rows<2>(cut->cut.guide_edges, out_edges, capacity, "out_edges", "out_edges (capacity in indices)");
  });
}

mcon_status mcon_cut_mesh_get_guides(mcon_cut_mesh cut, uint32_t* out_sizes, size_t size_capacity,
                                     uint32_t* out_vertices, size_t vertex_capacity) {
  return guard_object("mcon_cut_mesh_get_guides", cut, "cut mesh", [&] {
    const auto& guides = cut->cut.guides;
    if (out_sizes) {
      require_capacity(size_capacity, guides.size(), "out_sizes (capacity in guides)");
      for (std::size_t g = 0; g < guides.size(); ++g) out_sizes[g] = static_cast<uint32_t>(guides[g].size());
    }
    if (out_vertices) {
      std::size_t total = 0;
      for (const auto& g : guides) total += g.size();
      require_capacity(vertex_capacity, total, "out_vertices (capacity in vertices)");
      std::size_t i = 0;
      for (const auto& g : guides)
        for (int v : g) out_vertices[i++] = static_cast<uint32_t>(v);
    }
  });
}

mcon_status mcon_cut_mesh_get_guide_origins(mcon_cut_mesh cut, uint32_t* out_sets, uint32_t* out_polylines,
                                            size_t capacity) {
  return guard_object("mcon_cut_mesh_get_guide_origins", cut, "cut mesh", [&] {
    if (out_sets == nullptr && out_polylines == nullptr) return;
    require_capacity(capacity, cut->origins.size(), "origin arrays (capacity in guides)");
    for (std::size_t g = 0; g < cut->origins.size(); ++g) {
      if (out_sets) out_sets[g] = cut->origins[g][0];
      if (out_polylines) out_polylines[g] = cut->origins[g][1];
    }
  });
}

mcon_status mcon_cut_mesh_carry_field(mcon_cut_mesh cut, uint32_t dimension, const double* patch_values,
                                      size_t value_count, double* out_values, size_t capacity) {
  return guard_object("mcon_cut_mesh_carry_field", cut, "cut mesh", [&] {
    require(dimension >= 1 && dimension <= 65536u, MCON_ERROR_INVALID_ARGUMENT,
            "dimension must be in [1, 65536] (got " + std::to_string(dimension) + ")");
    require_pointer(patch_values, "patch_values");
    require_pointer(out_values, "out_values");
    const TriMesh& patch_mesh = cut->input();
    const std::size_t n = patch_mesh.positions.size();
    require(value_count == n * dimension, MCON_ERROR_INVALID_ARGUMENT,
            "value_count is " + std::to_string(value_count) + ", expected " + (cut->patch ? "patch" : "mesh") +
                " vertices x dimension = " + std::to_string(n * dimension));
    require_capacity(capacity, cut->cut.host.size() * dimension, "out_values (capacity in doubles)");
    Eigen::MatrixXd values(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(dimension));
    for (std::size_t i = 0; i < value_count; ++i) {
      require(std::isfinite(patch_values[i]), MCON_ERROR_NON_FINITE,
              "patch_values[" + std::to_string(i) + "] is not finite");
      values(static_cast<Eigen::Index>(i / dimension), static_cast<Eigen::Index>(i % dimension)) = patch_values[i];
    }
    const Eigen::MatrixXd out = carry_vertex_values(cut->cut, patch_mesh, values);
    for (Eigen::Index v = 0; v < out.rows(); ++v)
      for (Eigen::Index k = 0; k < out.cols(); ++k) out_values[static_cast<std::size_t>(v) * dimension + k] = out(v, k);
  });
}

mcon_status mcon_cut_mesh_compute_cross_field(mcon_cut_mesh cut, double* out_directions, size_t capacity) {
  return guard_object("mcon_cut_mesh_compute_cross_field", cut, "cut mesh", [&] {
    require_pointer(out_directions, "out_directions");
    require_capacity(capacity, cut->cut.mesh.triangles.size(), "out_directions (capacity in triangles)");
    const CrossField& field = guide_field(*cut);
    for (std::size_t t = 0; t < field.directions.size(); ++t)
      for (int k = 0; k < 3; ++k) out_directions[3 * t + k] = field.directions[t][k];
  });
}

mcon_status mcon_cut_mesh_write_quadwild(mcon_cut_mesh cut, const char* path_prefix) {
  return guard_object("mcon_cut_mesh_write_quadwild", cut, "cut mesh", [&] {
    require_pointer(path_prefix, "path_prefix");
    const std::string prefix = path_prefix;
    require(!prefix.empty(), MCON_ERROR_INVALID_ARGUMENT, "path_prefix is empty");
    const TriMesh mesh = host_units(*cut);
    const CrossField& field = guide_field(*cut);
    io::write_obj(prefix + ".obj", mesh);
    io::write_rosy(prefix + ".rosy", mesh, field.directions);
    io::write_sharp(prefix + ".sharp", mesh, cut->cut.guide_edges);
    write_manifest(prefix, mesh, cut->cut.guide_edges.size());
  });
}

}  // extern "C"
