#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task.h>

#include "base/error.h"
#include "operators/heat_geodesics.h"
#include "mesh/mesh.h"
#include "test_meshes.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

struct Errors {
  double mean = 0;  // mean relative error
  double max = 0;   // largest relative error
};

// Relative error of `distance` against `exact`, skipping vertices within 2 mean edge lengths of
// the source where the relative error is dominated by the discretization of the source itself.
Errors relative_errors(const TriMesh& mesh, const Eigen::VectorXd& distance, const std::vector<double>& exact) {
  const double h = mean_edge_length(mesh);
  Errors e;
  int count = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (exact[v] <= 2 * h) continue;
    const double rel = std::abs(distance[v] - exact[v]) / exact[v];
    e.mean += rel;
    e.max = std::max(e.max, rel);
    ++count;
  }
  e.mean /= count;
  return e;
}

std::vector<double> euclidean_from(const TriMesh& mesh, const Vec3& p) {
  std::vector<double> d;
  for (const Vec3& q : mesh.positions) d.push_back((q - p).norm());
  return d;
}

// Errors of distances from vertex `source` of a flat mesh, against the straight-line distance.
Errors planar_errors(const TriMesh& mesh, const Eigen::VectorXd& distance, int source) {
  return relative_errors(mesh, distance, euclidean_from(mesh, mesh.positions[source]));
}

// Adds the errors of one of `n` runs to `total`: the mean of the means, the largest maximum.
void accumulate(Errors& total, const Errors& e, std::size_t n) {
  total.mean += e.mean / static_cast<double>(n);
  total.max = std::max(total.max, e.max);
}

void print(const char* what, const Errors& e) { std::printf("[ measured ] %s: mean %.5f max %.4f\n", what, e.mean, e.max); }

void expect_valid_distances(const Eigen::VectorXd& d) {
  for (Eigen::Index v = 0; v < d.size(); ++v) {
    ASSERT_TRUE(std::isfinite(d[v])) << "vertex " << v;
    ASSERT_GE(d[v], 0.0) << "vertex " << v;
  }
}

constexpr int kGridN = 100;
int grid_vertex(int i, int j) { return j * kGridN + i; }

const TriMesh& jittered_grid() {
  static const TriMesh grid = test_meshes::make_grid(kGridN, 1.0, 0.3);
  return grid;
}

const HeatGeodesics& grid_geodesics() {
  static const HeatGeodesics geodesics(jittered_grid());
  return geodesics;
}

}  // namespace

TEST(HeatGeodesics, PlaneMatchesEuclideanDistance) {
  const TriMesh& grid = jittered_grid();
  const int source = grid_vertex(50, 50);
  const Eigen::VectorXd d = grid_geodesics().from_vertices({source});
  ASSERT_EQ(d.size(), grid.num_vertices());
  expect_valid_distances(d);
  EXPECT_EQ(d[source], 0.0);
  const Errors e = planar_errors(grid, d, source);
  print("plane, central source", e);  // measured: mean 0.0095, max 0.066
  EXPECT_LE(e.mean, 0.013);
  EXPECT_LE(e.max, 0.10);
}

TEST(HeatGeodesics, SphereMatchesGreatCircleDistance) {
  const TriMesh sphere = test_meshes::make_icosphere(5);
  ASSERT_EQ(sphere.num_vertices(), 10242);
  const HeatGeodesics geodesics(sphere);
  for (int source : {0, 5000}) {
    const Eigen::VectorXd d = geodesics.from_vertices({source});
    expect_valid_distances(d);
    std::vector<double> exact;
    for (const Vec3& p : sphere.positions) exact.push_back(std::acos(std::clamp(p.dot(sphere.positions[source]), -1.0, 1.0)));
    const Errors e = relative_errors(sphere, d, exact);
    print("icosphere", e);  // measured: mean 0.0068, max 0.063
    EXPECT_LE(e.mean, 0.010);
    EXPECT_LE(e.max, 0.10);
  }
}

