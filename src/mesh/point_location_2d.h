// Point location among planar triangles: which triangle of a 2D triangulation (a disk
// parametrization, or a deformed one) contains a point, and where (barycentric coordinates).
// A quadtree over the triangles' bounding boxes (cells split while they hold more than 8
// triangles) descends to one leaf per query however unevenly the triangles are spread; that
// matters because disk parametrizations of hands or feet squeeze whole fingers into tiny regions,
// where the thesis' uniform grid (§4.2) ends up with hundreds of triangles in a cell. (A bounding
// volume hierarchy was 4-5x slower per query on even meshes: it must backtrack.) Points outside
// the triangulation find their nearest triangle among those on its boundary.
#pragma once

#include <array>
#include <vector>

#include "mesh/mesh.h"

namespace mcon {

struct PointLocation {
  int triangle = -1;                // -1: no triangle found
  Vec3 barycentric = Vec3::Zero();  // weights of the triangle's corners, >= 0, summing to 1
  double distance = 0;              // 0 inside; the distance to the triangle otherwise
};

// Barycentric coordinates of p with respect to (a, b, c), unclamped (they sum to 1).
// A degenerate triangle gives (1, 0, 0).
Vec3 barycentric_2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c);

class TriangleLocator2D {
 public:
  TriangleLocator2D() = default;
  // Copies the points and triangles. Triangles may have either orientation. Throws EMPTY_MESH,
  // INDEX_OUT_OF_RANGE, NON_FINITE.
  TriangleLocator2D(const std::vector<Vec2>& points, const std::vector<Tri>& triangles);

  // The triangle containing p. Points on shared edges or vertices (within 1e-10 in barycentric
  // terms) are inside; among several hits the one where p lies deepest (largest smallest
  // barycentric) wins, then the lowest index, so the answer does not depend on the traversal.
  PointLocation locate(const Vec2& p) const;
  // The same answer as locate(p), found faster when p lies near triangle `hint` (the triangle
  // of a nearby earlier query): on an embedding (is_embedding()) a walk of a few steps from the
  // hint towards p stops in the triangle that contains p with a margin, the only one that can;
  // otherwise, or for hint -1, the full search runs.
  PointLocation locate(const Vec2& p, int hint) const;

  // Like locate, but if no triangle contains p, the triangle nearest to p within max_distance
  // (barycentric coordinates of the nearest point, distance > 0; ties: lowest index); triangle
  // -1 if none.
  PointLocation locate_nearest(const Vec2& p, double max_distance) const;
  PointLocation locate_nearest(const Vec2& p, double max_distance, int hint) const;

  // The triangles cover their union once: all have the same orientation and area != 0, every
  // edge has at most two triangles that run it in opposite directions, and the unpaired edges
  // form one loop that does not cross itself. (Then the number of triangles over a point is the
  // rim's winding number, 1 or 0.)
  bool is_embedding() const { return !neighbors_.empty(); }

  int num_triangles() const { return static_cast<int>(triangles_.size()); }
  const std::vector<Vec2>& points() const { return points_; }
  const std::vector<Tri>& triangles() const { return triangles_; }

 private:
  struct Node {
    Vec2 center;        // split point of an inner node
    int children = -1;  // inner: index of the first of 4 consecutive children (x-major: 0 = lower
                        // left, 1 = lower right, 2 = upper left, 3 = upper right); leaf: -1
    int first = 0;      // leaf: range in items_
    int count = 0;
    int full_first = 0;  // any node: triangles that cover the whole cell (range in full_items_)
    int full_count = 0;
  };
  void build(int self, const Vec2& lo, const Vec2& hi, std::vector<int> tris, int depth);
  int cell_relation(int triangle, const Vec2& lo, const Vec2& hi) const;

  std::vector<Vec2> points_;
  std::vector<Tri> triangles_;
  std::vector<Vec2> box_lo_, box_hi_;  // per triangle
  std::vector<Node> nodes_;
  Vec2 root_lo_ = Vec2::Zero(), root_hi_ = Vec2::Zero();
  std::vector<int> items_;             // triangle indices of the leaves, ascending per leaf
  std::vector<int> full_items_;        // triangles kept at inner nodes (Node::full_first)
  std::vector<int> boundary_;          // triangles with an edge used by no other triangle
  // Only on an embedding: per triangle, the triangle across the edge opposite each corner
  // (-1 on the boundary); empty otherwise.
  std::vector<std::array<int, 3>> neighbors_;
  PointLocation nearest_on_boundary(const Vec2& p, double max_distance) const;
  void detect_embedding(const std::vector<std::array<long long, 3>>& sorted_edges);
};

}  // namespace mcon
