#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/counter_rng.h"
#include "base/error.h"
#include "mesh/point_location_2d.h"
#include "synthetic_maps.h"

using namespace mcon;

namespace {

struct Planar {
  std::vector<Vec2> points;
  std::vector<Tri> triangles;
};

Planar jittered_disk() {
  const TriMesh m = synthetic::make_jittered_disk(9, 0.4);
  return {synthetic::planar_uv(m), m.triangles};
}

// Brute force: the smallest barycentric coordinate of p in triangle t.
double min_bary(const Planar& d, int t, const Vec2& p) {
  const Tri& tri = d.triangles[t];
  return barycentric_2d(p, d.points[tri[0]], d.points[tri[1]], d.points[tri[2]]).minCoeff();
}

Vec2 interpolate(const Planar& d, const PointLocation& loc) {
  const Tri& tri = d.triangles[loc.triangle];
  return loc.barycentric[0] * d.points[tri[0]] + loc.barycentric[1] * d.points[tri[1]] +
         loc.barycentric[2] * d.points[tri[2]];
}

}  // namespace

TEST(PointLocation2D, RandomPointsMatchBruteForce) {
  const Planar d = jittered_disk();
  const TriangleLocator2D locator(d.points, d.triangles);
  CounterRng rng(3, 0);
  int inside = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec2 p(2.4 * rng.uniform() - 1.2, 2.4 * rng.uniform() - 1.2);
    const PointLocation loc = locator.locate(p);
    double best = -std::numeric_limits<double>::infinity();
    for (int t = 0; t < static_cast<int>(d.triangles.size()); ++t) best = std::max(best, min_bary(d, t, p));
    if (best >= 1e-9) {
      ASSERT_GE(loc.triangle, 0) << "missed point " << p.transpose();
      EXPECT_NEAR(min_bary(d, loc.triangle, p), best, 1e-12);
      EXPECT_LT((interpolate(d, loc) - p).norm(), 1e-12);
      EXPECT_NEAR(loc.barycentric.sum(), 1.0, 1e-14);
      EXPECT_GE(loc.barycentric.minCoeff(), 0.0);
      ++inside;
    } else if (best < -1e-9) {
      EXPECT_EQ(loc.triangle, -1) << "false hit at " << p.transpose();
    }
  }
  EXPECT_GT(inside, 1500);
}

TEST(PointLocation2D, VerticesAndEdgeMidpointsAreFound) {
  const Planar d = jittered_disk();
  const TriangleLocator2D locator(d.points, d.triangles);
  for (const Tri& tri : d.triangles)
    for (int i = 0; i < 3; ++i) {
      for (const Vec2& p : {d.points[tri[i]], Vec2(0.5 * (d.points[tri[i]] + d.points[tri[(i + 1) % 3]]))}) {
        const PointLocation loc = locator.locate(p);
        ASSERT_GE(loc.triangle, 0);
        EXPECT_GE(loc.barycentric.minCoeff(), 0.0);
        EXPECT_LT((interpolate(d, loc) - p).norm(), 1e-12);
      }
    }
}

TEST(PointLocation2D, NearestOutsideMatchesBruteForce) {
  const Planar d = jittered_disk();
  const TriangleLocator2D locator(d.points, d.triangles);
  CounterRng rng(5, 0);
  for (int i = 0; i < 300; ++i) {
    const double a = 6.283185307179586 * rng.uniform(), r = 1.0 + 0.8 * rng.uniform();
    const Vec2 p(r * std::cos(a), r * std::sin(a));
    EXPECT_EQ(locator.locate(p).triangle, -1);
    const PointLocation loc = locator.locate_nearest(p, 10.0);
    ASSERT_GE(loc.triangle, 0);
    // Brute-force distance to the triangulation: closest boundary edge point.
    double best = std::numeric_limits<double>::infinity();
    for (const Tri& tri : d.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec2 a0 = d.points[tri[k]], a1 = d.points[tri[(k + 1) % 3]];
        const double t = std::clamp((p - a0).dot(a1 - a0) / (a1 - a0).squaredNorm(), 0.0, 1.0);
        best = std::min(best, (a0 + t * (a1 - a0) - p).norm());
      }
    EXPECT_NEAR(loc.distance, best, 1e-12);
    EXPECT_NEAR((interpolate(d, loc) - p).norm(), best, 1e-12);
  }
  // Beyond max_distance: nothing.
  EXPECT_EQ(locator.locate_nearest(Vec2(5, 0), 1.0).triangle, -1);
}

