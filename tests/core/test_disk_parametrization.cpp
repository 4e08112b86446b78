#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "patch/disk_parametrization.h"
#include "base/error.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

const double kPi = std::acos(-1.0);

// Deterministic uniform numbers in [-0.5, 0.5).
struct Lcg {
  unsigned state;
  double operator()() {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5;
  }
};

std::vector<int> only_boundary_loop(const TriMesh& mesh) {
  const MeshTopology topo = build_topology(mesh);
  EXPECT_EQ(topo.boundary_loops.size(), 1u);
  return topo.boundary_loops.at(0);
}

double signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 e1 = b - a, e2 = c - a;
  return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
}

// Checks the whole contract on a disk mesh: boundary on the unit circle at arc-length angles
// starting at 0, no flipped triangle, and the triangles tile the boundary polygon exactly once
// (total signed area = polygon area), which with no flips means the map is a bijection.
std::vector<Vec2> check_embedding(const TriMesh& mesh, const DiskParametrizationOptions& options = {}) {
  validate_mesh(mesh);
  const std::vector<int> loop = only_boundary_loop(mesh);
  const std::vector<Vec2> uv = disk_parametrization(mesh, loop, options);
  EXPECT_EQ(uv.size(), mesh.positions.size());

  const std::size_t nb = loop.size();
  double perimeter = 0;
  for (std::size_t k = 0; k < nb; ++k)
    perimeter += (mesh.positions[loop[(k + 1) % nb]] - mesh.positions[loop[k]]).norm();
  double arc = 0, polygon_area = 0;
  for (std::size_t k = 0; k < nb; ++k) {
    const Vec2& p = uv[loop[k]];
    EXPECT_NEAR(p.norm(), 1.0, 1e-12) << "boundary vertex " << loop[k];
    const double expected = 2 * kPi * arc / perimeter;
    EXPECT_NEAR(p.x(), std::cos(expected), 1e-12);
    EXPECT_NEAR(p.y(), std::sin(expected), 1e-12);
    arc += (mesh.positions[loop[(k + 1) % nb]] - mesh.positions[loop[k]]).norm();
    polygon_area += signed_area(Vec2::Zero(), p, uv[loop[(k + 1) % nb]]);
  }
  EXPECT_EQ(count_flipped_triangles(mesh, uv), 0);
  double tiled = 0, smallest = 1;
  for (const Tri& t : mesh.triangles) {
    const double a = signed_area(uv[t[0]], uv[t[1]], uv[t[2]]);
    tiled += a;
    smallest = std::min(smallest, a);
  }
  EXPECT_NEAR(tiled, polygon_area, 1e-9);
  EXPECT_GT(smallest, 0.0);
  for (const Vec2& p : uv) EXPECT_LE(p.norm(), 1.0 + 1e-12);
  return uv;
}

// Area-weighted L2 stretch of the map uv -> 3D (Sander et al. 2001), scaled so that an
// equal-area map scores 1: the quantity the stretch reduction lowers.
double l2_stretch(const TriMesh& mesh, const std::vector<Vec2>& uv) {
  double area2 = 0, area3 = 0, sum = 0;
  for (const Tri& t : mesh.triangles) {
    const Vec2 &p1 = uv[t[0]], &p2 = uv[t[1]], &p3 = uv[t[2]];
    const Vec3 &q1 = mesh.positions[t[0]], &q2 = mesh.positions[t[1]], &q3 = mesh.positions[t[2]];
    const double a = signed_area(p1, p2, p3), a3 = 0.5 * (q2 - q1).cross(q3 - q1).norm();
    const Vec3 ss = (q1 * (p2.y() - p3.y()) + q2 * (p3.y() - p1.y()) + q3 * (p1.y() - p2.y())) / (2 * a);
    const Vec3 st = (q1 * (p3.x() - p2.x()) + q2 * (p1.x() - p3.x()) + q3 * (p2.x() - p1.x())) / (2 * a);
    sum += a3 * 0.5 * (ss.squaredNorm() + st.squaredNorm());
    area2 += a;
    area3 += a3;
  }
  return std::sqrt(sum / area3 * area2 / area3);
}

