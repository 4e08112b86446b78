// Patches: geodesic disks cut out of a host mesh (extract_geodesic_disk) and their arrays.
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "capi/capi_handles.h"
#include "map/similarity_icp.h"
#include "mesh/mesh_topology.h"

using namespace mcon;
using namespace mcon::capi;

mcon_patch_t::~mcon_patch_t() { release_owned(context); }

namespace mcon::capi {

// capi_handles.h: a caller's point on a patch, checked.
SurfacePoint read_point(const mcon_surface_point& p, std::size_t triangle_count, const std::string& what) {
  require(p.face < triangle_count, MCON_ERROR_INVALID_ARGUMENT,
          what + ": face " + std::to_string(p.face) + " is not a triangle of the patch (" +
              std::to_string(triangle_count) + " triangles)");
  SurfacePoint out;
  out.triangle = static_cast<int>(p.face);
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double b = p.barycentric[k];
    require(std::isfinite(b), MCON_ERROR_NON_FINITE, what + ": barycentric[" + std::to_string(k) + "] is not finite");
    require(b >= -1e-9 && b <= 1 + 1e-9, MCON_ERROR_INVALID_ARGUMENT,
            what + ": barycentric[" + std::to_string(k) + "] = " + std::to_string(b) + " is outside [0, 1]");
    out.barycentric[k] = b;
    sum += b;
  }
  require(std::abs(sum - 1) <= 1e-6, MCON_ERROR_INVALID_ARGUMENT,
          what + ": barycentric weights sum to " + std::to_string(sum) + ", not 1");
  return out;
}

}  // namespace mcon::capi

namespace {

mcon_patch_options default_patch_options() {
  auto o = zeroed_struct<mcon_patch_options>();
  o.center_vertex = MCON_INVALID_INDEX;
  o.center_triangle = MCON_INVALID_INDEX;
  o.center_barycentric[0] = o.center_barycentric[1] = o.center_barycentric[2] = 1.0 / 3.0;
  o.radius = 0;  // no sensible default: the caller must choose the scale
  o.flags = MCON_PATCH_FILL_HOLES;
  o.snap_fraction = 0.2;
  return o;
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", x);
  return buf;
}

// The C options -> the core's options, with every field checked against the host.
PatchOptions to_core_options(const mcon_patch_options& o, const TriMesh& host, const OrientationReport& orientation) {
  PatchOptions po;
  if (o.center_vertex != MCON_INVALID_INDEX) {
    require(o.center_vertex < host.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
            "center_vertex " + std::to_string(o.center_vertex) + " is out of range (the host mesh has " +
                std::to_string(host.positions.size()) + " vertices)");
    po.center.vertex = static_cast<int>(o.center_vertex);
  } else {
    require(o.center_triangle != MCON_INVALID_INDEX, MCON_ERROR_INVALID_ARGUMENT,
            "no center: set center_vertex, or center_triangle and center_barycentric");
    require(o.center_triangle < host.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
            "center_triangle " + std::to_string(o.center_triangle) + " is out of range (the host mesh has " +
                std::to_string(host.triangles.size()) + " triangles)");
    const double* b = o.center_barycentric;
    for (int i = 0; i < 3; ++i)
      require(std::isfinite(b[i]), MCON_ERROR_NON_FINITE,
              "center_barycentric[" + std::to_string(i) + "] is not finite (" + number(b[i]) + ")");
    const double sum = b[0] + b[1] + b[2];
    require(b[0] >= 0 && b[1] >= 0 && b[2] >= 0 && std::abs(sum - 1.0) <= 1e-6, MCON_ERROR_INVALID_ARGUMENT,
            "center_barycentric (" + number(b[0]) + ", " + number(b[1]) + ", " + number(b[2]) +
                ") is not a point of the triangle (each >= 0, sum 1)");
    po.center.triangle = static_cast<int>(o.center_triangle);
    // Into the oriented triangle's corner order first, then normalized in that order: the same point
    // of a reversed and a consistent input gives the same weights bit for bit.
    const Vec3 w = oriented_barycentric(orientation, o.center_triangle, Vec3(b[0], b[1], b[2]));
    po.center.barycentric = w / (w[0] + w[1] + w[2]);
  }
  require(std::isfinite(o.radius), MCON_ERROR_NON_FINITE, "radius is not finite (" + number(o.radius) + ")");
  require(o.radius > 0, MCON_ERROR_INVALID_ARGUMENT, "radius must be > 0 (got " + number(o.radius) + ")");
  require((o.flags & ~static_cast<std::uint32_t>(MCON_PATCH_FILL_HOLES | MCON_PATCH_REPAIR_REGION)) == 0,
          MCON_ERROR_INVALID_ARGUMENT,
          "flags " + std::to_string(o.flags) +
              " has bits that are not mcon_patch_flags (MCON_PATCH_FILL_HOLES = 1, MCON_PATCH_REPAIR_REGION = 2)");
  require(std::isfinite(o.snap_fraction), MCON_ERROR_NON_FINITE,
          "snap_fraction is not finite (" + number(o.snap_fraction) + ")");
  require(o.snap_fraction >= 0 && o.snap_fraction <= 0.45, MCON_ERROR_INVALID_ARGUMENT,
          "snap_fraction " + number(o.snap_fraction) + " is outside [0, 0.45]");
  po.radius = o.radius;
  po.fill_holes = (o.flags & MCON_PATCH_FILL_HOLES) != 0;
  po.repair_region = (o.flags & MCON_PATCH_REPAIR_REGION) != 0;
  po.snap_fraction = o.snap_fraction;
  return po;
}

std::uint32_t to_index(int i) { return i < 0 ? MCON_INVALID_INDEX : static_cast<std::uint32_t>(i); }

// The patch info's part of the host's orientation report.
void record_host_orientation(mcon_patch_t& patch, const OrientationReport& host) {
  patch.host_reoriented_triangles = static_cast<std::size_t>(host.reoriented_triangles);
  patch.host_outward_turned_components = static_cast<std::uint32_t>(host.components_turned_outward);
  patch.host_inconsistent_components = static_cast<std::uint32_t>(host.inconsistent_components);
  patch.reoriented_triangles = 0;
  for (int t : patch.patch.host_triangle)
    patch.reoriented_triangles += t >= 0 && static_cast<std::size_t>(t) < host.reoriented.size() && host.reoriented[t];
}

// The first version of mcon_patch_info ends before the orientation fields.
constexpr std::size_t kPatchInfoMinSize = offsetof(mcon_patch_info, host_reoriented_triangles);

}  // namespace

