// Re-embedding maps (map_patches) through the C ABI: patches from plain arrays, computing a map
// with progress and cancellation, and its queries (info, both correspondences, phi, outside mask).
// Transfers are in capi_transfer.cpp, the cross field in capi_cross_field.cpp.
#include <cmath>
#include <cstddef>
#include <cstring>

#include "capi/capi_library.h"
#include "capi/capi_map_handles.h"
#include "mesh/mesh_topology.h"
#include "patch/patch_from_arrays.h"
#include "map/patch_map.h"

using namespace mcon;
using namespace mcon::capi;

mcon_map_t::~mcon_map_t() {
  release_owned(source);
  release_owned(target);
}

namespace {

// The first published sizes: mcon_map_options ended with progress_user_data and mcon_map_info
// with optimization_seconds. Callers compiled against that header keep working (the appended
// fields keep their defaults, or are not written).
constexpr std::size_t kMapOptionsMinSize = offsetof(mcon_map_options, orientation);
// An older caller's struct has no tail padding the appended field could be read from (docs/api.md).
static_assert(kMapOptionsMinSize % alignof(mcon_map_options) == 0);
constexpr std::size_t kMapInfoMinSize = offsetof(mcon_map_info, alignment_score_unreflected);

mcon_patch_frame default_frame() {
  auto f = zeroed_struct<mcon_patch_frame>();
  f.center_triangle = MCON_INVALID_INDEX;
  f.center_barycentric[0] = f.center_barycentric[1] = f.center_barycentric[2] = 1.0 / 3.0;
  f.scale = 1.0;
  return f;
}

mcon_map_options default_map_options() {
  auto o = zeroed_struct<mcon_map_options>();
  o.seed = 0;
  o.alignment_samples = 10000;
  o.allow_reflection = 1;
  o.max_iterations = 100;
  o.orientation = MCON_MAP_ORIENTATION_AUTOMATIC;
  o.guidance_weight = 1.0;
  o.refine_sigma_factor = 0.5;
  o.world_frame_anchor = PatchMapOptions{}.world_frame_anchor;
  o.coarse_stages = static_cast<std::uint32_t>(SurfaceMapOptions{}.coarse_stages);
  o.coarse_vertices = static_cast<std::uint32_t>(SurfaceMapOptions{}.coarse_vertices);
  return o;
}

std::uint32_t stop_reason_code(StopReason r) {
  switch (r) {
    case StopReason::converged: return MCON_MAP_STOP_CONVERGED;
    case StopReason::stalled: return MCON_MAP_STOP_STALLED;
    case StopReason::iteration_cap: return MCON_MAP_STOP_ITERATION_CAP;
    case StopReason::cancelled: return MCON_MAP_STOP_CANCELLED;
  }
  return MCON_MAP_STOP_ITERATION_CAP;
}

}  // namespace