TEST(HeatGeodesics, BoundarySourcesOnThePlane) {
  const TriMesh& grid = jittered_grid();
  for (int source : {grid_vertex(0, 0), grid_vertex(50, 0), grid_vertex(99, 50)}) {
    const Eigen::VectorXd d = grid_geodesics().from_vertices({source});
    expect_valid_distances(d);
    const Errors e = planar_errors(grid, d, source);
    print("plane, boundary source", e);  // measured: mean 0.0074 - 0.0092, max 0.06 - 0.10
    EXPECT_LE(e.mean, 0.013);
    EXPECT_LE(e.max, 0.15);
  }
}

// §3.2.2: a pure Neumann flow forces isolines to meet the boundary at right angles, which is
// wrong next to a source close to the boundary; averaging with the Dirichlet flow fixes that.
TEST(HeatGeodesics, BoundaryAveragingHelpsNearTheBoundary) {
  const TriMesh& grid = jittered_grid();
  const int source = grid_vertex(30, 3);
  HeatGeodesicsOptions neumann_only;
  neumann_only.boundary_average = false;
  const Errors averaged = planar_errors(grid, grid_geodesics().from_vertices({source}), source);
  const Errors neumann = planar_errors(grid, HeatGeodesics(grid, neumann_only).from_vertices({source}), source);
  print("plane, source near boundary, averaged", averaged);
  print("plane, source near boundary, Neumann only", neumann);
  // Measured: averaged mean 0.0107, max 0.101; Neumann only mean 0.0068, max 0.272. Averaging
  // trades a slightly larger mean error for a much smaller worst case along the boundary.
  EXPECT_LE(averaged.mean, 0.016);
  EXPECT_LE(averaged.max, 0.16);
  EXPECT_LT(averaged.max, 0.6 * neumann.max);
}

TEST(HeatGeodesics, PointSourceInsideTriangle) {
  const TriMesh& grid = jittered_grid();
  const HeatGeodesics& geodesics = grid_geodesics();
  const int triangle = 2 * (49 * (kGridN - 1) + 49);  // a triangle near the center
  const Vec3 bary(0.2, 0.3, 0.5);
  const Tri& tri = grid.triangles[triangle];
  const Vec3 point = bary[0] * grid.positions[tri[0]] + bary[1] * grid.positions[tri[1]] + bary[2] * grid.positions[tri[2]];
  const Eigen::VectorXd d = geodesics.from_point(triangle, bary);
  expect_valid_distances(d);
  // The corners carry their straight-line distances to the point in the barycentric mean.
  double corner_error = 0;
  for (int i = 0; i < 3; ++i) corner_error += bary[i] * (d[tri[i]] - (grid.positions[tri[i]] - point).norm());
  EXPECT_NEAR(corner_error, 0.0, 1e-12);
  const Errors e = relative_errors(grid, d, euclidean_from(grid, point));
  print("plane, point source", e);  // measured: mean 0.0050, max 0.10
  EXPECT_LE(e.mean, 0.009);
  EXPECT_LE(e.max, 0.15);

  // A point on a corner is that vertex as a source.
  const Eigen::VectorXd corner = geodesics.from_point(triangle, Vec3(0, 1, 0));
  const Eigen::VectorXd vertex = geodesics.from_vertices({tri[1]});
  for (int v = 0; v < grid.num_vertices(); ++v) ASSERT_EQ(corner[v], vertex[v]) << "vertex " << v;
}

