#include "transfer/guide_cutting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <unordered_map>

#include "base/error.h"
#include "mesh/closest_point_3d.h"
#include "mesh/edge_key.h"
#include "mesh/mesh_topology.h"
#include "transfer/guide_self_crossing.h"

namespace mcon {
namespace {

constexpr double kOnEdge = 1e-9;  // a barycentric weight at or below this is zero (traced crossings are exact)
constexpr double kPi = 3.14159265358979323846;

// A guide point in its simplest form: an input vertex, a point inside an input edge, or a point
// inside an input triangle.
struct Node {
  enum Kind { vertex, edge, face } kind = vertex;
  int v = -1;            // vertex: the input vertex
  int e = -1;            // edge: the input edge (topology index), a = edges[e][0] < b = edges[e][1]
  double t = 0;          // edge: parameter from a to b
  int f = -1;            // face: the input triangle
  Vec3 w = Vec3::Zero(); // face: barycentric weights
  int id = -1;           // its vertex in the cut mesh, once resolved
  bool snapped = false;  // moved onto an input vertex
};

double mean_side(const TriMesh& m, int t) {
  const Tri& tri = m.triangles[t];
  return ((m.positions[tri[0]] - m.positions[tri[1]]).norm() + (m.positions[tri[1]] - m.positions[tri[2]]).norm() +
          (m.positions[tri[2]] - m.positions[tri[0]]).norm()) /
         3.0;
}

// Smallest angle (degrees) of the triangle (a, b, c).
double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, v = r - p;
    return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / kPi;
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

// Smallest angle (degrees) over the given triangles of `m` (180 for none).
double smallest_angle_of(const TriMesh& m, const std::vector<int>& triangles) {
  double a = 180;
  for (int t : triangles) {
    const Tri& tri = m.triangles[t];
    a = std::min(a, min_angle(m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]));
  }
  return a;
}

// One input triangle's points in its own isometric 2D frame (corner 0 at the origin, corner 1
// on +x, counterclockwise), with the edges that must appear in its retriangulation.
struct LocalPoints {
  Vec2 c[3];
  double scale = 0, eps = 0;        // longest side; length tolerance 1e-9 * scale
  std::vector<int> ids;             // local point -> cut-mesh vertex
  std::vector<Vec2> xy;
  std::unordered_map<int, int> local;
  std::set<std::pair<int, int>> forced;
  int boundary_points = 0;

  int add(int id, const Vec2& x) {
    const auto [it, inserted] = local.emplace(id, static_cast<int>(ids.size()));
    if (inserted) {
      ids.push_back(id);
      xy.push_back(x);
    }
    return it->second;
  }
  void force(int a, int b) { forced.insert({std::min(a, b), std::max(a, b)}); }
  double orient(const Vec2& a, const Vec2& b, const Vec2& x) const { return cross2(b - a, x - a); }
  // x strictly inside the segment (a, b)?
  bool on_segment(const Vec2& a, const Vec2& b, const Vec2& x) const {
    const Vec2 d = b - a;
    const double len = d.norm();
    if (len == 0 || std::abs(orient(a, b, x)) > eps * len) return false;
    const double s = (x - a).dot(d) / (len * len);
    return s * len > eps && (1 - s) * len > eps;
  }
  // Do the segments (a, b) and (p, q) of local points cross properly (not at a shared end)? A
  // point within eps of the other segment's line counts as on it, so two pieces of one triangle
  // side (collinear up to rounding) never "cross".
  bool crosses(int a, int b, int p, int q) const {
    if (a == p || a == q || b == p || b == q) return false;
    return segments_cross_properly(xy[a], xy[b], xy[p], xy[q], eps);
  }
  Vec3 barycentric_of(const Vec2& x) const {
    const double area = cross2(c[1] - c[0], c[2] - c[0]);
    const double w1 = cross2(x - c[0], c[2] - c[0]) / area, w2 = cross2(c[1] - c[0], x - c[0]) / area;
    return Vec3(1 - w1 - w2, w1, w2);
  }
};

// Greedy constrained triangulation of a triangle's local points: the forced edges first, then the
// shortest segment that crosses nothing accepted and passes through no point (a maximal set of
// non-crossing segments of points in a convex polygon is a triangulation); its triangles are the
// empty counterclockwise 3-cycles. Throws NUMERICAL unless there are 2n - b - 2 of them (n points,
// b on the boundary).
std::vector<Tri> triangulate(const LocalPoints& P, int t) {
  const int count = static_cast<int>(P.xy.size());
  std::vector<std::array<int, 2>> accepted;
  for (const auto& [a, b] : P.forced) accepted.push_back({a, b});
  for (std::size_t i = 0; i < accepted.size(); ++i)
    for (std::size_t j = i + 1; j < accepted.size(); ++j)
      require(!P.crosses(accepted[i][0], accepted[i][1], accepted[j][0], accepted[j][1]), MCON_ERROR_NUMERICAL,
              "cutting guides into triangle " + std::to_string(t) + ": two guide pieces cross");
  std::vector<std::pair<double, std::array<int, 2>>> candidates;
  for (int a = 0; a < count; ++a)
    for (int b = a + 1; b < count; ++b)
      if (!P.forced.count({a, b})) candidates.push_back({(P.xy[a] - P.xy[b]).squaredNorm(), {a, b}});
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [length, e] : candidates) {
    bool ok = true;
    for (int k = 0; k < count && ok; ++k) ok = !P.on_segment(P.xy[e[0]], P.xy[e[1]], P.xy[k]);
    for (std::size_t i = 0; i < accepted.size() && ok; ++i) ok = !P.crosses(e[0], e[1], accepted[i][0], accepted[i][1]);
    if (ok) accepted.push_back(e);
  }
  std::vector<std::set<int>> adjacent(static_cast<std::size_t>(count));
  for (const auto& e : accepted) {
    adjacent[e[0]].insert(e[1]);
    adjacent[e[1]].insert(e[0]);
  }
  const double area_eps = P.eps * P.scale;
  std::vector<Tri> pieces;
  for (int a = 0; a < count; ++a)
    for (int b : adjacent[a]) {
      if (b <= a) continue;
      for (int k : adjacent[b]) {
        if (k <= b || !adjacent[a].count(k)) continue;
        int i = a, j = b, l = k;
        const double o = P.orient(P.xy[i], P.xy[j], P.xy[l]);
        if (std::abs(o) <= area_eps) continue;
        if (o < 0) std::swap(j, l);
        bool empty = true;
        for (int m = 0; m < count && empty; ++m)
          if (m != i && m != j && m != l)
            empty = !(P.orient(P.xy[i], P.xy[j], P.xy[m]) > -area_eps && P.orient(P.xy[j], P.xy[l], P.xy[m]) > -area_eps &&
                      P.orient(P.xy[l], P.xy[i], P.xy[m]) > -area_eps);
        if (empty) pieces.push_back({P.ids[i], P.ids[j], P.ids[l]});
      }
    }
  const int expected = 2 * count - P.boundary_points - 2;
  require(static_cast<int>(pieces.size()) == expected, MCON_ERROR_NUMERICAL,
          "cutting guides into triangle " + std::to_string(t) + " gave " + std::to_string(pieces.size()) +
              " triangles instead of " + std::to_string(expected) + "; try a larger snap_fraction");
  return pieces;
}

