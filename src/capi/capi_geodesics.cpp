// Geodesic distances on a patch (heat method, operators/heat_geodesics.h): from a surface point or
// from a set of vertices, with the operators factored once per patch handle.
#include <cmath>
#include <vector>

#include "capi/capi_handles.h"

using namespace mcon;
using namespace mcon::capi;

namespace {

// Checks the output, runs `distances` (which returns one value per vertex) in the context's arena
// and writes the result only once it is complete and finite.
template <typename Distances>
void write_distances(mcon_patch patch, double* out_distances, std::size_t capacity, const Distances& distances) {
  require_pointer(out_distances, "out_distances");
  const std::size_t n = patch->patch.mesh.positions.size();
  require_capacity(capacity, n, "out_distances (capacity in doubles)");
  const Eigen::VectorXd d =
      run_in_arena(patch->context, [&] { return distances(patch->heat.over(patch->patch.mesh)); });
  for (Eigen::Index v = 0; v < d.size(); ++v)
    require(std::isfinite(d[v]), MCON_ERROR_NUMERICAL,
            "the distance of vertex " + std::to_string(v) + " is not finite");
  for (Eigen::Index v = 0; v < d.size(); ++v) out_distances[v] = d[v];
}

}  // namespace

extern "C" {

mcon_status mcon_patch_compute_distance_from_point(mcon_patch patch, const mcon_surface_point* point,
                                                   double* out_distances, size_t capacity) {
  return guard_object("mcon_patch_compute_distance_from_point", patch, "patch", [&] {
    require_pointer(point, "point");
    const SurfacePoint p = read_point(*point, patch->patch.mesh.triangles.size(), "point");
    write_distances(patch, out_distances, capacity,
                    [&](const HeatGeodesics& heat) { return heat.from_point(p.triangle, p.barycentric); });
  });
}

mcon_status mcon_patch_compute_distance_from_vertices(mcon_patch patch, const uint32_t* vertices, size_t vertex_count,
                                                      double* out_distances, size_t capacity) {
  return guard_object("mcon_patch_compute_distance_from_vertices", patch, "patch", [&] {
    require(vertex_count > 0, MCON_ERROR_INVALID_ARGUMENT, "vertex_count is 0: give at least one source vertex");
    require_pointer(vertices, "vertices");
    const std::size_t n = patch->patch.mesh.positions.size();
    std::vector<int> sources;
    sources.reserve(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
      require(vertices[i] < n, MCON_ERROR_INVALID_ARGUMENT,
              "vertices[" + std::to_string(i) + "] = " + std::to_string(vertices[i]) +
                  " is not a vertex of the patch (" + std::to_string(n) + " vertices)");
      sources.push_back(static_cast<int>(vertices[i]));
    }
    write_distances(patch, out_distances, capacity,
                    [&](const HeatGeodesics& heat) { return heat.from_vertices(sources); });
  });
}

}  // extern "C"
