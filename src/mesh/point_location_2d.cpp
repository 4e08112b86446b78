#include "mesh/point_location_2d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "base/error.h"

namespace mcon {

namespace {


// Closest point of triangle (a, b, c) to p as barycentric coordinates (Ericson, Real-Time
// Collision Detection, 5.1.5); works for either orientation.
Vec3 closest_barycentric(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return Vec3(1, 0, 0);
  const Vec2 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return Vec3(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return Vec3(1 - v, v, 0);
  }
  const Vec2 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return Vec3(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return Vec3(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return Vec3(0, 1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return Vec3(1 - v - w, v, w);
}

constexpr double kInsideTolerance = 1e-10;
// A walk accepts a triangle only if p is inside it by this barycentric margin, far above both the
// inside tolerance and rounding, so on an embedding no other triangle can be as deep.
constexpr double kWalkMargin = 1e-7;
constexpr int kWalkSteps = 16;

// Whether segments [a, b] and [c, d] (sharing no endpoint) intersect, touching included.
bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  auto orient = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    const double v = cross2(q - p, r - p);
    return (v > 0) - (v < 0);
  };
  auto on_segment = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on [p, q], given collinear
    return r.x() >= std::min(p.x(), q.x()) && r.x() <= std::max(p.x(), q.x()) && r.y() >= std::min(p.y(), q.y()) &&
           r.y() <= std::max(p.y(), q.y());
  };
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}

}  // namespace

Vec3 barycentric_2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double area = cross2(b - a, c - a);
  if (area == 0 || !std::isfinite(area)) return Vec3(1, 0, 0);
  const double la = cross2(b - p, c - p) / area;
  const double lb = cross2(c - p, a - p) / area;
  return Vec3(la, lb, 1.0 - la - lb);
}

TriangleLocator2D::TriangleLocator2D(const std::vector<Vec2>& points, const std::vector<Tri>& triangles)
    : points_(points), triangles_(triangles) {
  require(!triangles_.empty(), MCON_ERROR_EMPTY_MESH, "point location: no triangles");
  const int n = static_cast<int>(triangles_.size());
  box_lo_.resize(n);
  box_hi_.resize(n);
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  std::vector<std::array<long long, 3>> edges;  // (min vertex, max vertex, triangle)
  edges.reserve(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Tri& t = triangles_[i];
    for (int v : t) {
      require(v >= 0 && v < static_cast<int>(points_.size()), MCON_ERROR_INDEX_OUT_OF_RANGE,
              "point location: triangle index out of range");
      require(std::isfinite(points_[v].x()) && std::isfinite(points_[v].y()), MCON_ERROR_NON_FINITE,
              "point location: non-finite point");
    }
    box_lo_[i] = points_[t[0]].cwiseMin(points_[t[1]]).cwiseMin(points_[t[2]]);
    box_hi_[i] = points_[t[0]].cwiseMax(points_[t[1]]).cwiseMax(points_[t[2]]);
    lo = lo.cwiseMin(box_lo_[i]);
    hi = hi.cwiseMax(box_hi_[i]);
    for (int k = 0; k < 3; ++k)
      edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]), i});
  }
  // Boundary triangles: those with an edge no other triangle shares.
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 0; k < edges.size();) {
    std::size_t e = k + 1;
    while (e < edges.size() && edges[e][0] == edges[k][0] && edges[e][1] == edges[k][1]) ++e;
    if (e - k == 1) boundary_.push_back(static_cast<int>(edges[k][2]));
    k = e;
  }
  std::sort(boundary_.begin(), boundary_.end());
  boundary_.erase(std::unique(boundary_.begin(), boundary_.end()), boundary_.end());
  detect_embedding(edges);
  // A square root cell, slightly padded.
  const double size = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-12});
  const Vec2 mid = 0.5 * (lo + hi);
  const Vec2 half = Vec2::Constant(0.5 * size * (1 + 1e-9));
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) all[i] = i;
  root_lo_ = mid - half;
  root_hi_ = mid + half;
  nodes_.emplace_back();
  build(0, root_lo_, root_hi_, std::move(all), 0);
}

