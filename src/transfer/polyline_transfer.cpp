#include "transfer/polyline_transfer.h"

#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <string>

#include "base/error.h"
#include "mesh/mesh_topology.h"
#include "mesh/point_location_2d.h"
#include "transfer/guide_self_crossing.h"
#include "transfer/polyline_straightening.h"

namespace mcon {

namespace {

Vec3 clamp_barycentric(const Vec3& b) {
  const Vec3 c = b.cwiseMax(0.0);
  const double s = c.sum();
  return s > 0 ? Vec3(c / s) : Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3);
}

struct TracePoint {
  int triangle;
  Vec3 barycentric;
  Vec2 uv;  // in the target disk's plane
  bool fixed = true;  // false: where the walk crossed an edge (straightened later)
};

struct SegmentExit {
  int edge = -1;  // the edge opposite this corner; -1 if the segment ends inside
  double s = std::numeric_limits<double>::infinity();  // segment parameter of the crossing
};

// Where the straight segment with barycentric coordinates l0 + s * d (s in [0, 1]) first leaves
// its triangle: the barycentric coordinate that reaches 0 first, ignoring the edge it came in by
// (`entry`, -1 for none). Both walks (point location and re-tracing) step through it.
SegmentExit first_exit(const Vec3& l0, const Vec3& d, int entry) {
  SegmentExit out;
  for (int i = 0; i < 3; ++i) {
    if (i == entry || !(d[i] < 0)) continue;
    const double si = -l0[i] / d[i];
    if (si < out.s) {
      out.s = si;
      out.edge = i;
    }
  }
  return out;
}

// One polyline's walk over the target: the pieces of it inside the overlap, and where the walk is.
struct Trace {
  std::vector<std::vector<TracePoint>> pieces;
  bool open = false;          // the last piece is still being traced
  int breaks = 0;             // times the walk left the target
  bool starts_inside = false;
  int cur = -1;               // target triangle of the walk, -1 outside
  int entry = -1;             // corner of `cur` opposite the edge the walk came in through

  void append(int t, const Vec3& b, const Vec2& uv, bool fixed = true);
};

void Trace::append(int t, const Vec3& b, const Vec2& uv, bool fixed) {
  std::vector<TracePoint>& piece = pieces.back();
  // The same point again (a segment starting on an edge, or passing a vertex): keep one, in
  // the triangle of the segment that follows it (fixed if either was).
  if (!piece.empty() && (piece.back().uv - uv).norm() <= 1e-14) {
    piece.back().triangle = t;
    piece.back().barycentric = clamp_barycentric(b);
    piece.back().fixed = piece.back().fixed || fixed;
    return;
  }
  piece.push_back({t, clamp_barycentric(b), uv, fixed});
}

// A closed polyline that starts inside and is still inside at its end.
void join_loop_ends(Trace& tr) {
  auto& pieces = tr.pieces;
  if (tr.breaks == 0 && pieces.size() == 1) {
    // The whole loop survived: drop the repeated first point; the one before it now carries
    // the triangle of the closing segment.
    if (pieces[0].size() >= 2) pieces[0].pop_back();
  } else if (pieces.size() >= 2) {
    // The piece that reaches the start again continues into the first piece.
    std::vector<TracePoint> merged = std::move(pieces.back());
    pieces.pop_back();
    merged.pop_back();
    merged.insert(merged.end(), pieces[0].begin(), pieces[0].end());
    pieces[0] = std::move(merged);
  }
}

bool crosses_itself(const TriMesh& T, const std::vector<StripPoint>& strip, bool closed) {
  std::vector<SurfacePoint> line;
  for (const StripPoint& s : strip) line.push_back(s.point);
  return find_self_crossing(T, line, closed).triangle >= 0;
}

// The traced pieces of input polyline `pi` as target polylines (closed if the whole loop
// survived), each straightened through the triangles it crosses (polyline_straightening.h).
void emit_pieces(const Trace& tr, bool closed, std::size_t pi, const TriMesh& T, std::vector<TracedPolyline>& result) {
  const bool closed_out = closed && tr.starts_inside && tr.breaks == 0 && tr.pieces.size() == 1;
  for (const auto& piece : tr.pieces) {
    if (piece.size() < 2) continue;
    TracedPolyline out;
    out.closed = closed_out && piece.size() >= 3;
    if (closed_out && !out.closed) continue;
    out.input = static_cast<int>(pi);
    std::vector<StripPoint> strip;
    for (const TracePoint& q : piece) strip.push_back({{q.triangle, q.barycentric}, q.fixed});
    const std::vector<StripPoint> traced = strip;
    straighten_polyline(T, strip, out.closed);
    // A guide that goes out and back through the same triangles (along a toe and back) is pulled
    // onto one line from both sides, and the two legs can end up crossing: then the piece keeps its
    // trace as it was, which did not cross itself, rather than hand the cut a self-crossing guide.
    if (crosses_itself(T, strip, out.closed) && !crosses_itself(T, traced, out.closed)) strip = traced;
    if (strip.size() < 2 || (out.closed && strip.size() < 3)) continue;
    for (const StripPoint& s : strip) {
      out.points.push_back(s.point);
      out.positions.push_back(position_on(T, s.point));
    }
    result.push_back(std::move(out));
  }
}

}  // namespace

