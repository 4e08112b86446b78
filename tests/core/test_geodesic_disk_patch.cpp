#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "patch/geodesic_disk_patch.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

mcon_status extraction_status(const TriMesh& host, const PatchOptions& o) {
  return status_of([&] { extract_geodesic_disk(host, o); });
}

PatchOptions at_vertex(int vertex, double radius) {
  PatchOptions o;
  o.center.vertex = vertex;
  o.radius = radius;
  return o;
}

Vec3 host_point(const TriMesh& host, const HostPoint& h) {
  return (1 - h.t) * host.positions[h.v0] + h.t * host.positions[h.v1];
}

// Checks the invariants every patch must satisfy.
void expect_valid_disk(const TriMesh& host, const Patch& p) {
  const MeshTopology t = build_topology(p.mesh);
  ASSERT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_EQ(euler_characteristic(p.mesh, t), 1);
  EXPECT_EQ(p.boundary_loop.size(), t.boundary_loops[0].size());
  EXPECT_EQ(p.param_flipped_triangles, 0);
  ASSERT_EQ(p.uv.size(), p.mesh.positions.size());
  for (const Vec2& q : p.uv) EXPECT_LE(q.norm(), 1.0 + 1e-9);
  for (int v : p.boundary_loop) EXPECT_NEAR(p.uv[v].norm(), 1.0, 1e-9);
  // The host link reproduces every vertex from host data.
  ASSERT_EQ(p.host_vertex.size(), p.mesh.positions.size());
  for (std::size_t v = 0; v < p.host_vertex.size(); ++v) {
    const HostPoint& h = p.host_vertex[v];
    if (h.v0 < 0) continue;
    const Vec3 expected = (host_point(host, h) - p.center_position) / p.radius;
    EXPECT_LT((expected - p.mesh.positions[v]).norm(), 1e-9) << "vertex " << v;
    EXPECT_GE(h.t, 0.0);
    EXPECT_LE(h.t, 1.0);
  }
  ASSERT_EQ(p.host_triangle.size(), p.mesh.triangles.size());
  EXPECT_NO_THROW(validate_mesh(p.mesh));
}

// Extracts the patch and checks the invariants above.
Patch extract_valid_disk(const TriMesh& host, const PatchOptions& o) {
  Patch p = extract_geodesic_disk(host, o);
  expect_valid_disk(host, p);
  return p;
}

}  // namespace


TEST(GeodesicDiskPatch, PlaneDiskIsRoundAndNormalized) {
  const TriMesh host = test_meshes::make_grid(61, 1.0, 0.3);
  const Patch p = extract_valid_disk(host, at_vertex(30 * 61 + 30, 0.3));
  EXPECT_EQ(p.filled_triangles(), 0);
  // Boundary vertices lie on the geodesic (here: Euclidean) circle of radius 1 after normalization.
  double max_dev = 0;
  for (int v : p.boundary_loop) max_dev = std::max(max_dev, std::abs(p.mesh.positions[v].norm() - 1.0));
  EXPECT_LT(max_dev, 0.05);
  EXPECT_NEAR(total_area(p.mesh), M_PI, 0.05 * M_PI);
  EXPECT_NEAR(p.max_geodesic_distance, 1.0, 0.05);
  EXPECT_NEAR(p.radius, 0.3, 0);
}

TEST(GeodesicDiskPatch, SphereCapHasTheSphericalCapArea) {
  const TriMesh host = test_meshes::make_icosphere(5, 2.0);
  const Patch p = extract_valid_disk(host, at_vertex(0, 1.5));  // geodesic radius on a sphere of radius 2
  const double cap = 2 * M_PI * 4.0 * (1 - std::cos(1.5 / 2.0));
  EXPECT_NEAR(total_area(p.mesh) * 1.5 * 1.5, cap, 0.03 * cap);
}