class GuideCutter {
 public:
  GuideCutter(const TriMesh& mesh, const GuideCutOptions& options)
      : mesh_(mesh), options_(options), topology_(build_topology(mesh)) {
    for (int e = 0; e < topology_.num_edges(); ++e) edge_index_[edge_key(topology_.edges[e][0], topology_.edges[e][1])] = e;
  }

  CutMesh run(const std::vector<std::vector<SurfacePoint>>& polylines, const std::vector<bool>& closed);

 private:
  Node classify(const SurfacePoint& p, const std::string& what) const;
  Node on_edge(int t, int i, int j, double s) const;  // the point (1 - s) corner i + s corner j of t
  void simplify(std::vector<Node>& line);
  void resolve(std::vector<std::vector<Node>>& lines);
  void assign_segments(const std::vector<std::vector<Node>>& lines, const std::vector<bool>& closed);
  void cut_triangle(int t);
  LocalPoints local_points(int t) const;
  void assemble_mesh(const std::vector<bool>& cut);
  void chain_guides();
  SurfacePoint closest_guide_point(int v, const std::vector<SurfacePoint>& line, bool closed, Vec3& x, double& distance) const;
  void relocate_snapped_vertices(const std::vector<std::vector<SurfacePoint>>& polylines, const std::vector<bool>& closed);
  void fair_chains();
  void build_stars();
  bool try_move(int v, const Vec3& q);
  void measure_min_angle();
  std::vector<int> triangles_of(const Node& n) const;
  int edge_of(int a, int b) const {
    const auto it = edge_index_.find(edge_key(a, b));
    return it == edge_index_.end() ? -1 : it->second;
  }
  int new_vertex(int t, const Vec3& w) {
    host_.push_back({t, w});
    return static_cast<int>(host_.size()) - 1;
  }

  const TriMesh& mesh_;
  const GuideCutOptions options_;
  const MeshTopology topology_;
  std::unordered_map<std::uint64_t, int> edge_index_;
  std::vector<SurfacePoint> host_;
  // Per input edge: its vertices in the cut mesh with their parameter, sorted, ends included.
  std::map<int, std::vector<std::pair<double, int>>> edge_vertices_;
  std::map<int, std::vector<int>> face_vertices_;  // per input triangle: cut-mesh vertices inside it
  // A guide segment between two resolved nodes, in the triangle it lies in (-1: along an input edge).
  struct Segment {
    int u = -1, v = -1, triangle = -1, edge = -1;
    std::vector<int> inner;  // vertices found on it, in order from u
  };
  std::vector<std::vector<Segment>> segments_;                // per guide
  std::map<int, std::vector<std::pair<int, int>>> in_triangle_;  // triangle -> (guide, segment)
  std::vector<std::vector<Tri>> pieces_;                      // per input triangle, its new triangles (if cut)
  std::vector<std::vector<int>> star_;                        // per cut-mesh vertex, its cut-mesh triangles
  CutMesh out_;
};

Node GuideCutter::on_edge(int t, int i, int j, double s) const {
  const Tri& tri = mesh_.triangles[t];
  Node n;
  int a = tri[i], b = tri[j];
  if (a > b) {
    std::swap(a, b);
    s = 1 - s;
  }
  n.kind = Node::edge;
  n.e = edge_of(a, b);
  n.t = s;
  if (s <= options_.snap_fraction || s >= 1 - options_.snap_fraction) {
    n.kind = Node::vertex;
    n.v = s <= options_.snap_fraction ? a : b;
    n.snapped = true;
  }
  return n;
}