TEST(HeatGeodesics, TwoSourcesGiveTheMinimumOfTheirFields) {
  const TriMesh& grid = jittered_grid();
  const HeatGeodesics& geodesics = grid_geodesics();
  const int a = grid_vertex(25, 40), b = grid_vertex(75, 60);
  const Eigen::VectorXd both = geodesics.from_vertices({a, b});
  const Eigen::VectorXd da = geodesics.from_vertices({a}), db = geodesics.from_vertices({b});
  expect_valid_distances(both);
  EXPECT_EQ(both[a], 0.0);
  EXPECT_EQ(both[b], 0.0);
  std::vector<double> exact;
  double diff = 0;
  for (int v = 0; v < grid.num_vertices(); ++v) {
    exact.push_back(std::min((grid.positions[v] - grid.positions[a]).norm(), (grid.positions[v] - grid.positions[b]).norm()));
    diff += std::abs(both[v] - std::min(da[v], db[v]));
  }
  diff /= grid.num_vertices();
  const Errors e = relative_errors(grid, both, exact);
  print("plane, two sources", e);
  std::printf("[ measured ] mean |d(a, b) - min(d(a), d(b))| = %.5f (domain size 1)\n", diff);
  EXPECT_LE(e.mean, 0.014);  // measured 0.0093
  EXPECT_LE(diff, 0.003);    // measured 0.0014

  // Order and repetition of the sources do not matter.
  const Eigen::VectorXd again = geodesics.from_vertices({b, a, b});
  for (int v = 0; v < grid.num_vertices(); ++v) ASSERT_NEAR(again[v], both[v], 1e-9) << "vertex " << v;
}

TEST(HeatGeodesics, OtherComponentsAreUnreachable) {
  TriMesh mesh = test_meshes::make_grid(30, 1.0, 0.2);
  const int grid_vertices = mesh.num_vertices();
  const TriMesh sphere = test_meshes::make_icosphere(3, 0.3);
  for (const Vec3& p : sphere.positions) mesh.positions.push_back(p + Vec3(3, 0, 0));
  for (const Tri& t : sphere.triangles) mesh.triangles.push_back({t[0] + grid_vertices, t[1] + grid_vertices, t[2] + grid_vertices});
  validate_mesh(mesh);
  const HeatGeodesics geodesics(mesh);
  const double inf = std::numeric_limits<double>::infinity();

  const int on_grid = 15 * 30 + 15, on_sphere = grid_vertices + 7;
  const Eigen::VectorXd from_grid = geodesics.from_vertices({on_grid});
  const Eigen::VectorXd from_sphere = geodesics.from_vertices({on_sphere});
  const Eigen::VectorXd from_both = geodesics.from_vertices({on_grid, on_sphere});
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const bool grid_side = v < grid_vertices;
    ASSERT_EQ(from_grid[v] == inf, !grid_side) << "vertex " << v;
    ASSERT_EQ(from_sphere[v] == inf, grid_side) << "vertex " << v;
    ASSERT_TRUE(std::isfinite(from_both[v])) << "vertex " << v;
    ASSERT_NEAR(from_both[v], grid_side ? from_grid[v] : from_sphere[v], 1e-9) << "vertex " << v;
  }
  // Both halves are right: Euclidean on the grid, great circles of radius 0.3 on the sphere.
  const TriMesh grid_part{std::vector<Vec3>(mesh.positions.begin(), mesh.positions.begin() + grid_vertices),
                          std::vector<Tri>(mesh.triangles.begin(), mesh.triangles.begin() + 2 * 29 * 29)};
  const Errors e = relative_errors(grid_part, from_grid.head(grid_vertices), euclidean_from(grid_part, mesh.positions[on_grid]));
  print("two components, grid part", e);
  EXPECT_LE(e.mean, 0.03);  // measured 0.021 (30 x 30 grid: 1.5% on average over sources)
  const Vec3 c(3, 0, 0), s = mesh.positions[on_sphere] - c;
  std::vector<double> exact;
  for (int v = grid_vertices; v < mesh.num_vertices(); ++v)
    exact.push_back(0.3 * std::acos(std::clamp((mesh.positions[v] - c).dot(s) / 0.09, -1.0, 1.0)));
  const Errors es = relative_errors(sphere, from_sphere.tail(sphere.num_vertices()), exact);
  print("two components, sphere part", es);
  EXPECT_LE(es.mean, 0.025);  // measured 0.0178 (642 vertices)
}

