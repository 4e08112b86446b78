#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/error.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

mcon_status status_of(const TriMesh& m) {
  try {
    validate_mesh(m);
  } catch (const Error& e) {
    return e.status();
  }
  return MCON_OK;
}

}  // namespace

TEST(Mesh, AnalyticMeshesAreValidAndHaveExpectedTopology) {
  const TriMesh grid = test_meshes::make_grid(10);
  EXPECT_EQ(status_of(grid), MCON_OK);
  MeshTopology t = build_topology(grid);
  EXPECT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_EQ(euler_characteristic(grid, t), 1);

  const TriMesh sphere = test_meshes::make_icosphere(3);
  EXPECT_EQ(status_of(sphere), MCON_OK);
  t = build_topology(sphere);
  EXPECT_TRUE(t.boundary_loops.empty());
  EXPECT_EQ(euler_characteristic(sphere, t), 2);
  EXPECT_NEAR(total_area(sphere), 4 * M_PI, 0.08);  // inscribed: 0.5% short at 642 vertices

  const TriMesh cyl = test_meshes::make_cylinder(1, 2, 32, 10);
  EXPECT_EQ(status_of(cyl), MCON_OK);
  t = build_topology(cyl);
  EXPECT_EQ(t.boundary_loops.size(), 2u);
  EXPECT_EQ(euler_characteristic(cyl, t), 0);

  const TriMesh disk = test_meshes::make_disk(8);
  EXPECT_EQ(status_of(disk), MCON_OK);
  t = build_topology(disk);
  ASSERT_EQ(t.boundary_loops.size(), 1u);
  EXPECT_EQ(t.boundary_loops[0].size(), 48u);
  EXPECT_EQ(euler_characteristic(disk, t), 1);
}

TEST(Mesh, BoundaryLoopFollowsTriangleWinding) {
  const TriMesh grid = test_meshes::make_grid(3);
  const MeshTopology t = build_topology(grid);
  ASSERT_EQ(t.boundary_loops.size(), 1u);
  // Counter-clockwise grid: the loop must have positive signed area in the xy plane.
  double area = 0;
  const auto& loop = t.boundary_loops[0];
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3& a = grid.positions[loop[i]];
    const Vec3& b = grid.positions[loop[(i + 1) % loop.size()]];
    area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_GT(area, 0);
}

TEST(Mesh, EachDefectHasItsOwnStatus) {
  TriMesh m = test_meshes::make_grid(4);
  m.positions[5].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(status_of(m), MCON_ERROR_NON_FINITE);

  m = test_meshes::make_grid(4);
  m.triangles[2][1] = 99;
  EXPECT_EQ(status_of(m), MCON_ERROR_INDEX_OUT_OF_RANGE);

  m = test_meshes::make_grid(4);
  m.triangles[2][1] = m.triangles[2][0];
  EXPECT_EQ(status_of(m), MCON_ERROR_REPEATED_INDEX);

  m = test_meshes::make_grid(4);
  m.positions.push_back(m.positions[0]);
  m.positions.push_back(m.positions[1]);
  m.positions.push_back(m.positions[0] * 0.5 + m.positions[1] * 0.5);  // collinear
  m.triangles.push_back({16, 17, 18});
  EXPECT_EQ(status_of(m), MCON_ERROR_DEGENERATE_TRIANGLE);

  m = test_meshes::make_grid(4);
  m.positions.emplace_back(0.5, 0.5, 1.0);
  m.triangles.push_back({0, 1, 16});  // a third triangle on edge (0, 1)... same direction as first
  EXPECT_EQ(status_of(m), MCON_ERROR_NON_MANIFOLD_EDGE);

  // Two grids touching at one vertex: a bow-tie vertex.
  m = test_meshes::make_grid(3);
  const int n = m.num_vertices();
  TriMesh other = test_meshes::make_grid(3);
  for (auto& p : other.positions) p += Vec3(2, 2, 0);
  m.positions.insert(m.positions.end(), other.positions.begin(), other.positions.end());
  for (Tri tri : other.triangles) {
    for (int& v : tri) v = (v == 0) ? 8 : v + n;  // other's corner 0 is glued onto m's corner 8
    m.triangles.push_back(tri);
  }
  m.positions[n] = m.positions[8];
  remove_unreferenced_vertices(m);  // other's corner 0 (vertex n) is unused now
  EXPECT_EQ(status_of(m), MCON_ERROR_NON_MANIFOLD_VERTEX);

  m = test_meshes::make_grid(4);
  m.positions.emplace_back(5, 5, 5);
  EXPECT_EQ(status_of(m), MCON_ERROR_ISOLATED_VERTEX);
  EXPECT_NO_THROW(validate_mesh_allow_isolated(m));
  const auto remap = remove_unreferenced_vertices(m);
  EXPECT_EQ(remap.back(), -1);
  EXPECT_EQ(status_of(m), MCON_OK);

  m = TriMesh{};
  EXPECT_EQ(status_of(m), MCON_ERROR_EMPTY_MESH);
}