Node GuideCutter::classify(const SurfacePoint& p, const std::string& what) const {
  const Vec3 w = checked_barycentric(p.triangle, p.barycentric, mesh_.num_triangles(), what);
  int nonzero = 0;
  for (int k = 0; k < 3; ++k) nonzero += w[k] > kOnEdge;
  const Tri& tri = mesh_.triangles[p.triangle];
  if (nonzero == 1) {
    Node n;
    n.v = tri[w[0] > kOnEdge ? 0 : w[1] > kOnEdge ? 1 : 2];
    return n;
  }
  if (nonzero == 2) {
    const int zero = w[0] <= kOnEdge ? 0 : w[1] <= kOnEdge ? 1 : 2;
    const int i = (zero + 1) % 3, j = (zero + 2) % 3;
    return on_edge(p.triangle, i, j, w[j] / (w[i] + w[j]));
  }
  // Inside: onto the nearest side if it is closer than snap_fraction of the mean side.
  const Vec3 x = position_on(mesh_, {p.triangle, w});
  int best = -1;
  double best_distance = options_.snap_fraction * mean_side(mesh_, p.triangle), best_s = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = mesh_.positions[tri[k]], b = mesh_.positions[tri[(k + 1) % 3]];
    const double s = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    const double d = (a + s * (b - a) - x).norm();
    if (d < best_distance) {
      best_distance = d;
      best = k;
      best_s = s;
    }
  }
  if (best >= 0) return on_edge(p.triangle, best, (best + 1) % 3, best_s);
  Node n;
  n.kind = Node::face;
  n.f = p.triangle;
  n.w = w;
  return n;
}

// Douglas-Peucker on each run of points inside one triangle, between the points that bound it.
void GuideCutter::simplify(std::vector<Node>& line) {
  std::vector<bool> keep(line.size(), true);
  for (std::size_t i = 0; i < line.size();) {
    if (line[i].kind != Node::face) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < line.size() && line[j + 1].kind == Node::face && line[j + 1].f == line[i].f) ++j;
    // Runs at an end of the polyline keep that end (a closed polyline's start is kept too).
    const std::size_t lo = i == 0 ? 0 : i - 1, hi = j + 1 == line.size() ? j : j + 1;
    const double tolerance = options_.simplify_fraction * mean_side(mesh_, line[i].f);
    auto x = [&](std::size_t k) -> Vec3 {
      const Node& n = line[k];
      if (n.kind == Node::face) return position_on(mesh_, {n.f, n.w});
      if (n.kind == Node::vertex) return mesh_.positions[n.v];
      const auto& e = topology_.edges[n.e];
      return (1 - n.t) * mesh_.positions[e[0]] + n.t * mesh_.positions[e[1]];
    };
    std::vector<std::pair<std::size_t, std::size_t>> stack{{lo, hi}};
    while (!stack.empty()) {
      const auto [a, b] = stack.back();
      stack.pop_back();
      if (b <= a + 1) continue;
      const Vec3 xa = x(a), xb = x(b);
      std::size_t far = a;
      double far_distance = -1;
      for (std::size_t k = a + 1; k < b; ++k) {
        const Vec3 d = xb - xa;
        const double s = d.squaredNorm() > 0 ? std::clamp((x(k) - xa).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
        const double dist = (xa + s * d - x(k)).norm();
        if (dist > far_distance) {
          far_distance = dist;
          far = k;
        }
      }
      if (far_distance > tolerance) {
        stack.push_back({a, far});
        stack.push_back({far, b});
      } else {
        for (std::size_t k = a + 1; k < b; ++k)
          if (line[k].kind == Node::face && k >= i && k <= j) keep[k] = false;
      }
    }
    i = j + 1;
  }
  std::vector<Node> kept;
  for (std::size_t k = 0; k < line.size(); ++k)
    if (keep[k]) kept.push_back(line[k]);
    else ++out_.dropped_points;
  line = std::move(kept);
}