TEST(PointLocation2D, RejectsBadInput) {
  EXPECT_THROW(TriangleLocator2D({Vec2(0, 0)}, {}), Error);
  try {
    TriangleLocator2D({Vec2(0, 0), Vec2(1, 0)}, {Tri{0, 1, 2}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_INDEX_OUT_OF_RANGE);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  try {
    TriangleLocator2D({Vec2(0, 0), Vec2(1, 0), Vec2(nan, 1)}, {Tri{0, 1, 2}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_NON_FINITE);
  }
  const TriangleLocator2D ok({Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, {Tri{0, 1, 2}});
  EXPECT_EQ(ok.locate(Vec2(nan, 0)).triangle, -1);
}

// A disk squeezed toward its center (as disk parametrizations squeeze fingers or an eye socket):
// a dense cluster under the boxes of long triangles, which the tree keeps at inner nodes instead
// of copying them into every leaf below. Queries concentrated in the cluster must still find the
// deepest containing triangle, with the lowest index among ties.
TEST(PointLocation2D, SqueezedClusterMatchesBruteForce) {
  Planar d = jittered_disk();
  for (Vec2& p : d.points) p *= std::pow(p.norm(), 5.0);
  const TriangleLocator2D locator(d.points, d.triangles);
  CounterRng rng(5, 0);
  int inside = 0;
  for (int i = 0; i < 3000; ++i) {
    const double r = std::pow(rng.uniform(), 4.0), a = 6.283185307179586 * rng.uniform();
    const Vec2 p(r * std::cos(a), r * std::sin(a));
    const PointLocation loc = locator.locate(p);
    double best = -std::numeric_limits<double>::infinity();
    int best_t = -1;
    for (int t = 0; t < static_cast<int>(d.triangles.size()); ++t) {
      const double m = min_bary(d, t, p);
      if (m > best) {
        best = m;
        best_t = t;
      }
    }
    if (best >= 1e-9) {
      ASSERT_GE(loc.triangle, 0) << "missed point " << p.transpose();
      EXPECT_NEAR(min_bary(d, loc.triangle, p), best, 1e-12);
      if (min_bary(d, loc.triangle, p) == best) {
        EXPECT_LE(loc.triangle, best_t);
      }
      ++inside;
    } else if (best < -1e-9) {
      EXPECT_EQ(loc.triangle, -1) << "false hit at " << p.transpose();
    }
  }
  EXPECT_GT(inside, 2000);
}

// locate's rule by brute force: inside the triangle's box, the deepest smallest barycentric
// coordinate above -1e-10, ties to the lowest index.
int brute_force_locate(const Planar& d, const Vec2& p) {
  double best_min = -1e-10;
  int best = -1;
  for (int t = 0; t < static_cast<int>(d.triangles.size()); ++t) {
    const Tri& tri = d.triangles[t];
    const Vec2 lo = d.points[tri[0]].cwiseMin(d.points[tri[1]]).cwiseMin(d.points[tri[2]]);
    const Vec2 hi = d.points[tri[0]].cwiseMax(d.points[tri[1]]).cwiseMax(d.points[tri[2]]);
    if (p.x() < lo.x() || p.y() < lo.y() || p.x() > hi.x() || p.y() > hi.y()) continue;
    const double m = min_bary(d, t, p);
    if (m > best_min || (m >= best_min && best < 0)) {
      best_min = m;
      best = t;
    }
  }
  return best;
}

// The tree keeps a triangle only in the cells it meets (not every cell its box meets), so on
// slivers the borderline points are the risk: on edges, on vertices, and a hair (1e-11 of the
// edge) to either side, within locate's tolerance or just beyond it, the answer must be
// exactly the brute force's.
TEST(PointLocation2D, SliverEdgesMatchBruteForceExactly) {
  Planar d = jittered_disk();
  for (Vec2& p : d.points) {
    p *= std::pow(p.norm(), 5.0);
    p = Vec2(40 * p.x() + 3 * p.y(), p.y());  // sheared: long thin triangles at every angle
  }
  const TriangleLocator2D locator(d.points, d.triangles);
  CounterRng rng(21, 0);
  int hits = 0, checked = 0;
  for (std::size_t t = 0; t < d.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec2 a = d.points[d.triangles[t][k]], b = d.points[d.triangles[t][(k + 1) % 3]];
      const Vec2 e = b - a, normal(-e.y(), e.x());
      const double s = rng.uniform();
      for (const Vec2& p : {a, Vec2(a + s * e), Vec2(a + s * e + 1e-11 * normal), Vec2(a + s * e - 1e-11 * normal),
                            Vec2(a + s * e + 1e-9 * normal), Vec2(a + s * e - 1e-9 * normal)}) {
        const int expected = brute_force_locate(d, p);
        const PointLocation loc = locator.locate(p);
        ASSERT_EQ(loc.triangle, expected) << "point " << p.transpose() << " on an edge of triangle " << t;
        hits += expected >= 0;
        ++checked;
      }
    }
  EXPECT_GT(hits, checked / 2);
}

// A walk from a hint must give exactly what the full search gives: same triangle, same
// barycentric coordinates bit for bit, whatever the hint (a neighbour's answer, a random
// triangle, -1, out of range), inside, on edges and outside.
void expect_hinted_equals_full(const Planar& d, std::uint64_t seed) {
  const TriangleLocator2D locator(d.points, d.triangles);
  ASSERT_TRUE(locator.is_embedding());
  CounterRng rng(seed, 0);
  const int nt = static_cast<int>(d.triangles.size());
  int previous = -1;
  for (int i = 0; i < 3000; ++i) {
    Vec2 p(2.4 * rng.uniform() - 1.2, 2.4 * rng.uniform() - 1.2);
    if (i % 5 == 0) p = d.points[d.triangles[i % nt][0]];  // on a vertex
    const int kind = i % 4;
    const int hint = kind == 0 ? previous : kind == 1 ? static_cast<int>(rng.uniform() * nt) : kind == 2 ? -1 : nt + 3;
    const PointLocation full = locator.locate(p), hinted = locator.locate(p, hint);
    ASSERT_EQ(hinted.triangle, full.triangle) << "point " << p.transpose() << " hint " << hint;
    EXPECT_EQ(hinted.barycentric, full.barycentric);
    EXPECT_EQ(hinted.distance, full.distance);
    const PointLocation near_full = locator.locate_nearest(p, 2.0), near_hinted = locator.locate_nearest(p, 2.0, hint);
    ASSERT_EQ(near_hinted.triangle, near_full.triangle);
    EXPECT_EQ(near_hinted.barycentric, near_full.barycentric);
    EXPECT_EQ(near_hinted.distance, near_full.distance);
    if (full.triangle >= 0) previous = full.triangle;
  }
}

TEST(PointLocation2D, HintedLocateEqualsTheFullSearch) {
  expect_hinted_equals_full(jittered_disk(), 11);
  Planar squeezed = jittered_disk();
  for (Vec2& p : squeezed.points) p *= std::pow(p.norm(), 5.0);
  expect_hinted_equals_full(squeezed, 12);
}

// Only an embedding may take the walk's answer; anything that can cover a point twice is seen.
TEST(PointLocation2D, EmbeddingIsDetected) {
  const Planar d = jittered_disk();
  EXPECT_TRUE(TriangleLocator2D(d.points, d.triangles).is_embedding());
  Planar reversed = d;  // both orientations but still an embedding as a set: not accepted (no walk)
  std::swap(reversed.triangles[5][0], reversed.triangles[5][1]);
  EXPECT_FALSE(TriangleLocator2D(reversed.points, reversed.triangles).is_embedding());
  Planar folded = d;  // an interior vertex pulled across its ring: flipped triangles
  const int inner = d.triangles[d.triangles.size() / 2][0];
  folded.points[inner] = Vec2(5, 5);
  EXPECT_FALSE(TriangleLocator2D(folded.points, folded.triangles).is_embedding());
  Planar twice = d;  // the same disk twice: two rim loops over each other
  const int nv = static_cast<int>(d.points.size());
  for (const Tri& t : d.triangles) twice.triangles.push_back({t[0] + nv, t[1] + nv, t[2] + nv});
  twice.points.insert(twice.points.end(), d.points.begin(), d.points.end());
  EXPECT_FALSE(TriangleLocator2D(twice.points, twice.triangles).is_embedding());
  Planar stacked = d;  // a triangle repeated: an edge with three triangles
  stacked.triangles.push_back(d.triangles[7]);
  EXPECT_FALSE(TriangleLocator2D(stacked.points, stacked.triangles).is_embedding());
  // A square whose two triangles overlap through a crossing rim (a bow tie): rejected.
  const std::vector<Vec2> bow = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1)};
  EXPECT_FALSE(TriangleLocator2D(bow, {{0, 1, 3}, {0, 3, 2}, {1, 2, 0}}).is_embedding());
  // Without an embedding the hinted call still answers exactly as the full search.
  const TriangleLocator2D locator(twice.points, twice.triangles);
  CounterRng rng(13, 0);
  for (int i = 0; i < 500; ++i) {
    const Vec2 p(2 * rng.uniform() - 1, 2 * rng.uniform() - 1);
    const PointLocation full = locator.locate(p), hinted = locator.locate(p, i % static_cast<int>(twice.triangles.size()));
    EXPECT_EQ(hinted.triangle, full.triangle);
    EXPECT_EQ(hinted.barycentric, full.barycentric);
  }
}