// How triangle i meets the closed cell [lo, hi]: 0 apart, 1 overlapping, 2 covering it. The
// separating axis test: the bounding boxes, then the three edge lines, each moved outward by a
// margin (1e-8 of the longest edge) far above locate's inside tolerance (1e-10 of a height) and
// rounding, so every triangle locate could accept at a point of the cell overlaps it. A degenerate
// triangle (locate accepts it anywhere in its box) is judged by its box alone.
int TriangleLocator2D::cell_relation(int i, const Vec2& lo, const Vec2& hi) const {
  if (box_lo_[i].x() > hi.x() || box_hi_[i].x() < lo.x() || box_lo_[i].y() > hi.y() || box_hi_[i].y() < lo.y())
    return 0;
  // A box inside the cell: the triangle is in it (the common case for small triangles).
  if (box_lo_[i].x() >= lo.x() && box_lo_[i].y() >= lo.y() && box_hi_[i].x() <= hi.x() && box_hi_[i].y() <= hi.y())
    return 1;
  const Tri& t = triangles_[i];
  const Vec2 a = points_[t[0]], b = points_[t[1]], c = points_[t[2]];
  const double area = cross2(b - a, c - a);
  if (area == 0 || !std::isfinite(area)) {
    const bool box_covers = box_lo_[i].x() <= lo.x() && box_lo_[i].y() <= lo.y() && box_hi_[i].x() >= hi.x() &&
                            box_hi_[i].y() >= hi.y();
    return box_covers ? 2 : 1;
  }
  const double sign = area > 0 ? 1.0 : -1.0;
  const Vec2 corner[4] = {lo, Vec2(hi.x(), lo.y()), Vec2(lo.x(), hi.y()), hi};
  const Vec2 p[3] = {a, b, c};
  const double margin = 1e-8 * std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
  bool covers = true;
  for (int k = 0; k < 3; ++k) {
    const Vec2 e = p[(k + 1) % 3] - p[k];
    const double allowed = -margin * e.norm();  // sign * cross2(e, q - p_k) >= allowed: inside the moved line
    double most = -std::numeric_limits<double>::infinity(), least = std::numeric_limits<double>::infinity();
    for (const Vec2& q : corner) {
      const double f = sign * cross2(e, q - p[k]);
      most = std::max(most, f);
      least = std::min(least, f);
    }
    if (most < allowed) return 0;  // the whole cell beyond this edge
    covers = covers && least >= 0;
  }
  return covers ? 2 : 1;
}

// Fills node `self` (cell [lo, hi]) with the triangles of `tris` that meet the cell (closed, so
// a point on a cell border finds every triangle touching it in either cell).
void TriangleLocator2D::build(int self, const Vec2& lo, const Vec2& hi, std::vector<int> tris, int depth) {
  constexpr int kLeafSize = 8, kMaxDepth = 24;
  // Triangles that cover the whole cell are candidates for every point of it: they stay at this
  // node instead of being copied into every descendant; triangles that only their box brought
  // here are dropped. Testing boxes alone copied long slivers over a dense cluster (an eye
  // socket, fingertips squeezed by the disk parametrization) into thousands of deep cells: a
  // 3,389-triangle hand disk had 53,000 nodes holding 340,000 entries.
  {
    std::vector<int> rest;
    rest.reserve(tris.size());
    nodes_[self].full_first = static_cast<int>(full_items_.size());
    for (int i : tris) {
      const int relation = cell_relation(i, lo, hi);
      if (relation == 0) continue;
      if (depth > 0 && relation == 2)
        full_items_.push_back(i);
      else
        rest.push_back(i);
    }
    nodes_[self].full_count = static_cast<int>(full_items_.size()) - nodes_[self].full_first;
    tris.swap(rest);
  }
  if (static_cast<int>(tris.size()) <= kLeafSize || depth >= kMaxDepth) {
    nodes_[self].first = static_cast<int>(items_.size());
    nodes_[self].count = static_cast<int>(tris.size());
    items_.insert(items_.end(), tris.begin(), tris.end());
    return;
  }
  const Vec2 c = 0.5 * (lo + hi);
  std::array<std::vector<int>, 4> part;
  for (int i : tris)
    for (int q = 0; q < 4; ++q) {
      const Vec2 qlo((q & 1) ? c.x() : lo.x(), (q & 2) ? c.y() : lo.y());
      const Vec2 qhi((q & 1) ? hi.x() : c.x(), (q & 2) ? hi.y() : c.y());
      if (box_lo_[i].x() <= qhi.x() && box_hi_[i].x() >= qlo.x() && box_lo_[i].y() <= qhi.y() &&
          box_hi_[i].y() >= qlo.y())
        part[q].push_back(i);
    }
  // Triangles that all overlap every quadrant (a tight fan) cannot be separated: stop here.
  bool progress = false;
  for (const auto& p : part) progress = progress || p.size() < tris.size();
  if (!progress) {
    nodes_[self].first = static_cast<int>(items_.size());
    nodes_[self].count = static_cast<int>(tris.size());
    items_.insert(items_.end(), tris.begin(), tris.end());
    return;
  }
  tris = std::vector<int>();
  const int first = static_cast<int>(nodes_.size());
  nodes_[self].center = c;
  nodes_[self].children = first;
  nodes_.resize(nodes_.size() + 4);
  for (int q = 0; q < 4; ++q) {
    const Vec2 qlo((q & 1) ? c.x() : lo.x(), (q & 2) ? c.y() : lo.y());
    const Vec2 qhi((q & 1) ? hi.x() : c.x(), (q & 2) ? hi.y() : c.y());
    build(first + q, qlo, qhi, std::move(part[q]), depth + 1);
  }
}

