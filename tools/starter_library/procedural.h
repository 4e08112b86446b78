// Procedural example constraints for the starter library, computed on a patch's arrays as the C
// API returns them (normalized positions, triangles, uv, center point). Nothing here is an
// artist's work: every constraint is a simple function of geodesic distance or of a plane, and the
// entries are tagged "example".
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <queue>
#include <utility>
#include <vector>

namespace starter {

struct SurfacePoint {
  std::uint32_t face = 0;
  std::array<double, 3> bary{{1, 0, 0}};
};

struct Polyline {
  std::vector<SurfacePoint> points;
  bool closed = false;
};

struct Geometry {
  std::vector<double> p;          // 3 per vertex (normalized: geodesic radius 1)
  std::vector<std::uint32_t> t;   // 3 per triangle
  std::vector<double> uv;         // 2 per vertex (unit disk)
  std::uint32_t center_face = 0;
  std::array<double, 3> center_bary{{1.0 / 3, 1.0 / 3, 1.0 / 3}};

  std::size_t nv() const { return p.size() / 3; }
  std::size_t nt() const { return t.size() / 3; }
  std::array<double, 3> pos(std::size_t v) const { return {p[3 * v], p[3 * v + 1], p[3 * v + 2]}; }
  std::array<double, 3> center() const {
    std::array<double, 3> c{{0, 0, 0}};
    for (int k = 0; k < 3; ++k) {
      const auto q = pos(t[3 * center_face + static_cast<std::size_t>(k)]);
      for (int a = 0; a < 3; ++a) c[a] += center_bary[k] * q[a];
    }
    return c;
  }
};

inline double dist3(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Per vertex, the triangles around it.
inline std::vector<std::vector<std::uint32_t>> vertex_faces(const Geometry& g) {
  std::vector<std::vector<std::uint32_t>> vf(g.nv());
  for (std::uint32_t f = 0; f < g.nt(); ++f)
    for (int k = 0; k < 3; ++k) vf[g.t[3 * f + static_cast<std::size_t>(k)]].push_back(f);
  return vf;
}

// Distance at x from a virtual source unfolded across edge (a, b) with known da, db (the planar
// update of fast marching); falls back to the two edge paths when the straight ray from the
// virtual source does not cross the edge.
inline double triangle_update(const std::array<double, 3>& x, const std::array<double, 3>& a,
                              const std::array<double, 3>& b, double da, double db) {
  const double fallback = std::min(da + dist3(x, a), db + dist3(x, b));
  const double e = dist3(a, b);
  if (e <= 0) return fallback;
  const double xa = dist3(x, a), xb = dist3(x, b);
  const double sx = (da * da - db * db + e * e) / (2 * e);
  const double sy2 = da * da - sx * sx;
  if (sy2 < 0) return fallback;
  const double sy = -std::sqrt(sy2);
  const double px = (xa * xa - xb * xb + e * e) / (2 * e);
  const double py = std::sqrt(std::max(0.0, xa * xa - px * px));
  if (py - sy <= 0) return fallback;
  const double s = -sy / (py - sy);
  const double cross = sx + s * (px - sx);
  if (cross < 0 || cross > e) return fallback;
  return std::min(fallback, std::hypot(px - sx, py - sy));
}

// Geodesic distance from the patch center by fast marching (first order; the patch is normalized
// so the boundary is at about 1).
inline std::vector<double> geodesic_distance(const Geometry& g) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> d(g.nv(), inf);
  std::vector<char> known(g.nv(), 0);
  const auto vf = vertex_faces(g);
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  const auto c = g.center();
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = g.t[3 * g.center_face + static_cast<std::size_t>(k)];
    d[v] = dist3(c, g.pos(v));
    heap.push({d[v], v});
  }
  while (!heap.empty()) {
    const auto [dv, v] = heap.top();
    heap.pop();
    if (known[v] || dv > d[v]) continue;
    known[v] = 1;
    for (std::uint32_t f : vf[v]) {
      const std::uint32_t* tri = &g.t[3 * f];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t x = tri[k];
        if (known[x]) continue;
        const std::uint32_t a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
        double cand = inf;
        if (known[a] && known[b])
          cand = triangle_update(g.pos(x), g.pos(a), g.pos(b), d[a], d[b]);
        else if (known[a])
          cand = d[a] + dist3(g.pos(x), g.pos(a));
        else if (known[b])
          cand = d[b] + dist3(g.pos(x), g.pos(b));
        if (cand < d[x]) {
          d[x] = cand;
          heap.push({cand, x});
        }
      }
    }
  }
  return d;
}