mcon_status status_of(const TriMesh& mesh, const std::vector<int>& loop, const DiskParametrizationOptions& o = {}) {
  try {
    disk_parametrization(mesh, loop, o);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()), "");
    return e.status();
  }
  return MCON_OK;
}

}  // namespace

TEST(DiskParametrization, ReproducesAFlatDiskWhoseBoundaryIsAlreadyTheCircle) {
  // make_disk's boundary ring is evenly spaced on the unit circle starting at angle 0, and
  // mean-value coordinates reproduce linear functions: the map must be the identity.
  const TriMesh disk = test_meshes::make_disk(8);
  const std::vector<Vec2> uv = check_embedding(disk);
  for (int v = 0; v < disk.num_vertices(); ++v) {
    EXPECT_NEAR(uv[v].x(), disk.positions[v].x(), 1e-10) << v;
    EXPECT_NEAR(uv[v].y(), disk.positions[v].y(), 1e-10) << v;
  }
}

TEST(DiskParametrization, StartsAtTheFirstLoopVertexAndFollowsRotatedLoops) {
  const TriMesh disk = test_meshes::make_disk(6);
  std::vector<int> loop = only_boundary_loop(disk);
  std::rotate(loop.begin(), loop.begin() + 5, loop.end());
  const std::vector<Vec2> uv = disk_parametrization(disk, loop);
  EXPECT_NEAR(uv[loop[0]].x(), 1.0, 1e-12);
  EXPECT_NEAR(uv[loop[0]].y(), 0.0, 1e-12);
  // Rotating the loop by 5 of 36 boundary vertices rotates the whole map by -5/36 of a turn.
  const double angle = -2 * kPi * 5 / 36;
  const Eigen::Rotation2Dd rotation(angle);
  for (int v = 0; v < disk.num_vertices(); ++v) {
    const Vec2 expected = rotation * Vec2(disk.positions[v].x(), disk.positions[v].y());
    EXPECT_NEAR((uv[v] - expected).norm(), 0.0, 1e-10) << v;
  }
  EXPECT_EQ(count_flipped_triangles(disk, uv), 0);
}

TEST(DiskParametrization, FlatConvexDiskKeepsInteriorVerticesStrictlyInside) {
  TriMesh disk = test_meshes::make_disk(10, 3.0);
  Lcg rnd{7u};
  const std::vector<int> loop = only_boundary_loop(disk);
  std::vector<char> on_boundary(disk.positions.size(), 0);
  for (int v : loop) on_boundary[v] = 1;
  for (std::size_t v = 0; v < disk.positions.size(); ++v)
    if (!on_boundary[v]) disk.positions[v] += Vec3(0.12 * rnd(), 0.12 * rnd(), 0.0);
  const std::vector<Vec2> uv = check_embedding(disk);
  double largest_interior = 0;
  for (std::size_t v = 0; v < uv.size(); ++v)
    if (!on_boundary[v]) largest_interior = std::max(largest_interior, uv[v].norm());
  EXPECT_LT(largest_interior, 0.95);  // the outermost interior ring sits at 0.9 of the radius
}

TEST(DiskParametrization, JitteredGridHasNoFlips) { check_embedding(test_meshes::make_grid(25, 2.0, 0.8)); }

TEST(DiskParametrization, BumpyNonConvexGridHasNoFlips) {
  // A tall narrow bump (height 3 on a 2 x 2 grid) plus random jitter in every direction.
  TriMesh grid = test_meshes::make_grid(41, 2.0, 0.7);
  Lcg rnd{99u};
  for (Vec3& p : grid.positions) {
    const double x = p.x() - 1.0, y = p.y() - 1.0;
    p.z() = 3.0 * std::exp(-(x * x + y * y) / 0.02) + 0.5 * std::exp(-((x - 0.5) * (x - 0.5)) / 0.01) + 0.03 * rnd();
  }
  check_embedding(grid);
}