TEST(GeodesicDiskPatch, PointCenterInsideATriangle) {
  const TriMesh host = test_meshes::make_grid(41, 1.0, 0.2);
  PatchOptions o;
  o.center.triangle = 1000;
  o.center.barycentric = Vec3(0.2, 0.3, 0.5);
  o.radius = 0.25;
  const Patch p = extract_geodesic_disk(host, o);
  expect_valid_disk(host, p);
  ASSERT_GE(p.center.triangle, 0);
  EXPECT_EQ(p.host_triangle[p.center.triangle], 1000);
  // The center maps back to the requested point, i.e. the origin of the normalized patch.
  const Tri& tri = p.mesh.triangles[p.center.triangle];
  const Vec3 c = p.center.barycentric[0] * p.mesh.positions[tri[0]] + p.center.barycentric[1] * p.mesh.positions[tri[1]] +
                 p.center.barycentric[2] * p.mesh.positions[tri[2]];
  EXPECT_LT(c.norm(), 1e-9);
}

TEST(GeodesicDiskPatch, DiskReachingTheHostBoundaryIsStillADisk) {
  const TriMesh host = test_meshes::make_grid(41, 1.0);
  // Near the left border: the disk is cut off by it.
  const Patch p = extract_valid_disk(host, at_vertex(20 * 41 + 3, 0.3));
}

TEST(GeodesicDiskPatch, HostHoleInsideTheDiskIsCappedAndFlagged) {
  TriMesh host = test_meshes::make_grid(41, 1.0);
  // Punch a hole near the center: drop the triangles around one vertex.
  const int hole = 20 * 41 + 22;
  std::vector<Tri> kept;
  for (const Tri& t : host.triangles)
    if (t[0] != hole && t[1] != hole && t[2] != hole) kept.push_back(t);
  host.triangles = kept;
  remove_unreferenced_vertices(host);
  PatchOptions o = at_vertex(20 * 41 + 18, 0.3);
  const Patch p = extract_valid_disk(host, o);
  EXPECT_GT(p.filled_triangles(), 0);
  int fill_vertices = 0;
  for (const HostPoint& h : p.host_vertex) fill_vertices += h.v0 < 0;
  EXPECT_EQ(fill_vertices, 1);  // one centroid for the one hole

  o.fill_holes = false;
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_NOT_A_DISK);
}

TEST(GeodesicDiskPatch, DiskWrappingAroundACylinderIsAnAnnulus) {
  const TriMesh host = test_meshes::make_cylinder(1.0, 12.0, 48, 97);
  PatchOptions o = at_vertex(48 * 48, 2.0);  // middle ring; radius < half the circumference (pi): a disk
  const Patch p = extract_valid_disk(host, o);
  o.radius = 4.0;  // > pi: the disk closes around the cylinder
  try {
    extract_geodesic_disk(host, o);
    FAIL() << "expected NOT_A_DISK";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_NOT_A_DISK);
    EXPECT_NE(std::string(e.what()).find("annulus"), std::string::npos) << e.what();
  }
}

TEST(GeodesicDiskPatch, WholeClosedSurfaceIsNotADisk) {
  const TriMesh host = test_meshes::make_icosphere(3, 1.0);
  PatchOptions o = at_vertex(0, 10.0);
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_NOT_A_DISK);
}

TEST(GeodesicDiskPatch, NoSliversAfterSnapping) {
  const TriMesh host = test_meshes::make_grid(61, 1.0, 0.3);
  PatchOptions o;
  o.center.vertex = 30 * 61 + 30;
  for (double radius : {0.2, 0.2137, 0.25, 0.3111}) {
    o.radius = radius;
    const Patch p = extract_geodesic_disk(host, o);
    double min_area = 1e300;
    for (int t = 0; t < p.mesh.num_triangles(); ++t) min_area = std::min(min_area, triangle_area(p.mesh, t));
    const double h = mean_edge_length(p.mesh);
    EXPECT_GT(min_area, 0.01 * h * h) << "radius " << radius;
  }
}

