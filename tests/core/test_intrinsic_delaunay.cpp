#include <gtest/gtest.h>

#include <cmath>

#include "operators/cotan_laplacian.h"
#include "operators/intrinsic_delaunay.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

// A grid stretched 6:1 along x: the alternating diagonals give obtuse triangles whose opposite
// angles sum to far more than pi, i.e. about half the interior edges are not Delaunay.
TriMesh stretched_grid(int n) {
  TriMesh m = test_meshes::make_grid(n, 1.0, 0.2);
  for (Vec3& p : m.positions) p.x() *= 6.0;
  return m;
}

double max_positive_off_diagonal(const SparseMatrix& L) {
  double worst = 0;
  for (int k = 0; k < L.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(L, k); it; ++it)
      if (it.row() != it.col()) worst = std::max(worst, it.value());
  return worst;
}

// The smallest cotan weight (sum of the two opposite half-cotangents) over interior edges.
double min_interior_weight(const IntrinsicTriangulation& it) {
  auto half_cot = [&](int t, int slot) {  // at the corner opposite `slot`
    const auto& l = it.lengths[t];
    const double a = l[slot], b = l[(slot + 1) % 3], c = l[(slot + 2) % 3];
    return (b * b + c * c - a * a) / (8 * triangle_area_from_lengths(a, b, c));
  };
  double worst = 1e300;
  for (std::size_t t = 0; t < it.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int g = it.across[t][c];
      if (g >= 0) worst = std::min(worst, half_cot(static_cast<int>(t), c) + half_cot(g / 3, g % 3));
    }
  return worst;
}

// Every intrinsic edge has the same length seen from both of its triangles, and the gluing is an
// involution.
void expect_consistent(const IntrinsicTriangulation& it) {
  for (std::size_t t = 0; t < it.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int g = it.across[t][c];
      if (g < 0) continue;
      const int u = g / 3, d = g % 3;
      ASSERT_EQ(it.across[u][d], static_cast<int>(3 * t + c));
      ASSERT_DOUBLE_EQ(it.lengths[u][d], it.lengths[t][c]);
      // Same edge, opposite direction.
      ASSERT_EQ(it.triangles[u][d], it.triangles[t][(c + 1) % 3]);
      ASSERT_EQ(it.triangles[u][(d + 1) % 3], it.triangles[t][c]);
    }
}

}  // namespace

TEST(IntrinsicDelaunay, UnflippedOperatorsMatchTheMeshOperators) {
  const TriMesh mesh = test_meshes::make_grid(12, 1.0, 0.3);
  const IntrinsicTriangulation it = intrinsic_triangulation(mesh, build_topology(mesh));
  expect_consistent(it);
  const SparseMatrix difference = cotan_laplacian(it) - cotan_laplacian(mesh);
  EXPECT_LT(difference.norm(), 1e-12);
  EXPECT_LT((vertex_areas(it) - vertex_areas(mesh)).norm(), 1e-14);
}

TEST(IntrinsicDelaunay, DelaunayMeshesAreLeftAlone) {
  // A regular grid (co-circular quads) and an icosphere are already Delaunay.
  for (const TriMesh& mesh : {test_meshes::make_grid(10), test_meshes::make_icosphere(3)}) {
    IntrinsicTriangulation it = intrinsic_triangulation(mesh, build_topology(mesh));
    make_delaunay(it);
    EXPECT_EQ(it.flips, 0);
  }
}

TEST(IntrinsicDelaunay, FlipsGiveNonNegativeWeightsAndKeepTheMetric) {
  const TriMesh mesh = stretched_grid(20);
  const MeshTopology topology = build_topology(mesh);
  IntrinsicTriangulation it = intrinsic_triangulation(mesh, topology);
  EXPECT_LT(min_interior_weight(it), -0.5);  // strongly negative cotan weights before
  make_delaunay(it);
  EXPECT_GT(it.flips, 100);
  expect_consistent(it);
  EXPECT_EQ(it.triangles.size(), mesh.triangles.size());
  // Every interior edge is Delaunay now. (Boundary edges cannot flip: an obtuse angle opposite
  // one keeps its negative weight.)
  EXPECT_GE(min_interior_weight(it), -1e-9);
  const SparseMatrix L = cotan_laplacian(it);
  EXPECT_LT(max_positive_off_diagonal(L), max_positive_off_diagonal(cotan_laplacian(mesh)));
  // The metric is unchanged: same total area, and on a flat mesh the intrinsic Laplacian still
  // annihilates linear functions at interior vertices (it is a triangulation of the same plane).
  const Eigen::VectorXd areas = vertex_areas(it);
  EXPECT_NEAR(areas.sum(), total_area(mesh), 1e-12 * total_area(mesh));
  Eigen::VectorXd x(mesh.num_vertices()), y(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    x[v] = mesh.positions[v].x();
    y[v] = mesh.positions[v].y();
  }
  const Eigen::VectorXd Lx = L * x, Ly = L * y;
  std::vector<char> boundary(mesh.num_vertices(), 0);
  for (const auto& loop : topology.boundary_loops)
    for (int v : loop) boundary[v] = 1;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (boundary[v]) continue;
    ASSERT_NEAR(Lx[v], 0.0, 1e-10) << "vertex " << v;
    ASSERT_NEAR(Ly[v], 0.0, 1e-10) << "vertex " << v;
  }
  // Boundary edges never move.
  for (std::size_t t = 0; t < it.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c)
      if (it.across[t][c] < 0) {
        ASSERT_TRUE(boundary[it.triangles[t][c]] && boundary[it.triangles[t][(c + 1) % 3]]);
      }
}

TEST(IntrinsicDelaunay, AreaFromLengths) {
  EXPECT_DOUBLE_EQ(triangle_area_from_lengths(3, 4, 5), 6.0);
  EXPECT_DOUBLE_EQ(triangle_area_from_lengths(5, 3, 4), 6.0);
  EXPECT_EQ(triangle_area_from_lengths(1, 2, 3), 0.0);  // degenerate
  // A needle with legs 1 and 1e-7 keeps its area to ~1e-9 relative.
  const double area = triangle_area_from_lengths(1.0, 1e-7, std::hypot(1.0, 1e-7));
  EXPECT_NEAR(area, 0.5e-7, 1e-16);
}