TEST(DiskParametrization, RolledUpGridHasNoFlips) {
  // Three quarters of a tube: the boundary is far from planar and the surface folds back.
  TriMesh grid = test_meshes::make_grid(30, 1.0, 0.5);
  for (Vec3& p : grid.positions) {
    const double a = 1.5 * kPi * p.x();
    p = Vec3(0.3 * std::cos(a), 0.3 * std::sin(a), p.y());
  }
  check_embedding(grid);
}

TEST(DiskParametrization, SphericalCapLargerThanAHemisphereHasNoFlips) {
  // Everything above z = -0.6 of a unit icosphere: the boundary circle is narrower than the cap.
  const TriMesh cap =
      test_meshes::select_faces(test_meshes::make_icosphere(3), [](const Vec3& p) { return p.z() > -0.6; });
  const std::vector<Vec2> uv = check_embedding(cap);
  // The pole (farthest from the boundary) lands near the disk's center.
  int top = 0;
  for (int v = 0; v < cap.num_vertices(); ++v)
    if (cap.positions[v].z() > cap.positions[top].z()) top = v;
  EXPECT_LT(uv[top].norm(), 0.1);
}

TEST(DiskParametrization, VeryAnisotropicTrianglesHaveNoFlips) {
  // Aspect ratio ~200: the grid squeezed in x, with columns alternating wide and very narrow
  // (needles and triangles with angles close to pi, where cotan weights would go negative).
  TriMesh grid = test_meshes::make_grid(31, 1.0, 0.0);
  std::vector<double> column_x(31, 0.0);
  for (int i = 1; i < 31; ++i) column_x[i] = column_x[i - 1] + (i % 2 ? 1.0 : 0.02);
  for (Vec3& p : grid.positions) {
    const int i = static_cast<int>(std::lround(p.x() * 30));
    p.x() = 0.005 * column_x[i];
  }
  check_embedding(grid);
}

TEST(DiskParametrization, StretchReductionUnsqueezesADeepCapAndStaysBijective) {
  // Almost the whole sphere: the mean-value map squeezes the far pole region into a tiny part of
  // the disk (as it squeezes the fingers of a hand patch cut at the wrist).
  const TriMesh cap =
      test_meshes::select_faces(test_meshes::make_icosphere(3), [](const Vec3& p) { return p.z() > -0.9; });
  const std::vector<int> loop = only_boundary_loop(cap);
  DiskParametrizationOptions plain;
  plain.stretch_iterations = 0;
  const std::vector<Vec2> uv0 = disk_parametrization(cap, loop, plain);
  const double before = l2_stretch(cap, uv0);
  EXPECT_GT(before, 2.0);
  // A threshold above the plain map's stretch keeps the plain mean-value map, bit for bit.
  DiskParametrizationOptions above;
  above.stretch_threshold = before + 1;
  EXPECT_EQ(disk_parametrization(cap, loop, above), uv0);
  // The default reduces the stretch of every patch (threshold 0).
  EXPECT_EQ(DiskParametrizationOptions{}.stretch_threshold, 0.0);
  const std::vector<Vec2> uv = check_embedding(cap);  // bijective, boundary unchanged
  const double after = l2_stretch(cap, uv);
  EXPECT_LT(after, 0.6 * before) << "plain " << before << ", reduced " << after;
  // Running the rounds to the end (no early stop) can only stretch less or equally, and one
  // round only more or equally (the least-stretched iterate is returned).
  DiskParametrizationOptions to_end;
  to_end.stretch_min_decrease = 0;
  const double least = l2_stretch(cap, check_embedding(cap, to_end));
  EXPECT_LE(least, after);
  DiskParametrizationOptions one_round;
  one_round.stretch_iterations = 1;
  const double one = l2_stretch(cap, disk_parametrization(cap, loop, one_round));
  EXPECT_LT(one, before);
  EXPECT_LE(after, one);
}