// Cut-mesh vertices for every node: input vertices keep their index; crossings of one edge that
// lie closer than snap_fraction merge (their mean parameter); points inside one triangle closer
// than snap_fraction * mean side merge.
void GuideCutter::resolve(std::vector<std::vector<Node>>& lines) {
  for (int v = 0; v < mesh_.num_vertices(); ++v) {
    const int t = topology_.vertex_triangles[v].front();
    Vec3 w = Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      if (mesh_.triangles[t][k] == v) w[k] = 1;
    host_.push_back({t, w});
  }
  std::map<int, std::vector<Node*>> on_edges;
  std::map<int, std::vector<Node*>> in_faces;
  for (auto& line : lines)
    for (Node& n : line) {
      if (n.kind == Node::vertex) n.id = n.v;
      if (n.kind == Node::edge) on_edges[n.e].push_back(&n);
    }
  for (auto& [e, nodes] : on_edges) {
    std::stable_sort(nodes.begin(), nodes.end(), [](const Node* p, const Node* q) { return p->t < q->t; });
    auto& list = edge_vertices_[e];
    const int a = topology_.edges[e][0], b = topology_.edges[e][1];
    list.push_back({0.0, a});
    for (std::size_t i = 0; i < nodes.size();) {
      std::size_t j = i;
      double sum = nodes[i]->t;
      while (j + 1 < nodes.size() && nodes[j + 1]->t - nodes[j]->t < options_.snap_fraction) sum += nodes[++j]->t;
      const double t = sum / static_cast<double>(j - i + 1);
      const int tri = topology_.edge_triangles[e][0];
      Vec3 w = Vec3::Zero();
      for (int k = 0; k < 3; ++k) {
        if (mesh_.triangles[tri][k] == a) w[k] = 1 - t;
        if (mesh_.triangles[tri][k] == b) w[k] = t;
      }
      const int id = new_vertex(tri, w);
      // Distinct crossings (not repeats of one point, as a polyline's closing point) merged here.
      for (std::size_t k = i + 1; k <= j; ++k) out_.merged_crossings += nodes[k]->t != nodes[k - 1]->t;
      for (std::size_t k = i; k <= j; ++k) {
        nodes[k]->id = id;
        nodes[k]->t = t;
      }
      list.push_back({t, id});
      i = j + 1;
    }
    list.push_back({1.0, b});
  }
  // A guide that leaves a vertex and comes back to it within a few points (it crossed an edge
  // and crossed back, and both crossings merged) would make a spike: the detour is dropped.
  for (auto& line : lines) {
    std::vector<Node> kept;
    for (const Node& n : line) {
      std::size_t back = 0;
      if (n.kind != Node::face)
        for (std::size_t k = kept.size(); k-- > 0 && kept.size() - k <= 4;)
          if (kept[k].kind != Node::face && kept[k].id == n.id) {
            back = kept.size() - k;
            break;
          }
      if (back == 0) {
        kept.push_back(n);
        continue;
      }
      out_.dropped_points += static_cast<int>(back - 1);  // a repeated point is not counted
      kept.resize(kept.size() - back + 1);
    }
    line = std::move(kept);
  }
  for (auto& line : lines)
    for (Node& n : line)
      if (n.kind == Node::face) in_faces[n.f].push_back(&n);
  for (auto& [f, nodes] : in_faces) {
    const double radius = options_.snap_fraction * mean_side(mesh_, f);
    std::vector<std::pair<Vec3, int>> representatives;
    for (Node* n : nodes) {
      const Vec3 x = position_on(mesh_, {f, n->w});
      for (const auto& [y, id] : representatives)
        if ((x - y).norm() < radius) {
          n->id = id;
          break;
        }
      if (n->id < 0) {
        n->id = new_vertex(f, n->w);
        representatives.push_back({x, n->id});
        face_vertices_[f].push_back(n->id);
      }
    }
  }
}

std::vector<int> GuideCutter::triangles_of(const Node& n) const {
  if (n.kind == Node::face) return {n.f};
  if (n.kind == Node::vertex) {
    std::vector<int> t = topology_.vertex_triangles[n.v];
    std::sort(t.begin(), t.end());
    return t;
  }
  std::vector<int> t;
  for (int k : topology_.edge_triangles[n.e])
    if (k >= 0) t.push_back(k);
  std::sort(t.begin(), t.end());
  return t;
}

void GuideCutter::assign_segments(const std::vector<std::vector<Node>>& lines, const std::vector<bool>& closed) {
  segments_.resize(lines.size());
  for (std::size_t g = 0; g < lines.size(); ++g) {
    const auto& line = lines[g];
    const std::size_t count = line.size() < 2 ? 0 : closed[g] ? line.size() : line.size() - 1;
    for (std::size_t i = 0; i < count; ++i) {
      const Node& p = line[i];
      const Node& q = line[(i + 1) % line.size()];
      if (p.id == q.id) continue;
      Segment s;
      s.u = p.id;
      s.v = q.id;
      // Along one input edge: both ends on it (an input vertex counts as on its edges).
      auto edge_through = [&](const Node& n, const Node& m) {
        if (n.kind == Node::face || m.kind == Node::face) return -1;
        if (n.kind == Node::edge && m.kind == Node::edge) return n.e == m.e ? n.e : -1;
        if (n.kind == Node::vertex && m.kind == Node::vertex) return edge_of(n.v, m.v);
        const Node& e = n.kind == Node::edge ? n : m;
        const int v = n.kind == Node::vertex ? n.v : m.v;
        return topology_.edges[e.e][0] == v || topology_.edges[e.e][1] == v ? e.e : -1;
      };
      s.edge = edge_through(p, q);
      if (s.edge < 0) {
        const std::vector<int> a = triangles_of(p), b = triangles_of(q);
        std::vector<int> common;
        std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
        require(!common.empty(), MCON_ERROR_INVALID_ARGUMENT,
                "guide " + std::to_string(g) + ": the ends of segment " + std::to_string(i) +
                    " share no triangle; give traced polylines (split at every edge, as polyline transfer "
                    "returns them)");
        s.triangle = common.front();
        in_triangle_[s.triangle].push_back({static_cast<int>(g), static_cast<int>(segments_[g].size())});
      }
      segments_[g].push_back(std::move(s));
    }
  }
}

// The corners of input triangle t, the vertices on its sides (each side piece forced) and the
// vertices inside it.
LocalPoints GuideCutter::local_points(int t) const {
  const Tri& tri = mesh_.triangles[t];
  const Vec3 p0 = mesh_.positions[tri[0]], p1 = mesh_.positions[tri[1]], p2 = mesh_.positions[tri[2]];
  const Vec3 ex = (p1 - p0).normalized();
  const Vec3 ey = (p1 - p0).cross(p2 - p0).normalized().cross(ex);
  auto to_2d = [&](const Vec3& x) { return Vec2((x - p0).dot(ex), (x - p0).dot(ey)); };
  LocalPoints P;
  P.c[0] = to_2d(p0);
  P.c[1] = to_2d(p1);
  P.c[2] = to_2d(p2);
  P.scale = std::max({(p1 - p0).norm(), (p2 - p1).norm(), (p0 - p2).norm()});
  P.eps = 1e-9 * P.scale;
  for (int k = 0; k < 3; ++k) {
    const int a = tri[k], b = tri[(k + 1) % 3];
    std::vector<std::pair<double, int>> side{{0.0, a}, {1.0, b}};
    const auto it = edge_vertices_.find(edge_of(a, b));
    if (it != edge_vertices_.end()) {
      side = it->second;
      if (a > b)
        for (auto& [s, id] : side) s = 1 - s;
      std::sort(side.begin(), side.end());
    }
    auto at = [&](std::size_t i) { return Vec2((1 - side[i].first) * P.c[k] + side[i].first * P.c[(k + 1) % 3]); };
    for (std::size_t i = 0; i + 1 < side.size(); ++i)
      P.force(P.add(side[i].second, at(i)), P.add(side[i + 1].second, at(i + 1)));
    P.boundary_points += static_cast<int>(side.size()) - 1;
  }
  const auto inside = face_vertices_.find(t);
  if (inside != face_vertices_.end())
    for (int id : inside->second)
      P.add(id, to_2d(position_on(mesh_, host_[id])));
  return P;
}

