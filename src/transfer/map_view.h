// The pieces of a re-embedding map Phi = g^-1 o phi o f (thesis eq. 4.1) that constraint transfer
// reads: both patches (normalized meshes + unit-disk parametrizations f, g), the deformed source
// disk phi, and the barycentric correspondences of both directions. A view, not a copy: the
// transfer modules (field_transfer.h, polyline_transfer.h) take one so that they work the same on
// a SurfaceMap from map_patches and on synthetic maps with a known phi (tests).
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "map/surface_map.h"

namespace mcon {

struct MapView {
  const TriMesh& source;
  const std::vector<Vec2>& source_uv;  // f, one per source vertex
  const TriMesh& target;
  const std::vector<Vec2>& target_uv;  // g, one per target vertex (boundary on the unit circle)
  const std::vector<Vec2>& phi;        // phi(f(v)) per source vertex, in the target disk's plane
  const std::vector<SurfacePoint>& source_to_target;  // per source vertex
  const std::vector<SurfacePoint>& target_to_source;  // per target vertex
};

// Both directions of the correspondence for a given phi, located exactly as compute_surface_map
// does (a point on a shared edge or vertex goes to the triangle where it lies deepest): for every
// source vertex the target triangle containing phi(v) in g's plane, for every target vertex the
// source triangle of the deformed disk phi containing g(w). For tests and for maps built outside
// compute_surface_map. Throws INVALID_ARGUMENT on size mismatches.
struct Correspondences {
  std::vector<SurfacePoint> source_to_target;
  std::vector<SurfacePoint> target_to_source;
};
Correspondences locate_correspondences(const TriMesh& source, const std::vector<Vec2>& phi, const TriMesh& target,
                                       const std::vector<Vec2>& target_uv);

// Checks that the view's arrays have matching sizes and indices in range (INVALID_ARGUMENT).
void check_map_view(const MapView& view);

// Triangles of phi whose orientation disagrees with the map's (inverted or degenerate): with
// `reflected` false a source triangle must keep its positive area in the source uv, with true it
// must have become negative. A valid map has none (the injectivity barrier, thesis eq. 4.12).
int count_phi_flips(const TriMesh& source, const std::vector<Vec2>& phi, bool reflected);

}  // namespace mcon