TEST(GeodesicDiskPatch, BadOptionsAreRejected) {
  const TriMesh host = test_meshes::make_grid(11);
  PatchOptions o = at_vertex(60, std::nan(""));
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_INVALID_ARGUMENT);
  o.radius = -1;
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_INVALID_ARGUMENT);
  o.radius = 0.3;
  o.center.vertex = 121;
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_INVALID_ARGUMENT);
  o.center.vertex = -1;
  o.center.triangle = 500;
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_INVALID_ARGUMENT);
  o.center.triangle = 5;
  o.center.barycentric = Vec3(0.5, 0.7, -0.2);
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_INVALID_ARGUMENT);
  o.center.vertex = 60;
  o.radius = 1e-6;  // far below the edge length
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_INVALID_ARGUMENT);
}

TEST(GeodesicDiskPatch, ProgressCanCancel) {
  const TriMesh host = test_meshes::make_grid(31);
  PatchOptions o = at_vertex(15 * 31 + 15, 0.3);
  int calls = 0;
  o.progress = [&](double f) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    return ++calls < 3;
  };
  EXPECT_EQ(extraction_status(host, o), MCON_ERROR_CANCELLED);
  EXPECT_EQ(calls, 3);
}

// A radius beyond the whole part of the mesh used to give a "disk" bounded by the mesh border,
// normalized so that its geodesic radius was far from 1 (radius 2 here: 0.37).
TEST(GeodesicDiskPatch, RadiusBeyondTheWholeMeshIsAnError) {
  const TriMesh host = test_meshes::make_grid(21, 1.0);
  for (double r : {2.0, 1e30}) {
    std::string message;
    try {
      extract_geodesic_disk(host, at_vertex(10 * 21 + 10, r));
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), MCON_ERROR_INVALID_ARGUMENT);
      message = e.what();
    }
    EXPECT_NE(message.find("larger than the whole part of the mesh"), std::string::npos) << r << ": " << message;
  }
  // Within the grid (the border is at distance 0.5) it is a valid disk of geodesic radius 1.
  const Patch p = extract_valid_disk(host, at_vertex(10 * 21 + 10, 0.45));
  EXPECT_NEAR(p.max_geodesic_distance, 1.0, 0.05);
}

// Messages print the radius in full: 1e-12 used to read "radius 0.000000 is too small".
TEST(GeodesicDiskPatch, TooSmallRadiusIsPrintedInFull) {
  const TriMesh host = test_meshes::make_grid(21, 1.0);
  std::string message;
  try {
    extract_geodesic_disk(host, at_vertex(10 * 21 + 10, 1e-12));
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("radius 1e-12 "), std::string::npos) << message;
}

// The supported coordinate range holds end to end: a grid scaled to either end gives the same
// normalized disk; beyond it validation names the range.
TEST(GeodesicDiskPatch, ScaleWithinTheSupportedRangeGivesTheSameDisk) {
  const TriMesh unit = test_meshes::make_grid(31, 1.0, 0.3);
  const Patch ref = extract_valid_disk(unit, at_vertex(15 * 31 + 15, 0.3));
  for (double scale : {1e-14, 1e14}) {
    TriMesh host = unit;
    for (Vec3& p : host.positions) p *= scale;
    const Patch p = extract_valid_disk(host, at_vertex(15 * 31 + 15, 0.3 * scale));
    EXPECT_EQ(p.mesh.num_vertices(), ref.mesh.num_vertices()) << scale;
    EXPECT_NEAR(p.max_geodesic_distance, ref.max_geodesic_distance, 1e-6) << scale;
  }
  for (double scale : {1e200, 1e100, 1e-100}) {
    TriMesh host = unit;
    for (Vec3& p : host.positions) p *= scale;
    std::string message;
    try {
      validate_mesh(host);
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), MCON_ERROR_INVALID_ARGUMENT) << scale;
      message = e.what();
    }
    EXPECT_NE(message.find("supported"), std::string::npos) << scale << ": " << message;
  }
}