// Retriangulates input triangle t with its guide pieces as forced edges, split where they cross
// each other (a new vertex) or pass through a point.
void GuideCutter::cut_triangle(int t) {
  LocalPoints P = local_points(t);
  auto& here = in_triangle_[t];
  std::vector<std::array<int, 2>> ends(here.size());
  for (std::size_t s = 0; s < here.size(); ++s) {
    const Segment& seg = segments_[here[s].first][here[s].second];
    ends[s] = {P.local.at(seg.u), P.local.at(seg.v)};
  }
  for (std::size_t s = 0; s < here.size(); ++s)
    for (std::size_t r = s + 1; r < here.size(); ++r) {
      const int a = ends[s][0], b = ends[s][1], p = ends[r][0], q = ends[r][1];
      if (!P.crosses(a, b, p, q)) continue;
      const Vec2 d1 = P.xy[b] - P.xy[a], d2 = P.xy[q] - P.xy[p];
      const Vec2 x = P.xy[a] + cross2(P.xy[p] - P.xy[a], d2) / cross2(d1, d2) * d1;
      // A third guide through the same point reuses it; the split below finds it on both.
      bool known = false;
      for (std::size_t k = 0; k < P.xy.size() && !known; ++k) known = (P.xy[k] - x).norm() <= P.eps;
      if (!known) P.add(new_vertex(t, P.barycentric_of(x)), x);
    }
  for (std::size_t s = 0; s < here.size(); ++s) {
    const int a = ends[s][0], b = ends[s][1];
    const Vec2 d = P.xy[b] - P.xy[a];
    std::vector<std::pair<double, int>> on;
    for (std::size_t k = 0; k < P.xy.size(); ++k)
      if (P.on_segment(P.xy[a], P.xy[b], P.xy[k])) on.push_back({(P.xy[k] - P.xy[a]).dot(d) / d.squaredNorm(), static_cast<int>(k)});
    std::sort(on.begin(), on.end());
    Segment& seg = segments_[here[s].first][here[s].second];
    int prev = a;
    for (const auto& [param, k] : on) {
      seg.inner.push_back(P.ids[k]);
      P.force(prev, k);
      prev = k;
    }
    P.force(prev, b);
  }
  pieces_[t] = triangulate(P, t);
}

// The point of the traced polyline closest to input vertex v (and its position and distance):
// the segment's triangle and the point's weights in it.
SurfacePoint GuideCutter::closest_guide_point(int v, const std::vector<SurfacePoint>& line, bool closed, Vec3& x_out,
                                              double& distance) const {
  const Vec3 x = mesh_.positions[v];
  const std::size_t segments = closed ? line.size() : line.size() - 1;
  distance = std::numeric_limits<double>::infinity();
  SurfacePoint target;
  for (std::size_t i = 0; i < segments; ++i) {
    const SurfacePoint& next = line[(i + 1) % line.size()];
    const int t = line[i].triangle;
    const Vec3 a = position_on(mesh_, line[i]);
    const Vec3 d = position_on(mesh_, next) - a;
    const double s = d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    const Vec3 q = a + s * d;
    if (!((q - x).norm() < distance)) continue;
    distance = (q - x).norm();
    x_out = q;
    // The segment lies in triangle t: the weights of q in it.
    const Tri& tri = mesh_.triangles[t];
    Vec3 bary;
    closest_point_on_triangle(q, mesh_.positions[tri[0]], mesh_.positions[tri[1]], mesh_.positions[tri[2]], bary);
    target = {t, bary};
  }
  return target;
}

