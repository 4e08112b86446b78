// Polylines on a patch expressed on its host (transfer/host_polylines.h): every point lands at the
// same place on the host, a polyline through a filled hole is split there, and a patch of another
// host is refused.
#include <gtest/gtest.h>

#include <cmath>

#include "patch/geodesic_disk_patch.h"
#include "test_meshes.h"
#include "test_status.h"
#include "transfer/host_polylines.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

// A 2 x 2 grid with a round hole at (1, 1) and the disk around (1.2, 1) that covers it (filled).
struct HoledDisk {
  TriMesh host;
  Patch patch;
};

const HoledDisk& holed_disk() {
  static const HoledDisk d = [] {
    HoledDisk x;
    x.host = test_meshes::select_faces(test_meshes::make_grid(41, 2.0),
                                       [](const Vec3& p) { return (p - Vec3(1, 1, 0)).norm() > 0.12; });
    int center = 0;
    for (int v = 0; v < x.host.num_vertices(); ++v)
      if ((x.host.positions[v] - Vec3(1.2, 1, 0)).norm() < (x.host.positions[center] - Vec3(1.2, 1, 0)).norm())
        center = v;
    PatchOptions o;
    o.center.vertex = center;
    o.radius = 0.7;
    x.patch = extract_geodesic_disk(x.host, o);
    return x;
  }();
  return d;
}

Vec3 host_position(const TriMesh& m, const SurfacePoint& p) {
  const Tri& t = m.triangles[p.triangle];
  return p.barycentric[0] * m.positions[t[0]] + p.barycentric[1] * m.positions[t[1]] +
         p.barycentric[2] * m.positions[t[2]];
}

SurfacePoint centroid(int triangle) { return {triangle, Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3)}; }

}  // namespace

TEST(HostPolylines, PointsLandAtTheSamePlaceOnTheHost) {
  const HoledDisk& d = holed_disk();
  ASSERT_GT(d.patch.filled_triangles(), 0);
  check_patch_of_host(d.host, d.patch);
  TracedPolyline line;
  line.closed = true;
  int kept = 0;
  for (int t = 0; t < d.patch.mesh.num_triangles() && kept < 40; t += 7) {
    if (d.patch.host_triangle[t] < 0) continue;
    // A corner, an edge point and an inside point of the same patch triangle.
    line.points.push_back({t, Vec3(1, 0, 0)});
    line.points.push_back({t, Vec3(0.3, 0.7, 0)});
    line.points.push_back({t, Vec3(0.2, 0.5, 0.3)});
    kept += 3;
  }
  const HostPolylines h = polylines_on_host(d.host, d.patch, {line});
  ASSERT_EQ(h.lines.size(), 1u);
  EXPECT_TRUE(h.closed[0]);
  EXPECT_EQ(h.dropped_points, 0);
  ASSERT_EQ(h.lines[0].size(), line.points.size());
  for (std::size_t i = 0; i < line.points.size(); ++i) {
    const SurfacePoint& p = line.points[i];
    const Vec3 on_patch = d.patch.center_position + d.patch.radius * host_position(d.patch.mesh, p);
    EXPECT_NEAR((host_position(d.host, h.lines[0][i]) - on_patch).norm(), 0, 1e-12) << i;
    EXPECT_NEAR(h.lines[0][i].barycentric.sum(), 1, 1e-12);
    // A point on a patch edge stays exactly on an edge (a zero weight) when the patch triangle is a
    // whole host triangle.
    bool whole = true;
    for (int c : d.patch.mesh.triangles[p.triangle]) whole &= d.patch.host_vertex[c].v0 == d.patch.host_vertex[c].v1;
    if (i % 3 == 1 && whole) {
      EXPECT_EQ(h.lines[0][i].barycentric.minCoeff(), 0.0) << i;
    }
  }
}

TEST(HostPolylines, APolylineThroughAFilledHoleIsSplitThere) {
  const HoledDisk& d = holed_disk();
  std::vector<int> host_tris, cap_tris;
  for (int t = 0; t < d.patch.mesh.num_triangles(); ++t) (d.patch.host_triangle[t] < 0 ? cap_tris : host_tris).push_back(t);
  ASSERT_GE(host_tris.size(), 4u);
  ASSERT_FALSE(cap_tris.empty());
  TracedPolyline line;
  line.closed = true;
  line.points = {centroid(host_tris[0]), centroid(host_tris[1]), centroid(cap_tris[0]), centroid(cap_tris[0]),
                 centroid(host_tris[2]), centroid(host_tris[3]), centroid(cap_tris[0]), centroid(host_tris[0])};
  const HostPolylines h = polylines_on_host(d.host, d.patch, {line});
  // Pieces: [0, 1], [4, 5], and the lone last point (dropped: fewer than 2 points).
  ASSERT_EQ(h.lines.size(), 2u);
  EXPECT_EQ(h.lines[0].size(), 2u);
  EXPECT_EQ(h.lines[1].size(), 2u);
  EXPECT_FALSE(h.closed[0]);
  EXPECT_FALSE(h.closed[1]);
  EXPECT_EQ(h.dropped_points, 3);
  EXPECT_EQ(h.split_polylines, 1);
  EXPECT_EQ(h.origin, std::vector<int>({0, 0}));
}

TEST(HostPolylines, APatchOfAnotherHostIsRefused) {
  const HoledDisk& d = holed_disk();
  TriMesh moved = d.host;
  for (Vec3& p : moved.positions) p.x() += 0.01;
  EXPECT_EQ(status_of([&] { check_patch_of_host(moved, d.patch); }), MCON_ERROR_INVALID_ARGUMENT);
  TriMesh fewer = d.host;
  fewer.positions.resize(10);
  EXPECT_EQ(status_of([&] { check_patch_of_host(fewer, d.patch); }), MCON_ERROR_INVALID_ARGUMENT);
  Patch from_arrays = d.patch;
  from_arrays.host_vertex.clear();
  EXPECT_EQ(status_of([&] { check_patch_of_host(d.host, from_arrays); }), MCON_ERROR_INVALID_ARGUMENT);
  // Triangles beyond the host: refused when a point is converted.
  TriMesh one_triangle = d.host;
  one_triangle.triangles.resize(1);
  TracedPolyline line;
  for (int t = 0; t < d.patch.mesh.num_triangles(); ++t)
    if (d.patch.host_triangle[t] > 0) {
      line.points = {centroid(t), centroid(t)};
      break;
    }
  EXPECT_EQ(status_of([&] { polylines_on_host(one_triangle, d.patch, {line}); }), MCON_ERROR_INVALID_ARGUMENT);
}