PointLocation TriangleLocator2D::locate(const Vec2& p) const {
  PointLocation best;
  if (nodes_.empty() || !std::isfinite(p.x()) || !std::isfinite(p.y())) return best;
  double best_min = -kInsideTolerance;
  auto consider = [&](int i) {
    if (p.x() < box_lo_[i].x() || p.y() < box_lo_[i].y() || p.x() > box_hi_[i].x() || p.y() > box_hi_[i].y()) return;
    const Tri& t = triangles_[i];
    const Vec3 l = barycentric_2d(p, points_[t[0]], points_[t[1]], points_[t[2]]);
    const double m = l.minCoeff();
    // Deepest wins, ties keep the lowest index: independent of the order candidates come in.
    if (m > best_min || (m >= best_min && (best.triangle < 0 || i < best.triangle))) {
      best_min = m;
      best.triangle = i;
      best.barycentric = l;
    }
  };
  int node = 0;
  for (;;) {
    const Node& nd = nodes_[node];
    for (int k = nd.full_first; k < nd.full_first + nd.full_count; ++k) consider(full_items_[k]);
    if (nd.children < 0) break;
    node = nd.children + (p.x() >= nd.center.x() ? 1 : 0) + (p.y() >= nd.center.y() ? 2 : 0);
  }
  const Node& leaf = nodes_[node];
  for (int k = leaf.first; k < leaf.first + leaf.count; ++k) consider(items_[k]);
  if (best.triangle >= 0) {
    Vec3& l = best.barycentric;
    l = l.cwiseMax(0.0);
    l /= l.sum();
  }
  return best;
}

void TriangleLocator2D::detect_embedding(const std::vector<std::array<long long, 3>>& edges) {
  const int n = static_cast<int>(triangles_.size());
  int sign = 0;
  for (const Tri& t : triangles_) {
    const double a = cross2(points_[t[1]] - points_[t[0]], points_[t[2]] - points_[t[0]]);
    const int s = (a > 0) - (a < 0);
    if (s == 0 || (sign != 0 && s != sign)) return;
    sign = s;
  }
  std::vector<std::array<int, 3>> nb(n, {-1, -1, -1});
  std::vector<std::array<int, 2>> rim;  // unpaired edges
  auto forward = [&](int t, long long a, long long b) {  // t runs a -> b
    for (int k = 0; k < 3; ++k)
      if (triangles_[t][k] == a && triangles_[t][(k + 1) % 3] == b) return true;
    return false;
  };
  auto corner_opposite = [&](int t, long long a, long long b) {
    for (int k = 0; k < 3; ++k)
      if (triangles_[t][k] != a && triangles_[t][k] != b) return k;
    return 0;
  };
  for (std::size_t k = 0; k < edges.size();) {
    std::size_t e = k + 1;
    while (e < edges.size() && edges[e][0] == edges[k][0] && edges[e][1] == edges[k][1]) ++e;
    if (e - k > 2) return;  // non-manifold edge
    // (Then: one consistent orientation, every triangle of the same sign and a simple rim loop
    // make the number of triangles over a point the rim's winding number, at most 1.)
    if (e - k == 1) {
      rim.push_back({static_cast<int>(edges[k][0]), static_cast<int>(edges[k][1])});
    } else {
      const int t0 = static_cast<int>(edges[k][2]), t1 = static_cast<int>(edges[k + 1][2]);
      if (forward(t0, edges[k][0], edges[k][1]) == forward(t1, edges[k][0], edges[k][1])) return;  // inconsistent
      nb[t0][corner_opposite(t0, edges[k][0], edges[k][1])] = t1;
      nb[t1][corner_opposite(t1, edges[k][0], edges[k][1])] = t0;
    }
    k = e;
  }
  // One loop: every rim vertex on exactly two rim edges, all reached from the first.
  std::vector<std::vector<int>> at(points_.size());
  for (std::size_t i = 0; i < rim.size(); ++i)
    for (int v : rim[i]) at[v].push_back(static_cast<int>(i));
  for (const auto& list : at)
    if (!list.empty() && list.size() != 2) return;
  if (rim.empty()) return;
  std::size_t visited = 0;
  int e = 0, v = rim[0][1];
  do {
    ++visited;
    e = at[v][0] == e ? at[v][1] : at[v][0];
    v = rim[e][0] == v ? rim[e][1] : rim[e][0];
  } while (e != 0 && visited <= rim.size());
  if (visited != rim.size()) return;
  // The loop does not cross itself (edges sharing a vertex are adjacent in a loop and skipped).
  for (std::size_t i = 0; i < rim.size(); ++i) {
    const Vec2 &a = points_[rim[i][0]], &b = points_[rim[i][1]];
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    for (std::size_t j = i + 1; j < rim.size(); ++j) {
      if (rim[j][0] == rim[i][0] || rim[j][0] == rim[i][1] || rim[j][1] == rim[i][0] || rim[j][1] == rim[i][1])
        continue;
      const Vec2 &c = points_[rim[j][0]], &d = points_[rim[j][1]];
      if (std::max(c.x(), d.x()) < lo.x() || std::min(c.x(), d.x()) > hi.x() || std::max(c.y(), d.y()) < lo.y() ||
          std::min(c.y(), d.y()) > hi.y())
        continue;
      if (segments_intersect(a, b, c, d)) return;
    }
  }
  neighbors_ = std::move(nb);
}

