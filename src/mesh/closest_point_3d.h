// Closest points on a triangle mesh in 3D: the exact closest point of one triangle (Ericson,
// Real-Time Collision Detection, §5.1.5: Voronoi regions of the vertices, edges and face), and a
// bounding-volume hierarchy over a mesh's triangles for nearest-surface queries (branch and bound
// on box distance). Used by the similarity ICP (map/similarity_icp.h) and by proximity transfer.
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

// The point of triangle (a, b, c) closest to p, and its barycentric weights (of a, b, c) in
// `barycentric`. Exact for non-degenerate triangles; a degenerate one falls back to its edges.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& barycentric);

struct ClosestSurfacePoint {
  SurfacePoint point;            // triangle and barycentric weights
  Vec3 position = Vec3::Zero();  // the point in 3D
  double squared_distance = 0;
};

class TriangleTree3D {
 public:
  // Keeps a reference to `mesh`, which must outlive the tree and not change.
  explicit TriangleTree3D(const TriMesh& mesh);

  // The closest point of the mesh surface to p. Exact; among equally close triangles the one with
  // the lowest index wins, so the answer does not depend on the tree's layout or query order.
  ClosestSurfacePoint closest(const Vec3& p) const;

 private:
  struct Node {
    Vec3 lo, hi;
    int first = 0, count = 0;  // leaf: triangles order_[first, first + count)
    int left = -1, right = -1;
  };
  int build(int first, int count);
  void search(int node, const Vec3& p, ClosestSurfacePoint& best) const;

  const TriMesh& mesh_;
  std::vector<int> order_;
  std::vector<Vec3> centroids_;
  std::vector<Node> nodes_;
};

}  // namespace mcon
