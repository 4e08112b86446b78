#include "mesh/closest_point_3d.h"

#include <algorithm>
#include <limits>

#include "base/error.h"

namespace mcon {

namespace {

// Leaves hold at most this many triangles.
constexpr int kLeafSize = 8;

double box_squared_distance(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const Vec3 d = (lo - p).cwiseMax(p - hi).cwiseMax(Vec3::Zero());
  return d.squaredNorm();
}

// Closest point on segment (a, b) to p, as the weight t of b.
double segment_parameter(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  return len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
}

}  // namespace

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& barycentric) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  if (ab.cross(ac).squaredNorm() <= 1e-30 * std::max(ab.squaredNorm() * ac.squaredNorm(), 1e-300)) {
    // Degenerate: the best of the three edges.
    const Vec3* corners[3] = {&a, &b, &c};
    double best = std::numeric_limits<double>::infinity();
    Vec3 out = a;
    for (int e = 0; e < 3; ++e) {
      const Vec3& u = *corners[e];
      const Vec3& v = *corners[(e + 1) % 3];
      const double t = segment_parameter(p, u, v);
      const Vec3 q = (1 - t) * u + t * v;
      if ((q - p).squaredNorm() < best) {
        best = (q - p).squaredNorm();
        out = q;
        barycentric = Vec3::Zero();
        barycentric[e] = 1 - t;
        barycentric[(e + 1) % 3] = t;
      }
    }
    return out;
  }
  // Ericson §5.1.5: test the Voronoi regions of a, b, c, the three edges, then the face.
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return barycentric = Vec3(1, 0, 0), a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return barycentric = Vec3(0, 1, 0), b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return barycentric = Vec3(1 - v, v, 0), a + v * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return barycentric = Vec3(0, 0, 1), c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return barycentric = Vec3(1 - w, 0, w), a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return barycentric = Vec3(0, 1 - w, w), b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  barycentric = Vec3(1 - v - w, v, w);
  return a + v * ab + w * ac;
}

TriangleTree3D::TriangleTree3D(const TriMesh& mesh) : mesh_(mesh) {
  require(mesh.num_triangles() > 0, MCON_ERROR_EMPTY_MESH, "closest point: the mesh has no triangles");
  order_.resize(mesh.triangles.size());
  centroids_.resize(mesh.triangles.size());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    order_[t] = t;
    const Tri& tri = mesh.triangles[t];
    centroids_[t] = (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0;
  }
  nodes_.reserve(2 * mesh.triangles.size() / kLeafSize + 2);
  build(0, mesh.num_triangles());
}

// Median split along the box's longest axis (ties by triangle index, so the layout is fixed).
int TriangleTree3D::build(int first, int count) {
  Node node;
  node.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  node.hi = -node.lo;
  for (int k = first; k < first + count; ++k)
    for (const int v : mesh_.triangles[order_[k]]) {
      node.lo = node.lo.cwiseMin(mesh_.positions[v]);
      node.hi = node.hi.cwiseMax(mesh_.positions[v]);
    }
  node.first = first;
  node.count = count;
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeafSize) return index;
  int axis = 0;
  (node.hi - node.lo).maxCoeff(&axis);
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int s, int t) {
                     const double cs = centroids_[s][axis], ct = centroids_[t][axis];
                     return cs < ct || (cs == ct && s < t);
                   });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].left = left;
  nodes_[index].right = right;
  nodes_[index].count = 0;
  return index;
}

void TriangleTree3D::search(int index, const Vec3& p, ClosestSurfacePoint& best) const {
  const Node& node = nodes_[index];
  if (box_squared_distance(p, node.lo, node.hi) > best.squared_distance) return;
  if (node.left < 0) {
    for (int k = node.first; k < node.first + node.count; ++k) {
      const int t = order_[k];
      const Tri& tri = mesh_.triangles[t];
      Vec3 bary;
      const Vec3 q = closest_point_on_triangle(p, mesh_.positions[tri[0]], mesh_.positions[tri[1]],
                                               mesh_.positions[tri[2]], bary);
      const double d = (q - p).squaredNorm();
      if (d < best.squared_distance || (d == best.squared_distance && t < best.point.triangle)) {
        best.squared_distance = d;
        best.point = {t, bary};
        best.position = q;
      }
    }
    return;
  }
  // Nearer child first; the bound prunes the other one.
  const double dl = box_squared_distance(p, nodes_[node.left].lo, nodes_[node.left].hi);
  const double dr = box_squared_distance(p, nodes_[node.right].lo, nodes_[node.right].hi);
  if (dl <= dr) {
    search(node.left, p, best);
    search(node.right, p, best);
  } else {
    search(node.right, p, best);
    search(node.left, p, best);
  }
}

ClosestSurfacePoint TriangleTree3D::closest(const Vec3& p) const {
  ClosestSurfacePoint best;
  best.squared_distance = std::numeric_limits<double>::infinity();
  search(0, p, best);
  return best;
}

}  // namespace mcon
