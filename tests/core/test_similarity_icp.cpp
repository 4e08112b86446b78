#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <tbb/task_arena.h>

#include "base/error.h"
#include "map/similarity_icp.h"
#include "mesh/closest_point_3d.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

Eigen::Matrix3d rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

SimilarityTransform3D known_transform() {
  SimilarityTransform3D T;
  T.rotation = rotation(0.35, Vec3(0.3, -0.5, 1.0));
  T.scale = 2.5;
  T.translation = Vec3(4.0, -1.5, 7.0);
  return T;
}

// Brute force over every triangle: the reference for the tree.
ClosestSurfacePoint brute_force(const TriMesh& m, const Vec3& p) {
  ClosestSurfacePoint best;
  best.squared_distance = std::numeric_limits<double>::infinity();
  for (int t = 0; t < m.num_triangles(); ++t) {
    Vec3 bary;
    const Vec3 q = closest_point_on_triangle(p, m.positions[m.triangles[t][0]], m.positions[m.triangles[t][1]],
                                             m.positions[m.triangles[t][2]], bary);
    if ((q - p).squaredNorm() < best.squared_distance) best = {{t, bary}, q, (q - p).squaredNorm()};
  }
  return best;
}

}  // namespace

TEST(ClosestPoint3D, EachVoronoiRegionOfATriangle) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  Vec3 bary;
  // Above the face: the orthogonal projection.
  EXPECT_TRUE(closest_point_on_triangle(Vec3(0.5, 0.5, 3), a, b, c, bary).isApprox(Vec3(0.5, 0.5, 0)));
  EXPECT_TRUE(bary.isApprox(Vec3(0.5, 0.25, 0.25)));
  // Beyond a vertex, beyond an edge (the hypotenuse), beyond another edge.
  EXPECT_TRUE(closest_point_on_triangle(Vec3(-1, -1, 1), a, b, c, bary).isApprox(a));
  EXPECT_TRUE(bary.isApprox(Vec3(1, 0, 0)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(3, 3, -1), a, b, c, bary).isApprox(Vec3(1, 1, 0)));
  EXPECT_TRUE(bary.isApprox(Vec3(0, 0.5, 0.5)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(1.5, -2, 0), a, b, c, bary).isApprox(Vec3(1.5, 0, 0)));
  EXPECT_TRUE(bary.isApprox(Vec3(0.25, 0.75, 0)));
  EXPECT_TRUE(closest_point_on_triangle(Vec3(5, -1, 0), a, b, c, bary).isApprox(b));
}

TEST(ClosestPoint3D, TreeMatchesBruteForce) {
  const TriMesh m = test_meshes::make_bumpy_grid(21);
  const TriangleTree3D tree(m);
  unsigned state = 7u;
  auto rnd = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24) * 3.0 - 1.5;
  };
  for (int k = 0; k < 500; ++k) {
    const Vec3 p(rnd(), rnd(), rnd());
    const ClosestSurfacePoint got = tree.closest(p), want = brute_force(m, p);
    ASSERT_NEAR(got.squared_distance, want.squared_distance, 1e-14) << k;
    const Tri& t = m.triangles[got.point.triangle];
    const Vec3 q = got.point.barycentric[0] * m.positions[t[0]] + got.point.barycentric[1] * m.positions[t[1]] +
                   got.point.barycentric[2] * m.positions[t[2]];
    ASSERT_LT((q - got.position).norm(), 1e-12);
  }
}

TEST(SimilarityIcp, WeightedUmeyamaIsExactOnASimilarity) {
  const TriMesh m = test_meshes::make_bumpy_grid(9);
  const SimilarityTransform3D T = known_transform();
  std::vector<Vec3> y;
  std::vector<double> w;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    y.push_back(T.apply(m.positions[i]));
    w.push_back(1.0 + static_cast<double>(i % 5));
  }
  const SimilarityTransform3D got = weighted_similarity(m.positions, y, w);
  EXPECT_NEAR(got.scale, 2.5, 1e-12);
  EXPECT_LT((got.rotation - T.rotation).norm(), 1e-12);
  EXPECT_LT((got.translation - T.translation).norm(), 1e-11);
  EXPECT_NEAR(got.rotation.determinant(), 1.0, 1e-12);
}

// A known similarity of a bumpy patch is recovered from the ICP start (centroids matched,
// area-ratio scale, identity rotation), and every source vertex lands on its own image.
TEST(SimilarityIcp, RecoversAKnownSimilarity) {
  const TriMesh source = test_meshes::make_bumpy_grid(17);
  TriMesh target = source;
  const SimilarityTransform3D T = known_transform();
  for (Vec3& p : target.positions) p = T.apply(p);
  SimilarityIcpOptions o;  // point-to-point ICP converges linearly: run it to the end
  o.max_iterations = 5000;
  o.relative_tolerance = 1e-10;
  const SimilarityIcpResult r = similarity_icp(source, target, o);
  EXPECT_NEAR(r.transform.scale, 2.5, 1e-6);
  EXPECT_LT((r.transform.rotation - T.rotation).norm(), 1e-6);
  EXPECT_LT((r.transform.translation - T.translation).norm(), 1e-5);
  EXPECT_LT(r.rms_distance, 1e-6);
  EXPECT_GT(r.iterations, 1);
  EXPECT_LT(r.iterations, o.max_iterations);  // stopped by the tolerance
  int on_own_image = 0;
  for (int v = 0; v < source.num_vertices(); ++v) {
    const Tri& t = target.triangles[r.closest[v].triangle];
    const Vec3 q = r.closest[v].barycentric[0] * target.positions[t[0]] +
                   r.closest[v].barycentric[1] * target.positions[t[1]] +
                   r.closest[v].barycentric[2] * target.positions[t[2]];
    on_own_image += (q - target.positions[v]).norm() < 1e-5;
  }
  EXPECT_EQ(on_own_image, source.num_vertices());
}

TEST(SimilarityIcp, BitIdenticalForAnyThreadCount) {
  const TriMesh source = test_meshes::make_bumpy_grid(31);
  TriMesh target = test_meshes::make_bumpy_grid(23);
  for (Vec3& p : target.positions) p = known_transform().apply(p);
  SimilarityIcpResult one, four;
  tbb::task_arena(1).execute([&] { one = similarity_icp(source, target); });
  tbb::task_arena(4).execute([&] { four = similarity_icp(source, target); });
  EXPECT_EQ(one.iterations, four.iterations);
  EXPECT_EQ(one.rms_distance, four.rms_distance);
  EXPECT_TRUE(one.transform.rotation == four.transform.rotation);
  for (std::size_t v = 0; v < one.closest.size(); ++v) {
    ASSERT_EQ(one.closest[v].triangle, four.closest[v].triangle);
    ASSERT_TRUE(one.closest[v].barycentric == four.closest[v].barycentric);
  }
}

TEST(SimilarityIcp, RejectsBadInput) {
  const TriMesh m = test_meshes::make_bumpy_grid(5);
  SimilarityIcpOptions o;
  o.max_iterations = -1;
  EXPECT_THROW(similarity_icp(m, m, o), Error);
  EXPECT_THROW(similarity_icp(TriMesh{}, m), Error);
}
