// Polyline and point transfer on synthetic disks with a known phi: re-traced polylines lie on the
// target (every segment inside one target triangle), follow the mapped straight segments, and
// lose exactly the parts outside the overlap.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "known_maps.h"
#include "transfer/polyline_transfer.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

constexpr double kPi = 3.141592653589793;

double height(double x, double y) { return 0.3 * std::sin(1.7 * x + 0.4) * std::cos(1.3 * y) + 0.2 * x * y; }

PolylineInput polyline_through(const known::KnownMap& m, const std::vector<Vec2>& uv, bool closed) {
  PolylineInput in;
  in.closed = closed;
  for (const Vec2& p : uv) {
    const known::SourcePoint s = known::source_point(m, p);
    EXPECT_GE(s.triangle, 0);
    in.points.push_back({s.triangle, s.barycentric});
  }
  return in;
}

std::vector<Vec2> circle(const Vec2& c, double r, int n, double start = 0) {
  std::vector<Vec2> out;
  for (int i = 0; i < n; ++i) {
    const double a = start + 2 * kPi * i / n;
    out.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  }
  return out;
}

Vec2 uv_of(const known::KnownMap& m, const SurfacePoint& p) {
  const Tri& t = m.target.triangles[p.triangle];
  return p.barycentric[0] * m.target_uv[t[0]] + p.barycentric[1] * m.target_uv[t[1]] + p.barycentric[2] * m.target_uv[t[2]];
}

// Barycentric coordinates of a 3D point in the plane of target triangle t, and its distance from
// that plane.
Vec3 bary3(const TriMesh& mesh, int t, const Vec3& x, double& off_plane) {
  const Tri& tri = mesh.triangles[t];
  const Vec3 a = mesh.positions[tri[0]], e1 = mesh.positions[tri[1]] - a, e2 = mesh.positions[tri[2]] - a;
  const Vec3 n = e1.cross(e2).normalized();
  off_plane = std::abs((x - a).dot(n));
  const Vec3 p = x - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), p1 = p.dot(e1), p2 = p.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double u = (d22 * p1 - d12 * p2) / det, v = (d11 * p2 - d12 * p1) / det;
  return Vec3(1 - u - v, u, v);
}

// Every segment (i, i+1) of a traced polyline lies in the triangle of point i: both ends are on
// that triangle (inside it, in its plane). Points are on the target surface.
void expect_on_surface(const known::KnownMap& m, const TracedPolyline& p) {
  ASSERT_EQ(p.points.size(), p.positions.size());
  const std::size_t n = p.points.size();
  const std::size_t segments = p.closed ? n : n - 1;
  for (std::size_t i = 0; i < n; ++i) {
    double off = 0;
    const Vec3 b = bary3(m.target, p.points[i].triangle, p.positions[i], off);
    EXPECT_LE(off, 1e-12) << i;
    EXPECT_GE(b.minCoeff(), -1e-9) << i;
  }
  for (std::size_t i = 0; i < segments; ++i) {
    const std::size_t j = (i + 1) % n;
    double off = 0;
    const Vec3 b = bary3(m.target, p.points[i].triangle, p.positions[j], off);
    EXPECT_LE(off, 1e-9) << "segment " << i;
    EXPECT_GE(b.minCoeff(), -1e-7) << "segment " << i << " leaves triangle " << p.points[i].triangle;
  }
}

// The distance of q from the polygonal path through `path` (closed or not).
double distance_to_path(const Vec2& q, const std::vector<Vec2>& path, bool closed) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = path.size(), segments = closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec2 a = path[i], b = path[(i + 1) % n];
    const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - q).norm());
  }
  return best;
}

}  // namespace

TEST(PolylineTransfer, ClosedLoopInsideIsRetracedOnTheCurvedTarget) {
  const auto psi = known::similarity(0.6, 0.75, Vec2(0.05, 0.02));
  const known::KnownMap m = known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(9, 0.35), psi, height);
  const std::vector<Vec2> loop = circle(Vec2(0.1, -0.05), 0.55, 37);
  const PolylineTransfer transfer(m.view());
  const std::vector<TracedPolyline> out = transfer.map_polylines({polyline_through(m, loop, true)});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].closed);
  EXPECT_EQ(out[0].input, 0);
  EXPECT_GT(out[0].points.size(), 2 * loop.size());  // split at the target's edges
  expect_on_surface(m, out[0]);
  std::vector<Vec2> mapped;
  for (const Vec2& p : loop) mapped.push_back(psi(p));
  // Straightened on the curved surface, the trace leaves the straight uv segments only slightly
  // (measured 2.3e-4 at most; the mapped points themselves stay exactly).
  for (const SurfacePoint& p : out[0].points) EXPECT_LE(distance_to_path(uv_of(m, p), mapped, true), 2e-3);
  // Every mapped input point is among the output points.
  for (const Vec2& q : mapped) {
    double best = 1e9;
    for (const SurfacePoint& p : out[0].points) best = std::min(best, (uv_of(m, p) - q).norm());
    EXPECT_LE(best, 1e-9);
  }
}