struct PolylineTransfer::Impl {
  MapView map;
  std::vector<std::array<int, 3>> neighbor;       // target triangle across the edge opposite corner k
  std::vector<std::array<int, 2>> boundary_edges;  // (triangle, corner opposite the boundary edge)
  // Built only if a point cannot be reached by walking (see locate): a quadtree over a squeezed
  // disk parametrization (filled eye sockets, fingers) is far more expensive than the walks.
  mutable std::once_flag locator_once;
  mutable std::unique_ptr<TriangleLocator2D> locator;

  explicit Impl(const MapView& m) : map(m) {
    const MeshTopology topo = build_topology(m.target);
    neighbor.resize(m.target.triangles.size());
    for (int t = 0; t < m.target.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) {
        const auto& et = topo.edge_triangles[topo.triangle_edges[t][k]];
        neighbor[t][k] = et[0] == t ? et[1] : et[0];
        if (neighbor[t][k] < 0) boundary_edges.push_back({t, k});
      }
  }

  Vec3 bary(int t, const Vec2& p) const {
    const Tri& tri = map.target.triangles[t];
    return barycentric_2d(p, map.target_uv[tri[0]], map.target_uv[tri[1]], map.target_uv[tri[2]]);
  }

  // The corner of triangle `t` opposite the edge it shares with `other`.
  int corner_facing(int t, int other) const {
    for (int k = 0; k < 3; ++k)
      if (neighbor[t][k] == other) return k;
    return -1;
  }

  // The target triangle containing p, the image of a point of source triangle `source_triangle`.
  // Walks in the target's disk plane from the image of one of that triangle's corners (whose
  // target triangle the map already knows) straight to p. The target's uv domain is convex (its
  // boundary vertices lie on the unit circle in order), so a walk that leaves it means p lies
  // outside. Only if no corner has an image on the target is the point located from scratch.
  PointLocation locate(const Vec2& p, int source_triangle) const {
    for (int k = 0; k < 3; ++k) {
      const int v = map.source.triangles[source_triangle][k];
      const SurfacePoint& c = map.source_to_target[v];
      if (c.triangle < 0) continue;
      const Vec2 a = map.phi[v];
      int cur = c.triangle, entry = -1;
      for (std::size_t steps = 0; steps <= 4 * neighbor.size() + 16; ++steps) {
        const Vec3 l0 = bary(cur, a), l1 = bary(cur, p);
        const SegmentExit exit = first_exit(l0, l1 - l0, entry);
        const int edge = exit.edge;
        const double s_exit = exit.s;
        if (edge < 0 || s_exit >= 1.0) {
          PointLocation out;
          out.triangle = cur;
          out.barycentric = clamp_barycentric(l1);
          return out;
        }
        const int next = neighbor[cur][edge];
        if (next < 0) return PointLocation{};  // left the (convex) target disk: outside
        entry = corner_facing(next, cur);
        cur = next;
      }
      break;  // no termination (degenerate geometry): fall back to the locator
    }
    std::call_once(locator_once,
                   [&] { locator = std::make_unique<TriangleLocator2D>(map.target_uv, map.target.triangles); });
    return locator->locate(p);
  }

  // Smallest s in [s_min, 1] where segment a->b enters the target through a boundary edge, not
  // counting `exclude` (the edge just left). Returns false if it never does.
  bool find_entry(const Vec2& a, const Vec2& b, double s_min, const std::array<int, 2>& exclude, double& s_out,
                  int& t_out, int& k_out) const {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [t, k] : boundary_edges) {
      if (t == exclude[0] && k == exclude[1]) continue;
      const Vec3 l0 = bary(t, a), l1 = bary(t, b);
      const double d = l1[k] - l0[k];
      if (!(d > 0)) continue;  // entering means the opposite corner's weight grows
      const double s = -l0[k] / d;
      if (s < s_min - 1e-12 || s > 1.0 || s >= best) continue;
      const Vec3 l = l0 + s * (l1 - l0);
      if (l.minCoeff() < -1e-9) continue;  // crosses the edge's line outside the edge
      best = s;
      t_out = t;
      k_out = k;
    }
    if (!(best <= 1.0)) return false;
    s_out = std::max(best, s_min);
    return true;
  }

  Trace start_trace(const Vec2& p0, int source_triangle) const;
  void trace_segment(const Vec2& a, const Vec2& b, std::size_t pi, Trace& tr) const;
};

// The walk's start: inside (a first piece) if the polyline's first point has an image on the target.
Trace PolylineTransfer::Impl::start_trace(const Vec2& p0, int source_triangle) const {
  Trace tr;
  const PointLocation loc = locate(p0, source_triangle);
  if (loc.triangle >= 0) {
    tr.pieces.emplace_back();
    tr.open = true;
    tr.starts_inside = true;
    tr.cur = loc.triangle;
    tr.append(tr.cur, loc.barycentric, p0);
  }
  return tr;
}