// On a long strip a unit heat spike underflows about 700 edges away; the far field must still
// be right (the solver scales the heat into the top of the double range).
TEST(HeatGeodesics, FarFieldOnALongStrip) {
  const int around = 8, along = 1200;
  const double pi = std::acos(-1.0);
  const double r = 1.0 / (2 * std::sin(pi / around));  // unit edges around
  const TriMesh strip = test_meshes::make_cylinder(r, along - 1.0, around, along);
  const HeatGeodesics geodesics(strip);
  // The prism unrolls into a periodic strip: vertex (i, j) sits at s = i + (j odd) / 2, z = j.
  const int source = 3;  // on the first ring, a boundary vertex
  const Eigen::VectorXd d = geodesics.from_vertices({source});
  expect_valid_distances(d);
  std::vector<double> exact;
  for (int v = 0; v < strip.num_vertices(); ++v) {
    const int i = v % around, j = v / around;
    double ds = std::abs(i + 0.5 * (j % 2) - source);
    ds = std::min(ds, around - ds);
    exact.push_back(std::hypot(ds, static_cast<double>(j)));
  }
  const Errors e = relative_errors(strip, d, exact);
  print("long strip", e);
  EXPECT_LE(e.mean, 0.012);  // measured 0.0071 (0.087 without the heat scaling)
  EXPECT_LE(e.max, 0.3);  // worst on the source's own (boundary) ring of 8 edges
  double far_max = 0;
  for (int v = 100 * around; v < strip.num_vertices(); ++v) far_max = std::max(far_max, std::abs(d[v] - exact[v]) / exact[v]);
  std::printf("[ measured ] largest relative error beyond 100 edges: %.4f\n", far_max);
  EXPECT_LE(far_max, 0.015);  // measured 0.0103 (0.375 without the heat scaling)
  const int far = (along - 1) * around + 3;
  std::printf("[ measured ] far end: %.3f (exact %.3f)\n", d[far], exact[far]);
  EXPECT_NEAR(d[far], exact[far], 0.01 * exact[far]);  // measured 1205.4 (749 without the scaling)
}

// Obtuse triangles (a grid stretched 10:1, so half the interior edges are far from Delaunay) give
// the extrinsic cotan operators negative weights; the intrinsic Delaunay operators stay accurate.
TEST(HeatGeodesics, ObtuseTrianglesUseIntrinsicDelaunayOperators) {
  TriMesh mesh = test_meshes::make_grid(40, 1.0, 0.2);
  for (Vec3& p : mesh.positions) p.x() *= 10.0;
  HeatGeodesicsOptions extrinsic;
  extrinsic.intrinsic_delaunay = false;
  const HeatGeodesics intrinsic_geodesics(mesh), extrinsic_geodesics(mesh, extrinsic);
  Errors intrinsic_errors, extrinsic_errors;
  const std::vector<int> sources{20 * 40 + 20, 10 * 40 + 5, 35 * 40 + 30};
  for (int source : sources) {
    accumulate(intrinsic_errors, planar_errors(mesh, intrinsic_geodesics.from_vertices({source}), source),
               sources.size());
    accumulate(extrinsic_errors, planar_errors(mesh, extrinsic_geodesics.from_vertices({source}), source),
               sources.size());
  }
  print("stretched grid, intrinsic Delaunay", intrinsic_errors);
  print("stretched grid, extrinsic cotan", extrinsic_errors);
  // Measured: intrinsic mean 0.018, max 0.105; extrinsic mean 0.33, max 0.74.
  EXPECT_LE(intrinsic_errors.mean, 0.03);
  EXPECT_LE(intrinsic_errors.max, 0.16);
  EXPECT_LT(intrinsic_errors.mean, 0.25 * extrinsic_errors.mean);
}

TEST(HeatGeodesics, ConcurrentQueriesAreBitIdentical) {
  const TriMesh& grid = jittered_grid();
  const HeatGeodesics& geodesics = grid_geodesics();
  const std::vector<int> sources{grid_vertex(10, 10), grid_vertex(90, 20), grid_vertex(40, 70), grid_vertex(0, 99)};
  std::vector<Eigen::VectorXd> serial, parallel(sources.size());
  for (int s : sources) serial.push_back(geodesics.from_vertices({s}));
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < sources.size(); ++k)
    threads.emplace_back([&, k] { parallel[k] = geodesics.from_vertices({sources[k]}); });
  for (auto& t : threads) t.join();
  for (std::size_t k = 0; k < sources.size(); ++k)
    for (int v = 0; v < grid.num_vertices(); ++v) ASSERT_EQ(serial[k][v], parallel[k][v]);
}