extern "C" {

mcon_status mcon_patch_frame_init_sized(mcon_patch_frame* frame, size_t struct_size) {
  return init_struct("mcon_patch_frame_init_sized", frame, struct_size, sizeof(mcon_patch_frame), "frame",
                     default_frame());
}

mcon_status mcon_patch_create_from_arrays(mcon_context context, const mcon_mesh_desc* mesh,
                                          const mcon_patch_frame* frame, mcon_patch* out_patch) {
  return guard_create("mcon_patch_create_from_arrays", out_patch, "out_patch", context, "context", [&] {
    require_pointer(mesh, "mesh");
    require_pointer(frame, "frame");
    const auto f = read_options(frame, sizeof(mcon_patch_frame), "mcon_patch_frame", default_frame());
    // The mesh's copy and validation are mcon_mesh_create's (same errors, named after it); a disk
    // has no inside, so its orientation only follows the majority of its triangles.
    std::unique_ptr<mcon_mesh_t> m;
    try {
      m = make_mesh(context, mesh, OrientationRule::majority);
    } catch (const Error& e) {
      throw Error(e.status(), std::string("mcon_mesh_create: ") + e.what());
    }
    TriMesh tri = std::move(m->mesh);
    const OrientationReport orientation = std::move(m->orientation);

    require(f.center_triangle != MCON_INVALID_INDEX, MCON_ERROR_INVALID_ARGUMENT,
            "frame.center_triangle is not set (the center is required)");
    require(f.center_triangle < tri.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
            "frame.center_triangle " + std::to_string(f.center_triangle) + " is out of range (the mesh has " +
                std::to_string(tri.triangles.size()) + " triangles)");
    PatchFrame pf;
    pf.center.triangle = static_cast<int>(f.center_triangle);
    pf.center.barycentric =
        oriented_barycentric(orientation, f.center_triangle,
                             Vec3(f.center_barycentric[0], f.center_barycentric[1], f.center_barycentric[2]));
    pf.origin = Vec3(f.origin[0], f.origin[1], f.origin[2]);
    pf.scale = f.scale;

    auto patch = std::make_unique<mcon_patch_t>();
    patch->patch = run_in_arena(context, [&] { return patch_from_mesh(std::move(tri), pf); });
    const MeshTopology topology = build_topology(patch->patch.mesh);
    patch->boundary_loops = static_cast<std::uint32_t>(topology.boundary_loops.size());
    patch->euler_characteristic = euler_characteristic(patch->patch.mesh, topology);
    patch->host_reoriented_triangles = patch->reoriented_triangles =
        static_cast<std::size_t>(orientation.reoriented_triangles);
    patch->host_inconsistent_components = static_cast<std::uint32_t>(orientation.inconsistent_components);
    retain_owned(context);
    patch->context = context;
    *out_patch = patch.release();
  });
}

mcon_status mcon_map_options_init_sized(mcon_map_options* options, size_t struct_size) {
  return init_struct("mcon_map_options_init_sized", options, struct_size, kMapOptionsMinSize, "options",
                     default_map_options());
}

mcon_status mcon_map_compute(mcon_patch source, mcon_patch target, const mcon_map_options* options,
                             mcon_map* out_map) {
  return guard_create("mcon_map_compute", out_map, "out_map", source, "patch", [&] {
    check_handle(target, "patch");
    const auto o = options ? read_options(options, kMapOptionsMinSize, "mcon_map_options",
                                          default_map_options())
                           : default_map_options();
    require(o.alignment_samples >= 1 && o.alignment_samples <= 100000000u, MCON_ERROR_INVALID_ARGUMENT,
            "alignment_samples must be in [1, 1e8] (got " + std::to_string(o.alignment_samples) + ")");
    require(o.max_iterations >= 1 && o.max_iterations <= 1000000u, MCON_ERROR_INVALID_ARGUMENT,
            "max_iterations must be in [1, 1e6] (got " + std::to_string(o.max_iterations) + ")");
    require(o.orientation <= MCON_MAP_ORIENTATION_REVERSE, MCON_ERROR_INVALID_ARGUMENT,
            "orientation " + std::to_string(o.orientation) +
                " is not an mcon_map_orientation (0 automatic, 1 preserve, 2 reverse)");

    PatchMapOptions po;
    po.map.alignment.samples = static_cast<int>(o.alignment_samples);
    po.map.alignment.seed = o.seed;
    po.map.alignment.allow_reflection = o.allow_reflection != 0;
    po.map.orientation = o.orientation == MCON_MAP_ORIENTATION_PRESERVE  ? MapOrientation::preserve
                         : o.orientation == MCON_MAP_ORIENTATION_REVERSE ? MapOrientation::reverse
                                                                         : MapOrientation::automatic;
    po.map.newton.max_iterations = static_cast<int>(o.max_iterations);
    require(o.coarse_stages <= 8 && o.coarse_vertices >= 100 && o.coarse_vertices <= 100000000u,
            MCON_ERROR_INVALID_ARGUMENT,
            "coarse_stages must be in [0, 8] (0 = off) and coarse_vertices in [100, 1e8] (got " +
                std::to_string(o.coarse_stages) + ", " + std::to_string(o.coarse_vertices) + ")");
    po.map.coarse_stages = static_cast<int>(o.coarse_stages);
    po.map.coarse_vertices = static_cast<int>(o.coarse_vertices);
    require(o.refine_sigma_factor >= 0 && o.refine_sigma_factor <= 1, MCON_ERROR_INVALID_ARGUMENT,
            "refine_sigma_factor must be 0 (no refinement) or in (0, 1] (got " + std::to_string(o.refine_sigma_factor) +
                ")");
    po.map.refine_sigma_factors.clear();
    if (o.refine_sigma_factor > 0) po.map.refine_sigma_factors.push_back(o.refine_sigma_factor);
    require(o.use_world_frame == 0 || o.orientation == MCON_MAP_ORIENTATION_AUTOMATIC, MCON_ERROR_INVALID_ARGUMENT,
            "use_world_frame needs orientation AUTOMATIC (the frame decides the orientation)");
    po.use_world_frame = o.use_world_frame != 0;
    po.world_frame_mirror = o.world_frame_mirror != 0;
    require(std::isfinite(o.world_frame_anchor) && o.world_frame_anchor >= 0, MCON_ERROR_INVALID_ARGUMENT,
            "world_frame_anchor must be finite and >= 0 (0 = no anchor)");
    po.world_frame_anchor = o.world_frame_anchor;
    if (o.use_up_hints != 0) {
      po.source_up = Vec3(o.source_up[0], o.source_up[1], o.source_up[2]);
      po.target_up = Vec3(o.target_up[0], o.target_up[1], o.target_up[2]);
    }
    Eigen::MatrixXd source_guidance, target_guidance;
    if (o.guidance_dimension == 0) {
      require(o.source_guidance == nullptr && o.target_guidance == nullptr, MCON_ERROR_INVALID_ARGUMENT,
              "guidance arrays given with guidance_dimension 0");
    } else {
      require(o.source_guidance != nullptr && o.target_guidance != nullptr, MCON_ERROR_NULL_POINTER,
              "guidance_dimension " + std::to_string(o.guidance_dimension) +
                  " needs both source_guidance and target_guidance");
      require(o.guidance_dimension <= 1024, MCON_ERROR_INVALID_ARGUMENT,
              "guidance_dimension must be in [0, 1024] (got " + std::to_string(o.guidance_dimension) + ")");
      require(std::isfinite(o.guidance_weight) && o.guidance_weight >= 0, MCON_ERROR_INVALID_ARGUMENT,
              "guidance_weight must be finite and >= 0");
      source_guidance = read_rows(o.source_guidance, source->patch.mesh.positions.size(), o.guidance_dimension,
                                  o.source_guidance_stride, "source_guidance");
      target_guidance = read_rows(o.target_guidance, target->patch.mesh.positions.size(), o.guidance_dimension,
                                  o.target_guidance_stride, "target_guidance");
      po.source_guidance = &source_guidance;
      po.target_guidance = &target_guidance;
      po.guidance_weight = o.guidance_weight;
    }
    std::shared_ptr<const std::atomic<bool>> cancelled;
    po.map.progress = make_progress(o.progress, o.progress_user_data, &cancelled);

    auto map = std::make_unique<mcon_map_t>();
    map->map = run_in_arena(source->context, [&] { return map_patches(source->patch, target->patch, po); });
    require(!(cancelled && cancelled->load()), MCON_ERROR_CANCELLED, "cancelled by the progress callback");
    // Local injectivity is the map's promise (thesis §4.1.3): count again before handing it out.
    const int flips = count_phi_flips(source->patch.mesh, map->map.phi, map->map.reflected);
    require(flips == 0, MCON_ERROR_NUMERICAL,
            "the map has " + std::to_string(flips) + " inverted triangles (a locally injective map has none)");
    map->flipped_triangles = 0;
    retain_owned(source);
    map->source = source;
    retain_owned(target);
    map->target = target;
    map->context = source->context;
    *out_map = map.release();
  });
}

mcon_status mcon_map_retain(mcon_map map) {
  return guard("mcon_map_retain", [&] { retain(map, "map"); });
}

mcon_status mcon_map_release(mcon_map map) {
  return guard("mcon_map_release", [&] { release(map, "map"); });
}

mcon_status mcon_map_info_init_sized(mcon_map_info* info, size_t struct_size) {
  return init_struct("mcon_map_info_init_sized", info, struct_size, kMapInfoMinSize, "info",
                     zeroed_struct<mcon_map_info>());
}

mcon_status mcon_map_get_info(mcon_map map, mcon_map_info* info) {
  return guard_object("mcon_map_get_info", map, "map", [&] {
    const SurfaceMap& m = map->map;
    auto v = zeroed_struct<mcon_map_info>();
    v.source_vertex_count = m.source_to_target.size();
    v.target_vertex_count = m.target_to_source.size();
    for (const SurfacePoint& p : m.source_to_target) v.source_vertices_inside += p.triangle >= 0 ? 1 : 0;
    for (const SurfacePoint& p : m.target_to_source) v.target_vertices_inside += p.triangle >= 0 ? 1 : 0;
    v.overlap_ratio = m.overlap_ratio;
    v.matching_score = m.matching_score;
    v.energy_total = m.energy.total;
    v.energy_descriptor = m.energy.value("descriptor");
    v.energy_distortion = m.energy.value("distortion");
    v.energy_area = m.energy.value("area");
    v.energy_injectivity = m.energy.value("injectivity");
    v.iterations = static_cast<std::uint32_t>(m.iterations);
    v.stop_reason = stop_reason_code(m.stop_reason);
    v.reflected = m.reflected ? 1 : 0;
    v.levels = static_cast<std::uint32_t>(m.levels.size());
    v.flipped_triangles = map->flipped_triangles;
    v.alignment_score = m.alignment.score;
    v.alignment_seconds = m.alignment_seconds;
    v.optimization_seconds = m.optimization_seconds;
    v.alignment_score_unreflected = m.alignment.score_unreflected;
    v.alignment_score_reflected = m.alignment.score_reflected;
    v.orientation_compared = m.orientation_compared ? 1 : 0;
    v.level0_energy_unreflected = m.level0_energy_unreflected;
    v.level0_energy_reflected = m.level0_energy_reflected;
    v.frame_decided = m.frame_decided ? 1 : 0;
    v.coarse_vertices = static_cast<std::uint32_t>(m.coarse_vertices);
    v.coarse_stages = static_cast<std::uint32_t>(m.coarse_stages);
    v.coarse_folds = static_cast<std::uint32_t>(m.coarse_folds);
    v.coarse_fallback = m.coarse_fallback ? 1 : 0;
    write_info(info, kMapInfoMinSize, "mcon_map_info", v);
  });
}

mcon_status mcon_map_get_energy_term_count(mcon_map map, uint32_t* out_count) {
  return guard_object("mcon_map_get_energy_term_count", map, "map", [&] {
    require_pointer(out_count, "out_count");
    *out_count = static_cast<std::uint32_t>(map->map.energy.values.size());
  });
}

mcon_status mcon_map_get_energy_term(mcon_map map, uint32_t index, const char** out_name, double* out_value) {
  return guard_object("mcon_map_get_energy_term", map, "map", [&] {
    require(out_name != nullptr || out_value != nullptr, MCON_ERROR_NULL_POINTER, "out_name and out_value are both NULL");
    const std::vector<double>& values = map->map.energy.values;
    require(index < values.size(), MCON_ERROR_INVALID_ARGUMENT,
            "energy term " + std::to_string(index) + " does not exist (the map has " + std::to_string(values.size()) +
                " terms: see mcon_map_get_energy_term_count)");
    if (out_name) *out_name = map_energy_terms()[index].name;
    if (out_value) *out_value = values[index];
  });
}

mcon_status mcon_map_get_correspondences(mcon_map map, mcon_map_direction direction, int32_t* out_triangle,
                                         double* out_barycentric, size_t capacity) {
  return guard_object("mcon_map_get_correspondences", map, "map", [&] {
    const std::int32_t d = enum_bits(direction);
    require(d == MCON_MAP_SOURCE_TO_TARGET || d == MCON_MAP_TARGET_TO_SOURCE, MCON_ERROR_INVALID_ARGUMENT,
            "direction " + std::to_string(d) + " is not an mcon_map_direction");
    const auto& points = d == MCON_MAP_SOURCE_TO_TARGET ? map->map.source_to_target : map->map.target_to_source;
    if (out_triangle == nullptr && out_barycentric == nullptr) return;  // nothing asked for
    require_capacity(capacity, points.size(), "correspondences (capacity in vertices)");
    for (std::size_t v = 0; v < points.size(); ++v) {
      const bool inside = points[v].triangle >= 0;
      if (out_triangle) out_triangle[v] = inside ? points[v].triangle : -1;
      if (out_barycentric)
        for (int k = 0; k < 3; ++k) out_barycentric[3 * v + k] = inside ? points[v].barycentric[k] : 0.0;
    }
  });
}

mcon_status mcon_map_get_phi(mcon_map map, double* out_xy, size_t capacity) {
  return guard_object("mcon_map_get_phi", map, "map", [&] {
    write_rows<2>(map->map.phi, out_xy, capacity, "out_xy", "out_xy (capacity in doubles)");
  });
}

mcon_status mcon_map_get_outside_mask(mcon_map map, uint8_t* out_mask, size_t capacity) {
  return guard_object("mcon_map_get_outside_mask", map, "map", [&] {
    require_pointer(out_mask, "out_mask");
    const auto& points = map->map.target_to_source;
    require_capacity(capacity, points.size(), "out_mask (capacity in vertices)");
    for (std::size_t w = 0; w < points.size(); ++w) out_mask[w] = points[w].triangle < 0 ? 1 : 0;
  });
}

}  // extern "C"