// The level set f = level as polylines of surface points: marching triangles, segments chained
// across shared edges; open polylines end on the patch boundary.
inline std::vector<Polyline> iso_lines(const Geometry& g, const std::vector<double>& f, double level) {
  // A level exactly at a vertex value would put two polyline points on that vertex.
  for (double x : f)
    if (x == level) level += 1e-9;
  struct Node {
    std::uint32_t a, b;    // the edge, a < b
    double t;              // crossing at (1 - t) * a + t * b
    std::vector<std::pair<std::uint32_t, std::size_t>> links;  // (face, other node)
  };
  std::vector<Node> nodes;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> node_of;
  auto node = [&](std::uint32_t i, std::uint32_t j) {
    const auto key = std::minmax(i, j);
    auto it = node_of.find(key);
    if (it != node_of.end()) return it->second;
    const double t = (level - f[key.first]) / (f[key.second] - f[key.first]);
    nodes.push_back({key.first, key.second, t, {}});
    node_of[key] = nodes.size() - 1;
    return nodes.size() - 1;
  };
  for (std::uint32_t face = 0; face < g.nt(); ++face) {
    const std::uint32_t* tri = &g.t[3 * face];
    std::vector<std::size_t> hits;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = tri[k], j = tri[(k + 1) % 3];
      if ((f[i] < level) != (f[j] < level)) hits.push_back(node(i, j));
    }
    if (hits.size() == 2) {
      nodes[hits[0]].links.push_back({face, hits[1]});
      nodes[hits[1]].links.push_back({face, hits[0]});
    }
  }
  // A point of node n expressed in face `face`.
  auto point = [&](std::size_t n, std::uint32_t face) {
    SurfacePoint sp;
    sp.face = face;
    sp.bary = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      if (g.t[3 * face + static_cast<std::size_t>(k)] == nodes[n].a) sp.bary[k] += 1 - nodes[n].t;
      if (g.t[3 * face + static_cast<std::size_t>(k)] == nodes[n].b) sp.bary[k] += nodes[n].t;
    }
    return sp;
  };
  std::vector<char> used(nodes.size(), 0);
  std::vector<Polyline> out;
  auto walk = [&](std::size_t start) {
    Polyline pl;
    std::size_t n = start;
    std::uint32_t prev_face = std::numeric_limits<std::uint32_t>::max();
    used[n] = 1;
    for (;;) {
      std::size_t next = n;
      std::uint32_t face = 0;
      bool found = false;
      for (const auto& [lf, other] : nodes[n].links)
        if (lf != prev_face && !used[other]) {
          next = other;
          face = lf;
          found = true;
          break;
        }
      if (!found) {
        // Closed if n links back to the start through a face other than the one we came by.
        for (const auto& [lf, other] : nodes[n].links)
          if (other == start && lf != prev_face && pl.points.size() >= 2) {
            pl.points.push_back(point(n, lf));
            pl.closed = true;
          }
        if (!pl.closed) pl.points.push_back(point(n, prev_face == std::numeric_limits<std::uint32_t>::max()
                                                         ? nodes[n].links.front().first
                                                         : prev_face));
        break;
      }
      pl.points.push_back(point(n, face));
      used[next] = 1;
      prev_face = face;
      n = next;
    }
    return pl;
  };
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if (!used[n] && nodes[n].links.size() == 1) out.push_back(walk(n));  // open: from a boundary edge
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if (!used[n] && !nodes[n].links.empty()) out.push_back(walk(n));
  return out;
}