TEST(HeatGeodesics, MovedObjectStillAnswers) {
  const TriMesh grid = test_meshes::make_grid(20);
  HeatGeodesics a(grid);
  const Eigen::VectorXd before = a.from_vertices({0});
  HeatGeodesics b(std::move(a));
  HeatGeodesics c(test_meshes::make_grid(5));
  c = std::move(b);
  const Eigen::VectorXd after = c.from_vertices({0});
  for (int v = 0; v < grid.num_vertices(); ++v) ASSERT_EQ(before[v], after[v]);
}

TEST(HeatGeodesics, BadArgumentsThrow) {
  const TriMesh grid = test_meshes::make_grid(10);
  const HeatGeodesics g(grid);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(status_of([&] { g.from_vertices({}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_vertices({-1}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_vertices({3, 100}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_point(-1, Vec3(1, 0, 0)); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_point(grid.num_triangles(), Vec3(1, 0, 0)); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_point(0, Vec3(nan, 0.5, 0.5)); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_point(0, Vec3(0.3, 0.3, 0.3)); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_point(0, Vec3(-0.5, 0.5, 1.0)); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { g.from_point(0, Vec3(0.25, 0.25, 0.5)); }), MCON_OK);
  EXPECT_EQ(status_of([&] { g.from_vertices({0, 99}); }), MCON_OK);
  try {
    g.from_vertices({3, 100});
    ADD_FAILURE() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("100"), std::string::npos) << e.what();
  }

  HeatGeodesicsOptions options;
  for (double bad : {0.0, -1.0, nan, std::numeric_limits<double>::infinity()}) {
    options.time_factor = bad;
    EXPECT_EQ(status_of([&] { HeatGeodesics{grid, options}; }), MCON_ERROR_INVALID_ARGUMENT) << bad;
  }
  EXPECT_EQ(status_of([&] { HeatGeodesics{TriMesh{}}; }), MCON_ERROR_EMPTY_MESH);
  TriMesh broken = grid;
  broken.triangles[5][1] = 1000;
  EXPECT_EQ(status_of([&] { HeatGeodesics{broken}; }), MCON_ERROR_INDEX_OUT_OF_RANGE);
  TriMesh non_finite = grid;
  non_finite.positions[7].y() = nan;
  EXPECT_EQ(status_of([&] { HeatGeodesics{non_finite}; }), MCON_ERROR_NON_FINITE);
  TriMesh non_manifold = grid;
  non_manifold.triangles.push_back(non_manifold.triangles[0]);
  EXPECT_EQ(status_of([&] { HeatGeodesics{non_manifold}; }), MCON_ERROR_NON_MANIFOLD_EDGE);
  TriMesh isolated = grid;
  isolated.positions.emplace_back(5, 5, 5);
  EXPECT_EQ(status_of([&] { HeatGeodesics{isolated}; }), MCON_ERROR_ISOLATED_VERTEX);
}

// Inside a parallel loop whose task group is cancelled (a sibling iteration threw), a nested
// parallel_invoke of that group skips its functions: the solvers stayed unfactored and the heat
// solution empty, and the solve read it out of bounds (a crash under eval-retrieval --noise). The
// heat method runs its own parallel work in an isolated group and computes as usual.
TEST(HeatGeodesics, ComputesInsideACancelledParallelLoop) {
  const TriMesh grid = test_meshes::make_grid(30);
  Eigen::VectorXd d;
  tbb::parallel_for(0, 1, [&](int) {
    tbb::task::current_context()->cancel_group_execution();
    const HeatGeodesics heat(grid);
    d = heat.from_vertices({0});
  });
  ASSERT_EQ(d.size(), grid.num_vertices());
  EXPECT_TRUE(d.allFinite());
  EXPECT_EQ(d[0], 0.0);
  EXPECT_NEAR(d[grid.num_vertices() - 1], std::sqrt(2.0), 0.1);
}