TEST(PolylineTransfer, TheTraceIsStraightOnTheSurfaceWhereTheParametrizationIsWarped) {
  // A flat target whose disk parametrization is warped (radially squeezed and twisted, the rim
  // kept on the circle): a straight line in that parametrization is a curve on the surface, and
  // at every edge it crosses the Jacobian jumps. The trace is the shortest path through the
  // triangles that line crosses: straight wherever it does not wrap around a vertex of them.
  known::KnownMap m = known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(9, 0.35),
                                  [](const Vec2& p) { return p; });
  for (std::size_t v = 0; v < m.target_uv.size(); ++v) {
    const Vec2 p = m.target.positions[v].head<2>();
    const double r2 = p.squaredNorm(), a = 0.6 * (1 - r2), c = std::cos(a), s = std::sin(a);
    const Vec2 q = (0.6 + 0.4 * r2) * p;
    m.target_uv[v] = Vec2(c * q.x() - s * q.y(), s * q.x() + c * q.y());
  }
  m.c = locate_correspondences(m.source, m.phi, m.target, m.target_uv);
  const Vec2 from(-0.45, -0.3), to(0.4, 0.35);
  const PolylineTransfer transfer(m.view());
  const std::vector<TracedPolyline> out = transfer.map_polylines({polyline_through(m, {from, to}, false)});
  ASSERT_EQ(out.size(), 1u);
  expect_on_surface(m, out[0]);
  const std::vector<Vec3>& x = out[0].positions;
  ASSERT_GT(x.size(), 6u);  // it crossed edges
  // Straight through every crossing that is not at a vertex (the target is flat: no unfolding).
  int straight = 0;
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    const Vec3& w = out[0].points[i].barycentric;
    if ((w.array() == 0.0).count() != 1) continue;
    // sin of the turn; the sweeps stop at a parameter change of 1e-12
    EXPECT_LE((x[i] - x[i - 1]).normalized().cross((x[i + 1] - x[i]).normalized()).norm(), 1e-7) << i;
    ++straight;
  }
  EXPECT_GT(straight, 6);
  // Shorter than the straight line of the parametrization lifted to the surface, and near the chord.
  const TriangleLocator2D locate(m.target_uv, m.target.triangles);
  double lifted = 0, traced = 0;
  Vec3 previous = x.front();
  for (int k = 1; k <= 2000; ++k) {
    const PointLocation l = locate.locate(from + (to - from) * (k / 2000.0));
    ASSERT_GE(l.triangle, 0);
    const Tri& t = m.target.triangles[l.triangle];
    Vec3 y = Vec3::Zero();
    for (int c = 0; c < 3; ++c) y += l.barycentric[c] * m.target.positions[t[c]];
    lifted += (y - previous).norm();
    previous = y;
  }
  for (std::size_t i = 0; i + 1 < x.size(); ++i) traced += (x[i + 1] - x[i]).norm();
  const double chord = (x.back() - x.front()).norm();
  EXPECT_LT(traced - chord, 0.5 * (lifted - chord));
  EXPECT_GT(lifted - chord, 1e-3 * chord);  // the warp is not negligible
}

