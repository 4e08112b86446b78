#include "transfer/host_polylines.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace mcon {
namespace {

// The weight of host vertex `v` in `weights` of host triangle `tri`; fails if `v` is no corner.
void add_weight(const Tri& tri, int v, double w, Vec3& weights, int patch_triangle) {
  for (int k = 0; k < 3; ++k)
    if (tri[k] == v) {
      weights[k] += w;
      return;
    }
  fail(MCON_ERROR_INVALID_ARGUMENT, "patch triangle " + std::to_string(patch_triangle) +
                                        " has a corner off its host triangle: the patch was not cut from this mesh");
}

}  // namespace

SurfacePoint patch_point_on_host(const TriMesh& host, const Patch& patch, const SurfacePoint& point) {
  const Vec3 w = checked_barycentric(point.triangle, point.barycentric, patch.mesh.num_triangles(), "guide point");
  require(patch.host_triangle.size() == patch.mesh.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
          "the patch has no host triangles (it was not extracted from a host mesh)");
  const int h = patch.host_triangle[point.triangle];
  if (h < 0) return {};  // a triangle that fills a hole of the host: no host point
  require(h < host.num_triangles(), MCON_ERROR_INVALID_ARGUMENT,
          "patch triangle " + std::to_string(point.triangle) + " lies on host triangle " + std::to_string(h) +
              ", beyond the mesh's " + std::to_string(host.num_triangles()) + ": the patch was not cut from this mesh");
  const Tri& tri = host.triangles[h];
  const Tri& corners = patch.mesh.triangles[point.triangle];
  Vec3 out = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const HostPoint& hp = patch.host_vertex[corners[k]];
    // Products with exact zeros stay exact zeros: a point on a host edge stays on it.
    add_weight(tri, hp.v0, w[k] * (1 - hp.t), out, point.triangle);
    if (hp.t != 0) add_weight(tri, hp.v1, w[k] * hp.t, out, point.triangle);
  }
  return {h, out};
}

HostPolylines polylines_on_host(const TriMesh& host, const Patch& patch, const std::vector<TracedPolyline>& polylines) {
  HostPolylines out;
  for (std::size_t i = 0; i < polylines.size(); ++i) {
    const TracedPolyline& line = polylines[i];
    std::vector<std::vector<SurfacePoint>> pieces(1);
    for (const SurfacePoint& p : line.points) {
      const SurfacePoint q = patch_point_on_host(host, patch, p);
      if (q.valid()) {
        pieces.back().push_back(q);
        continue;
      }
      ++out.dropped_points;
      if (!pieces.back().empty()) pieces.emplace_back();
    }
    if (pieces.back().empty()) pieces.pop_back();
    const bool whole = pieces.size() == 1 && pieces[0].size() == line.points.size();
    if (!whole && !line.points.empty()) ++out.split_polylines;
    for (auto& piece : pieces) {
      if (piece.size() < 2) continue;
      out.lines.push_back(std::move(piece));
      out.closed.push_back(whole && line.closed);
      out.origin.push_back(static_cast<int>(i));
    }
  }
  return out;
}

void check_patch_of_host(const TriMesh& host, const Patch& patch) {
  const int n = patch.mesh.num_vertices();
  require(static_cast<int>(patch.host_vertex.size()) == n, MCON_ERROR_INVALID_ARGUMENT,
          "the patch has no host points (it was made from arrays, not extracted from a host mesh)");
  for (int v = 0; v < n; ++v) {
    const HostPoint& hp = patch.host_vertex[v];
    if (hp.v0 < 0 && hp.v1 < 0) continue;  // the centre of a filled hole
    require(hp.v0 >= 0 && hp.v1 >= 0 && hp.v0 < host.num_vertices() && hp.v1 < host.num_vertices(),
            MCON_ERROR_INVALID_ARGUMENT,
            "patch vertex " + std::to_string(v) + " lies on host vertices beyond the mesh's " +
                std::to_string(host.num_vertices()) + ": the patch was not cut from this mesh");
    const Vec3 x = (1 - hp.t) * host.positions[hp.v0] + hp.t * host.positions[hp.v1];
    const Vec3 y = patch.center_position + patch.radius * patch.mesh.positions[v];
    require((x - y).norm() <= 1e-6 * patch.radius, MCON_ERROR_INVALID_ARGUMENT,
            "patch vertex " + std::to_string(v) + " is " + std::to_string((x - y).norm()) +
                " host units from its host point: the patch was not cut from this mesh");
  }
}

}  // namespace mcon