// A snapped input vertex on one guide moves onto that guide (the closest point of the traced
// polyline, which passes through its star): the guide keeps its traced shape instead of stepping
// through the vertex, and the vertex stays on the input surface. Kept where the move would fold a
// triangle of its star or shrink the star's smallest angle below 0.8 of what it was (then halfway
// is tried); boundary vertices and vertices shared by two guides stay.
void GuideCutter::relocate_snapped_vertices(const std::vector<std::vector<SurfacePoint>>& polylines,
                                             const std::vector<bool>& closed) {
  const int n = mesh_.num_vertices();
  std::vector<int> owner(static_cast<std::size_t>(n), -1);  // guide through the vertex, -2: several
  for (std::size_t g = 0; g < out_.guides.size(); ++g) {
    std::set<int> seen(out_.guides[g].begin(), out_.guides[g].end());
    for (int v : seen)
      if (v < n) owner[v] = owner[v] == -1 ? static_cast<int>(g) : -2;
  }
  std::vector<bool> boundary(static_cast<std::size_t>(n), false);
  for (int e = 0; e < topology_.num_edges(); ++e)
    if (topology_.is_boundary_edge(e)) boundary[topology_.edges[e][0]] = boundary[topology_.edges[e][1]] = true;
  for (int v = 0; v < n; ++v) {
    if (owner[v] < 0 || boundary[v]) continue;
    const auto& line = polylines[static_cast<std::size_t>(owner[v])];
    const Vec3 x = mesh_.positions[v];
    double best = 0;
    Vec3 target_x = x;
    SurfacePoint target = closest_guide_point(v, line, closed[static_cast<std::size_t>(owner[v])], target_x, best);
    // A crossing exactly at the vertex needs no move.
    if (!(best > 1e-12 * mean_side(mesh_, topology_.vertex_triangles[v].front()))) continue;
    // All the way onto the guide, else halfway (the host point moves with it, on the same line).
    double moved = 0;
    for (double fraction : {1.0, 0.5})
      if (try_move(v, x + fraction * (target_x - x))) {
        moved = fraction;
        break;
      }
    if (moved == 0) continue;
    if (moved < 1) {
      // Halfway between the vertex and its target point, in the target's triangle (v is a corner
      // of it or of a neighbour sharing the segment's plane): interpolate the weights.
      const Tri& tri = mesh_.triangles[target.triangle];
      Vec3 at_v = Vec3::Zero();
      for (int k = 0; k < 3; ++k)
        if (tri[k] == v) at_v[k] = 1;
      if (at_v.sum() == 0) {  // v is not a corner of that triangle: keep it where it was
        out_.mesh.positions[v] = x;
        continue;
      }
      target.barycentric = (1 - moved) * at_v + moved * target.barycentric;
    }
    out_.host[v] = target;
    ++out_.moved_vertices;
  }
}

// Chain fairing (docs/design.md §14, step 6). Tracing and snapping leave the chains zig-zagging at
// the scale of one triangle; a quad mesher lays its quad edges along the chain's chords, so every
// zig-zag becomes an angle between guide and quad edge. Each pass moves every chain vertex that one
// guide owns (not on the mesh border, not an open chain's end) halfway to the midpoint of its two
// chain neighbours (a Laplacian step, lambda 1/2), projected onto the input triangles its star lies
// in, so the vertex stays on the input surface and its host point moves with it. A move is kept
// only if no star triangle turns by more than 60 degrees, the star's smallest angle stays at least
// 0.8 of what it was, and the vertex stays within fair_max_shift mean edges of its place after the
// cut (the guide keeps the shape it was traced with).
void GuideCutter::fair_chains() {
  if (options_.fair_passes <= 0 || out_.guides.empty()) return;
  const int nv = out_.mesh.num_vertices();
  std::vector<int> owner(static_cast<std::size_t>(nv), -1);  // -2: several guides or twice in one
  std::vector<std::array<int, 2>> neighbours(static_cast<std::size_t>(nv), {-1, -1});
  for (std::size_t g = 0; g < out_.guides.size(); ++g) {
    const std::vector<int>& chain = out_.guides[g];
    const bool closed = chain.size() >= 4 && chain.front() == chain.back();
    const std::size_t m = closed ? chain.size() - 1 : chain.size();  // distinct positions
    for (std::size_t k = 0; k < m; ++k) {
      const int v = chain[k];
      owner[v] = owner[v] == -1 ? static_cast<int>(g) : -2;
      if (closed)
        neighbours[v] = {chain[(k + m - 1) % m], chain[(k + 1) % m]};
      else if (k > 0 && k + 1 < m)
        neighbours[v] = {chain[k - 1], chain[k + 1]};
    }
  }
  std::map<std::pair<int, int>, int> edge_uses;
  for (int t = 0; t < out_.mesh.num_triangles(); ++t) {
    const Tri& tri = out_.mesh.triangles[t];
    for (int k = 0; k < 3; ++k) ++edge_uses[{std::min(tri[k], tri[(k + 1) % 3]), std::max(tri[k], tri[(k + 1) % 3])}];
  }
  std::vector<bool> border(static_cast<std::size_t>(nv), false);
  for (const auto& [e, uses] : edge_uses)
    if (uses == 1) border[e.first] = border[e.second] = true;
  std::vector<Vec3>& x = out_.mesh.positions;
  const std::vector<Vec3> cut_position = x;
  std::vector<bool> faired(static_cast<std::size_t>(nv), false);
  for (int pass = 0; pass < options_.fair_passes; ++pass)
    for (std::size_t g = 0; g < out_.guides.size(); ++g)
      for (int v : out_.guides[g]) {
        if (owner[v] != static_cast<int>(g) || border[v] || neighbours[v][0] < 0) continue;
        const Vec3 want = 0.5 * x[v] + 0.25 * (x[neighbours[v][0]] + x[neighbours[v][1]]);
        // The closest point to `want` on the input triangles v's star lies in.
        double best = std::numeric_limits<double>::infinity();
        SurfacePoint to;
        Vec3 q = x[v];
        for (int t : star_[v]) {
          const int origin = out_.triangle_origin[t];
          const Tri& tri = mesh_.triangles[origin];
          Vec3 bary;
          const Vec3 p = closest_point_on_triangle(want, mesh_.positions[tri[0]], mesh_.positions[tri[1]],
                                                   mesh_.positions[tri[2]], bary);
          if ((p - want).norm() < best) {
            best = (p - want).norm();
            q = p;
            to = {origin, bary};
          }
        }
        if (!((q - cut_position[v]).norm() <= options_.fair_max_shift * mean_side(mesh_, to.triangle))) continue;
        if (!try_move(v, q)) continue;
        out_.host[v] = to;
        faired[v] = true;
      }
  out_.faired_vertices = static_cast<int>(std::count(faired.begin(), faired.end(), true));
}

