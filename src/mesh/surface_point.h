// The one point-on-a-triangle type: a triangle of a mesh and the barycentric weights of its
// corners. Library constraints, patch centers, map correspondences and traced polylines all use it.
#pragma once

#include <string>

#include "mesh/mesh.h"

namespace mcon {

struct SurfacePoint {
  int triangle = -1;                // -1: no point (e.g. outside a map's overlap)
  Vec3 barycentric = Vec3::Zero();  // weights of the triangle's corners in its own order, sum 1

  bool valid() const { return triangle >= 0; }
};

// Validation shared by the core and the C API: triangle in [0, triangle_count), weights finite,
// >= -1e-9, sum 1 within 1e-6. Returns the weights clamped to >= 0 and renormalized; throws
// INVALID_ARGUMENT (NON_FINITE for NaN/inf) naming the point by `what`.
Vec3 checked_barycentric(int triangle, const Vec3& barycentric, int triangle_count, const std::string& what);

// The point's position on `mesh` (its weights applied to its triangle's corners; not checked).
inline Vec3 position_on(const TriMesh& mesh, const SurfacePoint& p) {
  const Tri& t = mesh.triangles[p.triangle];
  return p.barycentric[0] * mesh.positions[t[0]] + p.barycentric[1] * mesh.positions[t[1]] +
         p.barycentric[2] * mesh.positions[t[2]];
}

}  // namespace mcon