TEST(PolylineTransfer, PartsOutsideTheOverlapAreDropped) {
  // phi shifts the source disk right by 0.8: everything beyond the target's rim disappears.
  const known::KnownMap m = known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(8, 0.3),
                                        known::similarity(0.0, 1.0, Vec2(0.8, 0.0)), height);
  const PolylineTransfer transfer(m.view());
  {
    const std::vector<TracedPolyline> out = transfer.map_polylines({polyline_through(m, {{-0.9, 0.01}, {0.9, 0.01}}, false)});
    ASSERT_EQ(out.size(), 1u);
    expect_on_surface(m, out[0]);
    EXPECT_FALSE(out[0].closed);
    EXPECT_NEAR(uv_of(m, out[0].points.front()).x(), -0.1, 1e-9);
    const Vec2 last = uv_of(m, out[0].points.back());
    EXPECT_GT(last.norm(), 0.98);  // ends on the target's boundary polygon
    for (const SurfacePoint& p : out[0].points) EXPECT_LE(uv_of(m, p).norm(), 1.0 + 1e-9);
  }
  {
    // A closed loop around (0.7 + 0.8, 0) ... partly outside: one open piece (the two ends of the
    // cut loop join through the start), from input 0.
    const std::vector<Vec2> loop = circle(Vec2(-0.1, 0.0), 0.5, 40, kPi);
    const std::vector<TracedPolyline> out = transfer.map_polylines({polyline_through(m, loop, true)});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_FALSE(out[0].closed);
    EXPECT_EQ(out[0].input, 0);
    expect_on_surface(m, out[0]);
    EXPECT_GT(uv_of(m, out[0].points.front()).norm(), 0.98);
    EXPECT_GT(uv_of(m, out[0].points.back()).norm(), 0.98);
  }
  {
    // Entirely outside: nothing.
    const std::vector<TracedPolyline> out = transfer.map_polylines({polyline_through(m, {{0.5, 0.1}, {0.9, 0.1}}, false)});
    EXPECT_TRUE(out.empty());
  }
}

TEST(PolylineTransfer, APolylineThatLeavesAndReturnsGivesTwoPieces) {
  const known::KnownMap m = known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(8, 0.3),
                                        known::similarity(0.0, 1.5, Vec2::Zero()));
  const PolylineTransfer transfer(m.view());
  const std::vector<PolylineInput> in = {polyline_through(m, {{-0.5, 0.2}, {0.0, 0.9}, {0.5, 0.2}}, false),
                                         polyline_through(m, {{-0.2, -0.2}, {0.2, -0.25}}, false)};
  const std::vector<TracedPolyline> out = transfer.map_polylines(in);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].input, 0);
  EXPECT_EQ(out[1].input, 0);
  EXPECT_EQ(out[2].input, 1);
  for (const TracedPolyline& p : out) expect_on_surface(m, p);
  EXPECT_NEAR(uv_of(m, out[0].points.front()).x(), -0.75, 1e-9);
  EXPECT_NEAR(uv_of(m, out[1].points.back()).x(), 0.75, 1e-9);
}

TEST(PolylineTransfer, PointsKeepTheirPlaceInPhi) {
  const auto psi = known::similarity(-1.1, 0.9, Vec2(0.2, 0.1), true);
  const known::KnownMap m = known::make(test_meshes::make_disk(5), synthetic::make_jittered_disk(8, 0.3), psi);
  const PolylineTransfer transfer(m.view());
  for (const Vec2& q : {Vec2(0.1, 0.2), Vec2(-0.4, 0.3), Vec2(0.0, -0.6), Vec2(0.33, 0.0)}) {
    const known::SourcePoint s = known::source_point(m, q);
    const SurfacePoint t = transfer.map_point({s.triangle, s.barycentric});
    ASSERT_GE(t.triangle, 0);
    EXPECT_LE((uv_of(m, t) - psi(q)).norm(), 1e-12);
    EXPECT_GE(t.barycentric.minCoeff(), 0.0);
    EXPECT_NEAR(t.barycentric.sum(), 1.0, 1e-12);
  }
  // The source point near the rim that phi pushes farthest out lands outside the target.
  Vec2 far_q = Vec2::Zero();
  for (const Vec2& q : circle(Vec2::Zero(), 0.95, 72))
    if (psi(q).norm() > psi(far_q).norm()) far_q = q;
  ASSERT_GT(psi(far_q).norm(), 1.02);
  const known::SourcePoint far = known::source_point(m, far_q);
  EXPECT_LT(transfer.map_point({far.triangle, far.barycentric}).triangle, 0);
}

TEST(PolylineTransfer, BadInputIsRejected) {
  const known::KnownMap m = known::make(test_meshes::make_disk(3), test_meshes::make_disk(3), [](const Vec2& p) { return p; });
  const PolylineTransfer transfer(m.view());
  EXPECT_EQ(status_of([&] { transfer.map_point({-1, Vec3(1, 0, 0)}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { transfer.map_point({m.source.num_triangles(), Vec3(1, 0, 0)}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { transfer.map_point({0, Vec3(0.7, 0.7, 0.7)}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { transfer.map_point({0, Vec3(1.5, -0.5, 0)}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { transfer.map_point({0, Vec3(std::nan(""), 0, 1)}); }), MCON_ERROR_NON_FINITE);
  PolylineInput one;
  one.points = {{0, Vec3(1, 0, 0)}};
  EXPECT_EQ(status_of([&] { transfer.map_polylines({one}); }), MCON_ERROR_INVALID_ARGUMENT);
}
