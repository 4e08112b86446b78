// A guide-aligned 4-RoSy cross field on a patch (cross_field.h) and its QuadWild `.rosy` file
// (docs/design.md §7: what quad meshers take as orientation input).
#include <cmath>

#include "capi/capi_map_handles.h"
#include "transfer/cross_field.h"
#include "io/mesh_io.h"

using namespace mcon;
using namespace mcon::capi;

namespace {

mcon_cross_field_options default_cross_field_options() {
  auto o = zeroed_struct<mcon_cross_field_options>();
  o.alignment_weight = 10.0;
  o.align_to_boundary = 0;
  o.boundary_weight = 1.0;
  return o;
}

}  // namespace

extern "C" {

mcon_status mcon_cross_field_options_init_sized(mcon_cross_field_options* options, size_t struct_size) {
  return init_struct("mcon_cross_field_options_init_sized", options, struct_size, sizeof(mcon_cross_field_options),
                     "options", default_cross_field_options());
}

mcon_status mcon_patch_compute_cross_field(mcon_patch patch, mcon_polyline_set guides,
                                           const mcon_cross_field_options* options, double* out_directions,
                                           double* out_confidence, size_t capacity) {
  return guard_object("mcon_patch_compute_cross_field", patch, "patch", [&] {
    const auto o = options ? read_options(options, sizeof(mcon_cross_field_options), "mcon_cross_field_options",
                                          default_cross_field_options())
                           : default_cross_field_options();
    require(std::isfinite(o.alignment_weight) && std::isfinite(o.boundary_weight), MCON_ERROR_NON_FINITE,
            "cross field weights must be finite");
    require(o.alignment_weight > 0, MCON_ERROR_INVALID_ARGUMENT, "alignment_weight must be > 0");
    require(o.boundary_weight > 0, MCON_ERROR_INVALID_ARGUMENT, "boundary_weight must be > 0");
    require_pointer(out_directions, "out_directions");
    const TriMesh& mesh = patch->patch.mesh;
    require_capacity(capacity, mesh.triangles.size(), "out_directions (capacity in triangles)");

    std::vector<std::vector<SurfacePoint>> lines;
    if (guides != nullptr) {
      check_handle(guides, "polyline set");
      require(guides->patch == patch, MCON_ERROR_INVALID_ARGUMENT,
              "the guides lie on another patch (use polylines transferred onto this patch)");
      for (const TracedPolyline& p : guides->polylines) {
        std::vector<SurfacePoint> line;
        for (const SurfacePoint& q : p.points) line.push_back({q.triangle, q.barycentric});
        if (p.closed && !line.empty()) line.push_back(line.front());
        lines.push_back(std::move(line));
      }
    }
    CrossFieldOptions co;
    co.alignment_weight = o.alignment_weight;
    co.align_to_boundary = o.align_to_boundary != 0;
    co.boundary_weight = o.boundary_weight;
    const CrossField field = run_in_arena(patch->context, [&] {
      return compute_cross_field(mesh, constraints_from_polylines(mesh, lines), co);
    });
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) out_directions[3 * t + k] = field.directions[t][k];
      if (out_confidence) out_confidence[t] = field.confidence[t];
    }
  });
}

mcon_status mcon_patch_write_rosy(mcon_patch patch, const double* directions, size_t triangle_count,
                                  const char* path) {
  return guard_object("mcon_patch_write_rosy", patch, "patch", [&] {
    require_pointer(directions, "directions");
    require_pointer(path, "path");
    require(path[0] != '\0', MCON_ERROR_INVALID_ARGUMENT, "path is empty");
    const TriMesh& mesh = patch->patch.mesh;
    require(triangle_count == mesh.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
            "triangle_count is " + std::to_string(triangle_count) + ", the patch has " +
                std::to_string(mesh.triangles.size()) + " triangles");
    std::vector<Vec3> d(triangle_count);
    for (std::size_t t = 0; t < triangle_count; ++t) {
      d[t] = Vec3(directions[3 * t], directions[3 * t + 1], directions[3 * t + 2]);
      require(d[t].allFinite(), MCON_ERROR_NON_FINITE, "direction " + std::to_string(t) + " is not finite");
    }
    io::write_rosy(path, mesh, d);
  });
}

}  // extern "C"