// Every cut-mesh vertex's triangles; the moves after the cut change positions, never triangles.
void GuideCutter::build_stars() {
  star_.assign(static_cast<std::size_t>(out_.mesh.num_vertices()), {});
  for (int t = 0; t < out_.mesh.num_triangles(); ++t)
    for (int v : out_.mesh.triangles[t]) star_[v].push_back(t);
}

// Moves cut-mesh vertex v to q, unless that turns a triangle of its star by more than 60 degrees
// (a fold or near-fold) or shrinks the star's smallest angle below 0.8 of what it was; then v stays.
bool GuideCutter::try_move(int v, const Vec3& q) {
  const std::vector<int>& star = star_[v];
  std::vector<Vec3> normals;
  for (int t : star) normals.push_back(triangle_normal(out_.mesh, t));
  const double before = smallest_angle_of(out_.mesh, star);
  const Vec3 was = out_.mesh.positions[v];
  out_.mesh.positions[v] = q;
  bool ok = smallest_angle_of(out_.mesh, star) >= 0.8 * before;
  for (std::size_t k = 0; k < star.size() && ok; ++k) ok = triangle_normal(out_.mesh, star[k]).dot(normals[k]) > 0.5;
  if (!ok) out_.mesh.positions[v] = was;
  return ok;
}

// The smallest angle made: over the cut pieces and the stars of moved input vertices.
void GuideCutter::measure_min_angle() {
  const int n = mesh_.num_vertices();
  out_.min_angle_created = 180;
  std::vector<bool> changed(out_.mesh.triangles.size(), false);
  for (std::size_t t = 0; t < changed.size(); ++t) {
    const Tri& tri = out_.mesh.triangles[t];
    changed[t] = tri != mesh_.triangles[out_.triangle_origin[t]];
    for (int v : tri) changed[t] = changed[t] || (v < n && out_.mesh.positions[v] != mesh_.positions[v]);
  }
  for (std::size_t t = 0; t < changed.size(); ++t)
    if (changed[t]) {
      const Tri& tri = out_.mesh.triangles[t];
      out_.min_angle_created =
          std::min(out_.min_angle_created, min_angle(out_.mesh.positions[tri[0]], out_.mesh.positions[tri[1]], out_.mesh.positions[tri[2]]));
    }
}

CutMesh GuideCutter::run(const std::vector<std::vector<SurfacePoint>>& polylines, const std::vector<bool>& closed_in) {
  std::vector<bool> closed = closed_in.empty() ? std::vector<bool>(polylines.size(), false) : closed_in;
  std::vector<std::vector<Node>> lines(polylines.size());
  for (std::size_t g = 0; g < polylines.size(); ++g) {
    require(polylines[g].size() >= 2, MCON_ERROR_INVALID_ARGUMENT,
            "guide " + std::to_string(g) + " has " + std::to_string(polylines[g].size()) + " points; give at least 2");
    for (std::size_t i = 0; i < polylines[g].size(); ++i)
      lines[g].push_back(classify(polylines[g][i], "guide " + std::to_string(g) + " point " + std::to_string(i)));
    simplify(lines[g]);
  }
  refuse_self_crossing_guides(mesh_, polylines, closed);
  for (const auto& line : lines)
    for (const Node& n : line) out_.snapped_to_vertices += n.snapped;
  resolve(lines);
  assign_segments(lines, closed);

  pieces_.assign(mesh_.triangles.size(), {});
  std::vector<bool> cut(mesh_.triangles.size(), false);
  for (const auto& [e, list] : edge_vertices_)
    for (int k : topology_.edge_triangles[e])
      if (k >= 0 && list.size() > 2) cut[k] = true;
  for (const auto& [f, ids] : face_vertices_)
    if (!ids.empty()) cut[f] = true;
  for (const auto& [f, s] : in_triangle_)
    if (!s.empty()) cut[f] = true;
  for (int t = 0; t < mesh_.num_triangles(); ++t)
    if (cut[t]) cut_triangle(t);
  assemble_mesh(cut);
  chain_guides();
  build_stars();
  relocate_snapped_vertices(polylines, closed);
  fair_chains();
  measure_min_angle();
  return std::move(out_);
}

// The cut mesh: the input's vertices, then the new ones; uncut triangles as they were, cut ones
// replaced by their pieces.
void GuideCutter::assemble_mesh(const std::vector<bool>& cut) {
  out_.host = host_;
  out_.mesh.positions.reserve(host_.size());
  for (const SurfacePoint& h : host_) out_.mesh.positions.push_back(position_on(mesh_, h));
  for (int v = 0; v < mesh_.num_vertices(); ++v) out_.mesh.positions[v] = mesh_.positions[v];
  for (int t = 0; t < mesh_.num_triangles(); ++t) {
    if (!cut[t]) {
      out_.mesh.triangles.push_back(mesh_.triangles[t]);
      out_.triangle_origin.push_back(t);
      continue;
    }
    ++out_.input_triangles_cut;
    const Tri& tri = mesh_.triangles[t];
    out_.min_angle_of_cut_input = std::min(out_.min_angle_of_cut_input,
                                           min_angle(mesh_.positions[tri[0]], mesh_.positions[tri[1]], mesh_.positions[tri[2]]));
    for (const Tri& piece : pieces_[t]) {
      out_.mesh.triangles.push_back(piece);
      out_.triangle_origin.push_back(t);
      const auto& x = out_.mesh.positions;
      out_.min_angle_created = std::min(out_.min_angle_created, min_angle(x[piece[0]], x[piece[1]], x[piece[2]]));
    }
  }
}