inline std::array<double, 3> point_position(const Geometry& g, const SurfacePoint& sp) {
  std::array<double, 3> c{{0, 0, 0}};
  for (int k = 0; k < 3; ++k) {
    const auto q = g.pos(g.t[3 * sp.face + static_cast<std::size_t>(k)]);
    for (int a = 0; a < 3; ++a) c[a] += sp.bary[k] * q[a];
  }
  return c;
}

inline double length(const Geometry& g, const Polyline& pl) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < pl.points.size(); ++i)
    s += dist3(point_position(g, pl.points[i]), point_position(g, pl.points[i + 1]));
  if (pl.closed && pl.points.size() > 2) s += dist3(point_position(g, pl.points.back()), point_position(g, pl.points[0]));
  return s;
}

// A vertex as a surface point (its first face, weight 1 on its corner).
inline SurfacePoint vertex_point(const Geometry& g, const std::vector<std::vector<std::uint32_t>>& vf,
                                 std::uint32_t v) {
  SurfacePoint sp;
  sp.face = vf[v].front();
  sp.bary = {0, 0, 0};
  for (int k = 0; k < 3; ++k)
    if (g.t[3 * sp.face + static_cast<std::size_t>(k)] == v) sp.bary[k] = 1;
  return sp;
}

// Boundary vertices (on an edge used by one triangle).
inline std::vector<char> boundary_vertices(const Geometry& g) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (std::size_t f = 0; f < g.nt(); ++f)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(g.t[3 * f + static_cast<std::size_t>(k)], g.t[3 * f + (static_cast<std::size_t>(k) + 1) % 3])];
  std::vector<char> b(g.nv(), 0);
  for (const auto& [e, c] : count)
    if (c == 1) b[e.first] = b[e.second] = 1;
  return b;
}

inline std::vector<std::vector<std::uint32_t>> vertex_neighbours(const Geometry& g) {
  std::vector<std::vector<std::uint32_t>> nb(g.nv());
  for (std::size_t f = 0; f < g.nt(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = g.t[3 * f + static_cast<std::size_t>(k)], j = g.t[3 * f + (static_cast<std::size_t>(k) + 1) % 3];
      nb[i].push_back(j);
      nb[j].push_back(i);
    }
  for (auto& n : nb) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return nb;
}

// Interior local maxima of d over two rings of neighbours with d >= min_value, largest first, at
// least `separation` apart (3D, normalized units); at most `count`. Boundary vertices are never
// maxima: the cut puts them all at distance 1, so their noise would win over the real tips.
inline std::vector<std::uint32_t> distance_maxima(const Geometry& g, const std::vector<double>& d, double min_value,
                                                  double separation, std::size_t count) {
  const auto nb = vertex_neighbours(g);
  const auto boundary = boundary_vertices(g);
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t v = 0; v < g.nv(); ++v) {
    if (d[v] < min_value || boundary[v]) continue;
    bool is_max = true;
    for (std::uint32_t a : nb[v]) {
      if (d[a] > d[v]) is_max = false;
      for (std::uint32_t b : nb[a])
        if (d[b] > d[v]) is_max = false;
    }
    if (is_max) candidates.push_back(v);
  }
  std::sort(candidates.begin(), candidates.end(), [&](std::uint32_t a, std::uint32_t b) {
    return d[a] != d[b] ? d[a] > d[b] : a < b;
  });
  std::vector<std::uint32_t> out;
  for (std::uint32_t v : candidates) {
    bool far = true;
    for (std::uint32_t w : out)
      if (dist3(g.pos(v), g.pos(w)) < separation) far = false;
    if (far) out.push_back(v);
    if (out.size() == count) break;
  }
  return out;
}

// From `start` down the discrete gradient of d (always to the neighbour with the smallest d)
// until d < stop: a flow line as a vertex path.
inline std::vector<std::uint32_t> descend(const Geometry& g, const std::vector<double>& d, std::uint32_t start,
                                          double stop) {
  const auto nb = vertex_neighbours(g);
  std::vector<std::uint32_t> path{start};
  std::uint32_t v = start;
  while (d[v] >= stop) {
    std::uint32_t best = v;
    for (std::uint32_t a : nb[v])
      if (d[a] < d[best]) best = a;
    if (best == v) break;
    path.push_back(best);
    v = best;
  }
  return path;
}

}  // namespace starter