extern "C" {

mcon_status mcon_patch_options_init_sized(mcon_patch_options* options, size_t struct_size) {
  return init_struct("mcon_patch_options_init_sized", options, struct_size, sizeof(mcon_patch_options), "options",
                     default_patch_options());
}

mcon_status mcon_patch_extract(mcon_mesh host, const mcon_patch_options* options, mcon_patch* out_patch) {
  return guard_create("mcon_patch_extract", out_patch, "out_patch", host, "mesh", [&] {
    require_pointer(options, "options");
    const auto o = read_options(options, sizeof(mcon_patch_options), "mcon_patch_options", default_patch_options());
    PatchOptions po = to_core_options(o, host->mesh, host->orientation);
    po.validate_region = host->validated_locally;
    // A host validated whole has nothing to repair; asking for it there is a slip worth naming.
    require(!po.repair_region || host->validated_locally, MCON_ERROR_INVALID_ARGUMENT,
            "MCON_PATCH_REPAIR_REGION needs a host made with MCON_MESH_VALIDATE_LOCALLY (a host validated whole has "
            "no defect to repair)");
    std::shared_ptr<const std::atomic<bool>> cancelled;
    po.progress = make_progress(o.progress, o.progress_user_data, &cancelled);

    auto patch = std::make_unique<mcon_patch_t>();
    patch->patch = run_in_arena(host->context, [&] { return extract_geodesic_disk(host->mesh, po); });
    // Even if the core finished anyway, a "cancel" answer means the call is cancelled.
    require(!(cancelled && cancelled->load()), MCON_ERROR_CANCELLED, "cancelled by the progress callback");

    const MeshTopology topology = build_topology(patch->patch.mesh);
    patch->boundary_loops = static_cast<std::uint32_t>(topology.boundary_loops.size());
    patch->euler_characteristic = euler_characteristic(patch->patch.mesh, topology);
    // The core promises a disk; a patch that is not one must never reach the caller.
    require(patch->boundary_loops == 1 && patch->euler_characteristic == 1, MCON_ERROR_NOT_A_DISK,
            "the extracted patch has " + std::to_string(patch->boundary_loops) +
                " boundary loops and Euler characteristic " + std::to_string(patch->euler_characteristic) +
                " (a disk has 1 and 1)");

    record_host_orientation(*patch, host->orientation);
    retain_owned(host->context);
    patch->context = host->context;
    *out_patch = patch.release();
  });
}

mcon_status mcon_patch_retain(mcon_patch patch) {
  return guard("mcon_patch_retain", [&] { retain(patch, "patch"); });
}

mcon_status mcon_patch_release(mcon_patch patch) {
  return guard("mcon_patch_release", [&] { release(patch, "patch"); });
}

mcon_status mcon_patch_info_init_sized(mcon_patch_info* info, size_t struct_size) {
  return init_struct("mcon_patch_info_init_sized", info, struct_size, kPatchInfoMinSize, "info",
                     zeroed_struct<mcon_patch_info>());
}

mcon_status mcon_patch_get_info(mcon_patch patch, mcon_patch_info* info) {
  return guard_object("mcon_patch_get_info", patch, "patch", [&] {
    const Patch& p = patch->patch;
    auto v = zeroed_struct<mcon_patch_info>();
    v.vertex_count = p.mesh.positions.size();
    v.triangle_count = p.mesh.triangles.size();
    v.filled_triangle_count = static_cast<std::size_t>(p.filled_triangles());
    v.boundary_loops = patch->boundary_loops;
    v.euler_characteristic = patch->euler_characteristic;
    v.radius = p.radius;
    for (int i = 0; i < 3; ++i) {
      v.center[i] = p.center_position[i];
      v.center_barycentric[i] = p.center.barycentric[i];
    }
    v.center_patch_triangle = to_index(p.center.triangle);
    v.max_geodesic_distance = p.max_geodesic_distance;
    v.param_flipped_triangles = static_cast<std::uint32_t>(p.param_flipped_triangles);
    v.host_reoriented_triangles = patch->host_reoriented_triangles;
    v.host_outward_turned_components = patch->host_outward_turned_components;
    v.host_inconsistent_components = patch->host_inconsistent_components;
    v.reoriented_triangles = patch->reoriented_triangles;
    write_info(info, kPatchInfoMinSize, "mcon_patch_info", v);
  });
}

mcon_status mcon_patch_repair_info_init_sized(mcon_patch_repair_info* info, size_t struct_size) {
  return init_struct("mcon_patch_repair_info_init_sized", info, struct_size, sizeof(mcon_patch_repair_info), "info",
                     zeroed_struct<mcon_patch_repair_info>());
}

mcon_status mcon_patch_get_repairs(mcon_patch patch, mcon_patch_repair_info* info) {
  return guard_object("mcon_patch_get_repairs", patch, "patch", [&] {
    const PatchRepairs& r = patch->patch.repairs;
    auto v = zeroed_struct<mcon_patch_repair_info>();
    v.zero_area_triangles_removed = static_cast<std::uint32_t>(r.zero_area_triangles_removed);
    v.triangles_split = static_cast<std::uint32_t>(r.triangles_split);
    v.vertices_merged = static_cast<std::uint32_t>(r.vertices_merged);
    v.pinched_vertices_split = static_cast<std::uint32_t>(r.pinched_vertices_split);
    write_info(info, sizeof(mcon_patch_repair_info), "mcon_patch_repair_info", v);
  });
}

mcon_status mcon_patch_get_positions(mcon_patch patch, double* out_xyz, size_t capacity) {
  return guard_object("mcon_patch_get_positions", patch, "patch", [&] {
    write_rows<3>(patch->patch.mesh.positions, out_xyz, capacity, "out_xyz", "out_xyz (capacity in doubles)");
  });
}

mcon_status mcon_patch_get_triangles(mcon_patch patch, uint32_t* out_indices, size_t capacity) {
  return guard_object("mcon_patch_get_triangles", patch, "patch", [&] {
    write_rows<3>(patch->patch.mesh.triangles, out_indices, capacity, "out_indices",
                  "out_indices (capacity in indices)");
  });
}

mcon_status mcon_patch_get_uv(mcon_patch patch, double* out_uv, size_t capacity) {
  return guard_object("mcon_patch_get_uv", patch, "patch", [&] {
    const auto& uv = patch->patch.uv;
    // An internal invariant (never a caller's mistake), checked before the caller's arguments.
    require(uv.size() == patch->patch.mesh.positions.size(), MCON_ERROR_UNKNOWN,
            "the patch has " + std::to_string(uv.size()) + " uv values for " +
                std::to_string(patch->patch.mesh.positions.size()) + " vertices");
    write_rows<2>(uv, out_uv, capacity, "out_uv", "out_uv (capacity in doubles)");
  });
}

mcon_status mcon_patch_get_host_vertices(mcon_patch patch, uint32_t* out_v0, uint32_t* out_v1, double* out_t,
                                         size_t capacity) {
  return guard_object("mcon_patch_get_host_vertices", patch, "patch", [&] {
    const auto& host = patch->patch.host_vertex;
    if (out_v0 == nullptr && out_v1 == nullptr && out_t == nullptr) return;  // nothing asked for
    require_capacity(capacity, host.size(), "host vertex arrays (capacity in vertices)");
    for (std::size_t v = 0; v < host.size(); ++v) {
      if (out_v0) out_v0[v] = to_index(host[v].v0);
      if (out_v1) out_v1[v] = to_index(host[v].v1);
      if (out_t) out_t[v] = host[v].t;
    }
  });
}

mcon_status mcon_patch_get_host_triangles(mcon_patch patch, uint32_t* out_host_triangle, size_t capacity) {
  return guard_object("mcon_patch_get_host_triangles", patch, "patch", [&] {
    require_pointer(out_host_triangle, "out_host_triangle");
    const auto& host = patch->patch.host_triangle;
    require_capacity(capacity, host.size(), "out_host_triangle (capacity in triangles)");
    for (std::size_t t = 0; t < host.size(); ++t) out_host_triangle[t] = to_index(host[t]);
  });
}

mcon_status mcon_patch_closest_points(mcon_patch patch, const double* xyz, size_t count, uint32_t* out_triangles,
                                      double* out_barycentric, double* out_distances) {
  return guard_object("mcon_patch_closest_points", patch, "patch", [&] {
    const TriangleTree3D& tree = patch->closest_tree.over_made([&] { return host_mesh(patch->patch); });
    write_closest_points(patch->context, tree, xyz, count, out_triangles, out_barycentric, out_distances);
  });
}

}  // extern "C"