PointLocation TriangleLocator2D::locate(const Vec2& p, int hint) const {
  if (neighbors_.empty() || hint < 0 || hint >= num_triangles() || !std::isfinite(p.x()) || !std::isfinite(p.y()))
    return locate(p);
  int t = hint;
  for (int step = 0; step < kWalkSteps; ++step) {
    const Tri& tri = triangles_[t];
    Vec3 l = barycentric_2d(p, points_[tri[0]], points_[tri[1]], points_[tri[2]]);
    Eigen::Index k = 0;
    const double m = l.minCoeff(&k);
    if (m > kWalkMargin) {  // as locate's result: clamped (a no-op here) and normalized
      PointLocation hit;
      hit.triangle = t;
      l = l.cwiseMax(0.0);
      l /= l.sum();
      hit.barycentric = l;
      return hit;
    }
    if (m > -kWalkMargin || neighbors_[t][k] < 0) break;  // near an edge, or towards the outside
    t = neighbors_[t][k];
  }
  return locate(p);
}

PointLocation TriangleLocator2D::locate_nearest(const Vec2& p, double max_distance, int hint) const {
  const PointLocation hit = locate(p, hint);
  if (hit.triangle >= 0 || !std::isfinite(p.x()) || !std::isfinite(p.y())) return hit;
  return nearest_on_boundary(p, max_distance);
}

PointLocation TriangleLocator2D::locate_nearest(const Vec2& p, double max_distance) const {
  const PointLocation hit = locate(p);
  if (hit.triangle >= 0 || !std::isfinite(p.x()) || !std::isfinite(p.y())) return hit;
  return nearest_on_boundary(p, max_distance);
}

PointLocation TriangleLocator2D::nearest_on_boundary(const Vec2& p, double max_distance) const {
  // Outside the triangulation the nearest point lies on its boundary. The triangles of the leaf
  // nearest to p bound the distance first, so most boundary triangles are skipped by their box.
  PointLocation best;
  double best_d2 = max_distance * max_distance;
  {
    const Vec2 q = p.cwiseMax(root_lo_).cwiseMin(root_hi_);
    auto bound = [&](int i) {
      const Tri& t = triangles_[i];
      const Vec3 l = closest_barycentric(p, points_[t[0]], points_[t[1]], points_[t[2]]);
      const Vec2 c = l[0] * points_[t[0]] + l[1] * points_[t[1]] + l[2] * points_[t[2]];
      best_d2 = std::min(best_d2, (c - p).squaredNorm() * (1 + 1e-12) + 1e-300);
    };
    int node = 0;
    for (;;) {
      const Node& nd = nodes_[node];
      for (int k = nd.full_first; k < nd.full_first + nd.full_count; ++k) bound(full_items_[k]);
      if (nd.children < 0) break;
      node = nd.children + (q.x() >= nd.center.x() ? 1 : 0) + (q.y() >= nd.center.y() ? 2 : 0);
    }
    for (int k = nodes_[node].first; k < nodes_[node].first + nodes_[node].count; ++k) bound(items_[k]);
  }
  for (int i : boundary_) {  // ascending: ties keep the lowest index
    const Vec2 q0 = p.cwiseMax(box_lo_[i]).cwiseMin(box_hi_[i]);
    if ((q0 - p).squaredNorm() > best_d2) continue;
    const Tri& t = triangles_[i];
    const Vec3 l = closest_barycentric(p, points_[t[0]], points_[t[1]], points_[t[2]]);
    const Vec2 q = l[0] * points_[t[0]] + l[1] * points_[t[1]] + l[2] * points_[t[2]];
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2 || (d2 == best_d2 && best.triangle < 0)) {
      best_d2 = d2;
      best.triangle = i;
      best.barycentric = l;
    }
  }
  if (best.triangle >= 0) best.distance = std::sqrt(best_d2);
  return best;
}

}  // namespace mcon