// Walks the segment a -> b (of polyline `pi`) over the target, triangle by triangle: a piece
// ends where the walk leaves the target disk and a new one starts where it enters again.
void PolylineTransfer::Impl::trace_segment(const Vec2& a, const Vec2& b, std::size_t pi, Trace& tr) const {
  const std::size_t step_cap = 4 * map.target.triangles.size() + 16;
  if ((b - a).norm() <= 1e-15) return;
  int& cur = tr.cur;
  int& entry = tr.entry;
  double s = 0;
  std::array<int, 2> left_edge{-1, -1};
  std::size_t steps = 0;
  while (true) {
    require(++steps <= step_cap, MCON_ERROR_NUMERICAL,
            "polyline " + std::to_string(pi) + ": the walk over the target did not terminate");
    if (cur < 0) {
      double se = 0;
      int t = -1, kk = -1;
      if (!find_entry(a, b, s, left_edge, se, t, kk)) break;  // this segment stays outside
      tr.pieces.emplace_back();
      tr.open = true;
      cur = t;
      entry = kk;
      s = se;
      const Vec2 x = a + s * (b - a);
      tr.append(cur, bary(cur, x), x);
      continue;
    }
    const Vec3 l0 = bary(cur, a), l1 = bary(cur, b), d = l1 - l0;
    const SegmentExit exit = first_exit(l0, d, entry);
    const int edge = exit.edge;
    double s_exit = exit.s;
    if (edge < 0 || s_exit >= 1.0) {  // b lies in this triangle
      tr.append(cur, l1, b);
      entry = -1;
      break;
    }
    s_exit = std::max(s_exit, s);
    const Vec2 x = a + s_exit * (b - a);
    const int next = neighbor[cur][edge];
    if (next < 0) {  // leaving the target disk: the rest of this piece is outside the overlap
      tr.append(cur, l0 + s_exit * d, x);
      tr.open = false;
      ++tr.breaks;
      left_edge = {cur, edge};
      cur = -1;
      entry = -1;
      // Re-enter only strictly later: a segment grazing a boundary vertex could otherwise
      // "enter" through the other boundary edge at the same point and circle the vertex.
      s = s_exit + 1e-9;
      continue;
    }
    entry = corner_facing(next, cur);
    cur = next;
    s = s_exit;
    // On the shared edge exactly (the weight of the corner facing it is 0), free to slide along it.
    Vec3 on_edge = bary(cur, x);
    on_edge[entry] = 0.0;
    tr.append(cur, on_edge, x, false);
  }
}

PolylineTransfer::PolylineTransfer(const MapView& map) {
  check_map_view(map);
  impl_ = new Impl(map);
}

PolylineTransfer::~PolylineTransfer() { delete impl_; }

Vec2 PolylineTransfer::phi_of(const SurfacePoint& p) const {
  const MapView& m = impl_->map;
  const Vec3 b = checked_barycentric(p.triangle, p.barycentric, m.source.num_triangles(), "source point");
  const Tri& t = m.source.triangles[p.triangle];
  // phi is affine on each source triangle: the point keeps its barycentric coordinates (Fig. 4.3).
  return b[0] * m.phi[t[0]] + b[1] * m.phi[t[1]] + b[2] * m.phi[t[2]];
}

SurfacePoint PolylineTransfer::map_point(const SurfacePoint& p) const {
  const PointLocation loc = impl_->locate(phi_of(p), p.triangle);
  SurfacePoint out;
  if (loc.triangle >= 0) {
    out.triangle = loc.triangle;
    out.barycentric = loc.barycentric;
  }
  return out;
}

std::vector<TracedPolyline> PolylineTransfer::map_polylines(const std::vector<PolylineInput>& inputs) const {
  const Impl& I = *impl_;
  std::vector<TracedPolyline> result;
  for (std::size_t pi = 0; pi < inputs.size(); ++pi) {
    const PolylineInput& in = inputs[pi];
    require(in.points.size() >= 2, MCON_ERROR_INVALID_ARGUMENT,
            "polyline " + std::to_string(pi) + " has " + std::to_string(in.points.size()) + " points (at least 2)");
    std::vector<Vec2> p;
    p.reserve(in.points.size() + 1);
    for (const SurfacePoint& q : in.points) p.push_back(phi_of(q));
    if (in.closed) p.push_back(p.front());

    Trace tr = I.start_trace(p[0], in.points[0].triangle);
    for (std::size_t k = 0; k + 1 < p.size(); ++k) I.trace_segment(p[k], p[k + 1], pi, tr);
    if (in.closed && tr.starts_inside && tr.open) join_loop_ends(tr);
    emit_pieces(tr, in.closed, pi, I.map.target, result);
  }
  return result;
}

}  // namespace mcon
