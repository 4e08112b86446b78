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