// One error names every offender's count and the first few, so all can be fixed in one pass.
std::string validation_message(const TriMesh& m) {
  try {
    validate_mesh(m);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Mesh, AnErrorCountsEveryOffenderAndNamesTheFirstFew) {
  TriMesh m = test_meshes::make_grid(4);
  for (int k = 0; k < 3; ++k) m.positions.emplace_back(5, 5, 5 + k);
  EXPECT_EQ(validation_message(m),
            "vertex 16 is not used by any triangle (3 vertices are used by no triangle in all: 16, 17, 18)");

  for (int k = 0; k < 7; ++k) m.positions.emplace_back(6, 5, 5 + k);
  EXPECT_EQ(validation_message(m),
            "vertex 16 is not used by any triangle (10 vertices are used by no triangle in all, the first 8: 16, "
            "17, 18, 19, 20, 21, 22, 23)");

  // Two zero-area triangles (a corner moved onto the opposite edge's line) and one alone.
  m = test_meshes::make_grid(4);
  for (int t : {3, 11}) {
    const Tri tri = m.triangles[t];
    m.positions.push_back(m.positions[tri[0]]);
    m.positions.push_back(m.positions[tri[1]]);
    m.positions.push_back(0.5 * (m.positions[tri[0]] + m.positions[tri[1]]));
    const int n = m.num_vertices();
    m.triangles.push_back({n - 3, n - 2, n - 1});
  }
  const std::string two = validation_message(m);
  EXPECT_EQ(two, "triangle 18 has zero area (2 triangles have zero area in all: 18, 19)") << two;
  m.triangles.pop_back();
  m.positions.resize(m.positions.size() - 3);
  EXPECT_EQ(validation_message(m), "triangle 18 has zero area");
}

TEST(Mesh, FromStridedFloatArrays) {
  // Interleaved float positions with a padding float, and padded index records.
  const float data[4][4] = {{0, 0, 0, 9}, {1, 0, 0, 9}, {1, 1, 0, 9}, {0, 1, 0, 9}};
  const std::uint32_t idx[2][4] = {{0, 1, 2, 77}, {0, 2, 3, 77}};
  MeshArrays a;
  a.positions = data;
  a.positions_are_double = false;
  a.position_stride = sizeof(data[0]);
  a.vertex_count = 4;
  a.indices = &idx[0][0];
  a.index_stride = sizeof(idx[0]);
  a.triangle_count = 2;
  const TriMesh m = mesh_from_arrays(a);
  EXPECT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.triangles[1][2], 3);
  EXPECT_DOUBLE_EQ(m.positions[2].y(), 1.0);

  a.position_stride = 8;  // smaller than a position
  EXPECT_THROW(mesh_from_arrays(a), Error);
}