TEST(DiskParametrization, RejectsInvalidStretchOptions) {
  const TriMesh disk = test_meshes::make_disk(4);
  const std::vector<int> loop = only_boundary_loop(disk);
  DiskParametrizationOptions o;
  o.stretch_iterations = -1;
  EXPECT_EQ(status_of(disk, loop, o), MCON_ERROR_INVALID_ARGUMENT);
  for (double e : {0.0, -0.5, 1.5, std::nan("")}) {
    o = {};
    o.stretch_exponent = e;
    EXPECT_EQ(status_of(disk, loop, o), MCON_ERROR_INVALID_ARGUMENT) << e;
  }
  for (double t : {-1.0, std::nan(""), HUGE_VAL}) {
    o = {};
    o.stretch_threshold = t;
    EXPECT_EQ(status_of(disk, loop, o), MCON_ERROR_INVALID_ARGUMENT) << t;
  }
  for (double d : {-0.1, 1.0, std::nan("")}) {
    o = {};
    o.stretch_min_decrease = d;
    EXPECT_EQ(status_of(disk, loop, o), MCON_ERROR_INVALID_ARGUMENT) << d;
  }
  o = {};
  o.stretch_iterations = 0;
  EXPECT_EQ(status_of(disk, loop, o), MCON_OK);
}

TEST(DiskParametrization, RejectsLoopsThatAreNotTheBoundary) {
  const TriMesh disk = test_meshes::make_disk(4);
  const std::vector<int> loop = only_boundary_loop(disk);

  std::vector<int> reversed(loop.rbegin(), loop.rend());
  EXPECT_EQ(status_of(disk, reversed), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<int> missing(loop.begin(), loop.end() - 1);
  EXPECT_EQ(status_of(disk, missing), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<int> swapped = loop;
  std::swap(swapped[2], swapped[3]);
  EXPECT_EQ(status_of(disk, swapped), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<int> interior = loop;
  interior[0] = 0;  // the center vertex
  EXPECT_EQ(status_of(disk, interior), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<int> out_of_range = loop;
  out_of_range[4] = disk.num_vertices();
  EXPECT_EQ(status_of(disk, out_of_range), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of(disk, {}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of(disk, {-1, 2, 3}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of(disk, loop), MCON_OK);

  // A closed sphere has no boundary at all.
  EXPECT_EQ(status_of(test_meshes::make_icosphere(1), {0, 1, 2}), MCON_ERROR_INVALID_ARGUMENT);
  // An annulus: a real boundary loop, but not a disk.
  const TriMesh tube = test_meshes::make_cylinder(1, 1, 12, 4);
  EXPECT_EQ(status_of(tube, build_topology(tube).boundary_loops[0]), MCON_ERROR_NOT_A_DISK);
}

TEST(DiskParametrization, CountsFlippedAndDegenerateTriangles) {
  const TriMesh disk = test_meshes::make_disk(3);
  std::vector<Vec2> uv = disk_parametrization(disk, only_boundary_loop(disk));
  EXPECT_EQ(count_flipped_triangles(disk, uv), 0);
  std::vector<Vec2> mirrored = uv;
  for (Vec2& p : mirrored) p.y() = -p.y();
  EXPECT_EQ(count_flipped_triangles(disk, mirrored), disk.num_triangles());
  std::vector<Vec2> collapsed = uv;
  collapsed[0] = collapsed[disk.triangles[0][1]];  // the center onto a ring vertex: its fan degenerates
  EXPECT_GE(count_flipped_triangles(disk, collapsed), 2);
  uv.pop_back();
  try {
    count_flipped_triangles(disk, uv);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_INVALID_ARGUMENT);
  }
}