// The guides as vertex chains of the cut mesh, and their distinct edges.
void GuideCutter::chain_guides() {
  out_.guides.resize(segments_.size());
  for (std::size_t g = 0; g < segments_.size(); ++g) {
    std::vector<int>& chain = out_.guides[g];
    for (const Segment& s : segments_[g]) {
      if (chain.empty()) chain.push_back(s.u);
      if (s.edge >= 0) {  // along an input edge: its vertices between the ends
        const auto it = edge_vertices_.find(s.edge);
        std::vector<std::pair<double, int>> list =
            it != edge_vertices_.end()
                ? it->second
                : std::vector<std::pair<double, int>>{{0.0, topology_.edges[s.edge][0]}, {1.0, topology_.edges[s.edge][1]}};
        auto at = [&](int id) {
          for (std::size_t k = 0; k < list.size(); ++k)
            if (list[k].second == id) return static_cast<int>(k);
          return -1;
        };
        const int from = at(s.u), to = at(s.v);
        for (int k = from; k != to;) {
          k += to > from ? 1 : -1;
          chain.push_back(list[k].second);
        }
      } else {
        chain.insert(chain.end(), s.inner.begin(), s.inner.end());
        chain.push_back(s.v);
      }
    }
  }
  std::set<std::pair<int, int>> mesh_edges, guide_edges;
  for (const Tri& tri : out_.mesh.triangles)
    for (int k = 0; k < 3; ++k) mesh_edges.insert({std::min(tri[k], tri[(k + 1) % 3]), std::max(tri[k], tri[(k + 1) % 3])});
  // A chain that steps through a snapped input vertex v between p and q where (p, q) is an edge
  // takes that edge: p and q lie on the guide, v only near it (the step would be a zig-zag).
  for (std::vector<int>& chain : out_.guides) {
    std::vector<int> kept;
    for (std::size_t k = 0; k < chain.size(); ++k) {
      kept.push_back(chain[k]);
      while (kept.size() >= 3) {
        const int p = kept[kept.size() - 3], v = kept[kept.size() - 2], q = kept.back();
        if (v >= mesh_.num_vertices() || p == q || !mesh_edges.count({std::min(p, q), std::max(p, q)})) break;
        kept.erase(kept.end() - 2);
        ++out_.shortcuts;
      }
    }
    chain = std::move(kept);
    for (std::size_t k = 0; k + 1 < chain.size(); ++k)
      guide_edges.insert({std::min(chain[k], chain[k + 1]), std::max(chain[k], chain[k + 1])});
  }
  for (const auto& e : guide_edges) {
    require(mesh_edges.count(e) > 0, MCON_ERROR_NUMERICAL,
            "cutting guides: guide edge (" + std::to_string(e.first) + ", " + std::to_string(e.second) +
                ") is not an edge of the cut mesh");
    out_.guide_edges.push_back({e.first, e.second});
  }
}

}  // namespace

CutMesh cut_guides_into_mesh(const TriMesh& mesh, const std::vector<std::vector<SurfacePoint>>& polylines,
                             const std::vector<bool>& closed, const GuideCutOptions& options) {
  require(std::isfinite(options.snap_fraction) && options.snap_fraction >= 0 && options.snap_fraction <= 0.45,
          MCON_ERROR_INVALID_ARGUMENT, "snap_fraction must be in [0, 0.45]");
  require(std::isfinite(options.simplify_fraction) && options.simplify_fraction >= 0 && options.simplify_fraction <= 1,
          MCON_ERROR_INVALID_ARGUMENT, "simplify_fraction must be in [0, 1]");
  require(options.fair_passes >= 0 && options.fair_passes <= 100, MCON_ERROR_INVALID_ARGUMENT,
          "fair_passes must be in [0, 100]");
  require(std::isfinite(options.fair_max_shift) && options.fair_max_shift >= 0 && options.fair_max_shift <= 0.5,
          MCON_ERROR_INVALID_ARGUMENT, "fair_max_shift must be in [0, 0.5]");
  require(closed.empty() || closed.size() == polylines.size(), MCON_ERROR_INVALID_ARGUMENT,
          "closed has " + std::to_string(closed.size()) + " flags for " + std::to_string(polylines.size()) +
              " polylines; give one per polyline or none");
  require(mesh.num_triangles() > 0, MCON_ERROR_EMPTY_MESH, "cannot cut guides into a mesh without triangles");
  GuideCutter cutter(mesh, options);
  return cutter.run(polylines, closed);
}

Eigen::MatrixXd carry_vertex_values(const CutMesh& cut, const TriMesh& input, const Eigen::MatrixXd& values) {
  require(values.rows() == input.num_vertices(), MCON_ERROR_INVALID_ARGUMENT,
          "values have " + std::to_string(values.rows()) + " rows for " + std::to_string(input.num_vertices()) +
              " vertices");
  Eigen::MatrixXd out(static_cast<Eigen::Index>(cut.host.size()), values.cols());
  for (std::size_t v = 0; v < cut.host.size(); ++v) {
    const SurfacePoint& h = cut.host[v];
    const Tri& tri = input.triangles[h.triangle];
    out.row(static_cast<Eigen::Index>(v)) = h.barycentric[0] * values.row(tri[0]) + h.barycentric[1] * values.row(tri[1]) +
                                            h.barycentric[2] * values.row(tri[2]);
  }
  return out;
}

}  // namespace mcon
