#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "transfer/cross_field.h"
#include "base/error.h"
#include "io/mesh_io.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;
namespace fs = std::filesystem;

namespace {

const double kPi = std::acos(-1.0);

double deg(double radians) { return radians * 180.0 / kPi; }

// Angle between two crosses (4-symmetric), in [0, 45] degrees: the angle from u to v about n,
// reduced modulo 90 degrees.
double cross_angle_deg(const Vec3& u, const Vec3& v, const Vec3& n) {
  const double a = std::atan2(u.cross(v).dot(n), u.dot(v));
  return std::abs(deg(std::remainder(a, kPi / 2)));
}

Vec3 centroid(const TriMesh& m, int t) {
  const Tri& tri = m.triangles[t];
  return (m.positions[tri[0]] + m.positions[tri[1]] + m.positions[tri[2]]) / 3.0;
}

Vec3 planar(double angle_deg) {
  const double a = angle_deg * kPi / 180.0;
  return Vec3(std::cos(a), std::sin(a), 0.0);
}

// Angle of a cross on the z = 0 plane, in [0, 90) degrees.
double cross_angle_xy(const Vec3& d) {
  const double a = deg(std::atan2(d.y(), d.x()));
  return a - 90.0 * std::floor(a / 90.0);
}

// The surface point of a planar (z = 0) mesh at (x, y), by brute force.
SurfacePoint locate(const TriMesh& m, double x, double y) {
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Tri& tri = m.triangles[t];
    const Vec2 a = m.positions[tri[0]].head<2>(), b = m.positions[tri[1]].head<2>(), c = m.positions[tri[2]].head<2>();
    const Vec2 p(x, y);
    const double area = cross2(b - a, c - a);
    const double l0 = cross2(b - p, c - p) / area, l1 = cross2(c - p, a - p) / area, l2 = cross2(a - p, b - p) / area;
    if (l0 >= -1e-12 && l1 >= -1e-12 && l2 >= -1e-12) {
      Vec3 bary(std::max(l0, 0.0), std::max(l1, 0.0), std::max(l2, 0.0));
      return {t, bary / bary.sum()};
    }
  }
  ADD_FAILURE() << "point (" << x << ", " << y << ") is outside the mesh";
  return {};
}

// Per interior edge, the 4-symmetric angle between the crosses of its two faces after unfolding
// one face onto the other about the edge (the rotation taking one normal to the other).
std::vector<double> neighbor_jumps_deg(const TriMesh& m, const CrossField& f) {
  const MeshTopology topo = build_topology(m);
  std::vector<double> jumps;
  for (int e = 0; e < topo.num_edges(); ++e) {
    if (topo.is_boundary_edge(e)) continue;
    const int a = topo.edge_triangles[e][0], b = topo.edge_triangles[e][1];
    const Vec3 na = triangle_normal(m, a), nb = triangle_normal(m, b);
    const Vec3 unfolded = Eigen::Quaterniond::FromTwoVectors(nb, na) * f.directions[b];
    jumps.push_back(cross_angle_deg(f.directions[a], unfolded, na));
  }
  return jumps;
}

double max_neighbor_jump_deg(const TriMesh& m, const CrossField& f) {
  const std::vector<double> jumps = neighbor_jumps_deg(m, f);
  return *std::max_element(jumps.begin(), jumps.end());
}

void expect_unit_tangent(const TriMesh& m, const CrossField& f) {
  ASSERT_EQ(f.directions.size(), m.triangles.size());
  ASSERT_EQ(f.confidence.size(), m.triangles.size());
  for (int t = 0; t < m.num_triangles(); ++t) {
    EXPECT_NEAR(f.directions[t].norm(), 1.0, 1e-12) << t;
    EXPECT_NEAR(f.directions[t].dot(triangle_normal(m, t)), 0.0, 1e-12) << t;
    EXPECT_GE(f.confidence[t], 0.0);
    EXPECT_LE(f.confidence[t], 1.0);
  }
}

TEST(CrossField, StraightGuideOnFlatGridAlignsEverywhere) {
  const TriMesh m = test_meshes::make_grid(21, 1.0, 0.35);  // jittered: frames and weights vary
  // A guide at 30 degrees through the middle, sampled densely, found face by face.
  std::vector<SurfacePoint> line;
  const Vec3 dir = planar(30.0);
  for (double s = -0.45; s <= 0.45; s += 0.02) line.push_back(locate(m, 0.5 + s * dir.x(), 0.5 + s * dir.y()));
  const std::vector<DirectionConstraint> constraints = constraints_from_polylines(m, {line});
  ASSERT_GT(constraints.size(), 30u);
  const CrossField f = compute_cross_field(m, constraints);
  expect_unit_tangent(m, f);
  double worst = 0;
  for (int t = 0; t < m.num_triangles(); ++t) worst = std::max(worst, cross_angle_deg(f.directions[t], dir, Vec3::UnitZ()));
  EXPECT_LT(worst, 1e-6);
  // All guides agree, so every face is fully confident.
  for (double c : f.confidence) EXPECT_NEAR(c, 1.0, 1e-9);
}

TEST(CrossField, PerpendicularRegionsAreTheSameCross) {
  const TriMesh m = test_meshes::make_grid(25);
  std::vector<DirectionConstraint> constraints;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const double x = centroid(m, t).x();
    if (x < 0.25) constraints.push_back({t, planar(10.0), 1.0});
    if (x > 0.75) constraints.push_back({t, planar(100.0), 1.0});
  }
  const CrossField f = compute_cross_field(m, constraints);
  for (int t = 0; t < m.num_triangles(); ++t) EXPECT_LT(cross_angle_deg(f.directions[t], planar(10.0), Vec3::UnitZ()), 1e-6);
}

TEST(CrossField, TransitionsSmoothlyBetweenDifferentRegions) {
  const TriMesh m = test_meshes::make_grid(31);
  std::vector<DirectionConstraint> constraints;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const double x = centroid(m, t).x();
    if (x < 0.2) constraints.push_back({t, planar(0.0), 1.0});
    if (x > 0.8) constraints.push_back({t, planar(30.0), 1.0});
  }
  const CrossField f = compute_cross_field(m, constraints);
  expect_unit_tangent(m, f);
  // Constrained regions follow their guides; the field turns gradually in between.
  std::vector<double> column_sum(10, 0.0);
  std::vector<int> column_count(10, 0);
  for (int t = 0; t < m.num_triangles(); ++t) {
    const double x = centroid(m, t).x();
    double a = cross_angle_xy(f.directions[t]);
    if (a > 60) a -= 90;  // near 0 from below
    if (x < 0.2) {
      EXPECT_NEAR(a, 0.0, 1.0);
    }
    if (x > 0.8) {
      EXPECT_NEAR(a, 30.0, 1.0);
    }
    const int col = std::min(9, static_cast<int>(x * 10));
    column_sum[col] += a;
    ++column_count[col];
  }
  for (int c = 2; c < 8; ++c) {
    const double mean = column_sum[c] / column_count[c], previous = column_sum[c - 1] / column_count[c - 1];
    EXPECT_GT(mean, previous + 1.0) << "column " << c;  // strictly turning, no jump elsewhere
  }
  EXPECT_LT(max_neighbor_jump_deg(m, f), 2.0);
  // Constraints disagree in the middle: confidence drops below 1 but stays high (no singularity).
  double min_confidence = 1;
  for (double c : f.confidence) min_confidence = std::min(min_confidence, c);
  EXPECT_LT(min_confidence, 0.999);
  EXPECT_GT(min_confidence, 0.5);
}

TEST(CrossField, CylinderFieldFollowsTheAxis) {
  const TriMesh m = test_meshes::make_cylinder(1.0, 3.0, 32, 24);
  // Guide along the axis on one strip of the cylinder only.
  std::vector<DirectionConstraint> constraints;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Vec3 c = centroid(m, t);
    if (std::abs(std::atan2(c.y(), c.x())) < 0.2) constraints.push_back({t, Vec3::UnitZ(), 1.0});
  }
  ASSERT_GT(constraints.size(), 50u);
  const CrossField f = compute_cross_field(m, constraints);
  expect_unit_tangent(m, f);
  double worst = 0;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Vec3 n = triangle_normal(m, t);
    const Vec3 axis = (Vec3::UnitZ() - Vec3::UnitZ().dot(n) * n).normalized();
    worst = std::max(worst, cross_angle_deg(f.directions[t], axis, n));
  }
  EXPECT_LT(worst, 0.5);  // all the way around, on the far side too
  EXPECT_LT(max_neighbor_jump_deg(m, f), 0.5);
}

TEST(CrossField, SphereHasSingularitiesWhereConfidenceDrops) {
  const TriMesh m = test_meshes::make_icosphere(3);
  // Guides along the equator (direction east) near the front.
  std::vector<DirectionConstraint> constraints;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Vec3 c = centroid(m, t);
    if (std::abs(c.z()) < 0.1 && c.x() > 0.5) constraints.push_back({t, Vec3::UnitZ().cross(c), 1.0});
  }
  const CrossField f = compute_cross_field(m, constraints);
  expect_unit_tangent(m, f);
  double min_c = 1, max_c = 0;
  for (int t = 0; t < m.num_triangles(); ++t) {
    min_c = std::min(min_c, f.confidence[t]);
    max_c = std::max(max_c, f.confidence[t]);
    const Vec3 c = centroid(m, t);
    if (std::abs(c.z()) < 0.1 && c.x() > 0.5) {
      EXPECT_LT(cross_angle_deg(f.directions[t], Vec3::UnitZ().cross(c).normalized(), triangle_normal(m, t)), 3.0);
    }
  }
  EXPECT_GT(max_c, 0.9);
  EXPECT_LT(min_c, 0.5);  // a closed sphere needs singularities (index sum 2)
}

TEST(CrossField, ConstraintsAreProjectedIntoTheFacePlane) {
  const TriMesh m = test_meshes::make_grid(15);
  const CrossField in_plane = compute_cross_field(m, {{7, Vec3(1, 2, 0), 1.0}});
  const CrossField tilted = compute_cross_field(m, {{7, Vec3(1, 2, 0) + 5 * Vec3::UnitZ(), 1.0}});
  for (int t = 0; t < m.num_triangles(); ++t) {
    EXPECT_LT(cross_angle_deg(tilted.directions[t], Vec3(1, 2, 0).normalized(), Vec3::UnitZ()), 1e-9);
    EXPECT_LT((tilted.directions[t] - in_plane.directions[t]).norm(), 1e-12);
  }
  // On a curved mesh too: a direction with a normal component gives the same field as its
  // tangential part.
  const TriMesh cyl = test_meshes::make_cylinder(1.0, 2.0, 24, 12);
  const Vec3 n = triangle_normal(cyl, 30);
  const Vec3 tangent = (Vec3(0.3, -0.2, 1.0) - Vec3(0.3, -0.2, 1.0).dot(n) * n);
  const CrossField a = compute_cross_field(cyl, {{30, tangent, 1.0}});
  const CrossField b = compute_cross_field(cyl, {{30, tangent + 3.0 * n, 1.0}});
  for (int t = 0; t < cyl.num_triangles(); ++t) EXPECT_LT((a.directions[t] - b.directions[t]).norm(), 1e-9);
}

TEST(CrossField, BoundaryAlignmentWithoutGuides) {
  const TriMesh m = test_meshes::make_disk(12);
  CrossFieldOptions o;
  o.align_to_boundary = true;
  const CrossField f = compute_cross_field(m, {}, o);
  expect_unit_tangent(m, f);
  const MeshTopology topo = build_topology(m);
  double sum = 0;
  int count = 0;
  for (int e = 0; e < topo.num_edges(); ++e) {
    if (!topo.is_boundary_edge(e)) continue;
    const int t = topo.edge_triangles[e][0];
    const Vec3 d = m.positions[topo.edges[e][1]] - m.positions[topo.edges[e][0]];
    sum += cross_angle_deg(f.directions[t], d.normalized(), Vec3::UnitZ());
    ++count;
  }
  EXPECT_LT(sum / count, 3.0);
  double confident = 0;
  for (int t = 0; t < m.num_triangles(); ++t) confident = std::max(confident, f.confidence[t]);
  EXPECT_GT(confident, 0.9);
}

TEST(CrossField, SmoothestFieldWithoutConstraints) {
  // A flat disk has trivial holonomy: the smoothest cross field is parallel (constant).
  const TriMesh m = test_meshes::make_disk(10);
  const CrossField f = compute_cross_field(m, {});
  expect_unit_tangent(m, f);
  for (int t = 0; t < m.num_triangles(); ++t) {
    EXPECT_LT(cross_angle_deg(f.directions[t], f.directions[0], Vec3::UnitZ()), 1e-6) << t;
    EXPECT_EQ(f.confidence[t], 0.0);
  }
  // On a sphere it still returns unit tangent crosses, smooth away from the singularities: few
  // edges see a jump of more than a few degrees, unlike a random field.
  const TriMesh s = test_meshes::make_icosphere(3);
  const CrossField sf = compute_cross_field(s, {});
  expect_unit_tangent(s, sf);
  std::vector<double> jumps = neighbor_jumps_deg(s, sf);
  std::sort(jumps.begin(), jumps.end());
  EXPECT_LT(jumps[jumps.size() / 2], 1.5);  // measured 0.9
  EXPECT_LT(jumps[jumps.size() * 9 / 10], 5.0);  // measured 3.9
  EXPECT_GT(jumps.back(), 5.0);  // singularities exist (index sum 2)
}

TEST(CrossField, UnconstrainedComponentGetsSmoothestField) {
  TriMesh m = test_meshes::make_grid(9);
  const TriMesh other = test_meshes::make_grid(9);
  const int offset = m.num_vertices(), first_other = m.num_triangles();
  for (const Vec3& p : other.positions) m.positions.push_back(p + Vec3(3, 0, 0));
  for (const Tri& t : other.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const CrossField f = compute_cross_field(m, {{0, planar(20.0), 1.0}});
  expect_unit_tangent(m, f);
  for (int t = 0; t < first_other; ++t) {
    EXPECT_LT(cross_angle_deg(f.directions[t], planar(20.0), Vec3::UnitZ()), 1e-6);
    EXPECT_NEAR(f.confidence[t], 1.0, 1e-9);
  }
  for (int t = first_other; t < m.num_triangles(); ++t) {
    EXPECT_LT(cross_angle_deg(f.directions[t], f.directions[first_other], Vec3::UnitZ()), 1e-6);
    EXPECT_EQ(f.confidence[t], 0.0);
  }
}

TEST(CrossField, Deterministic) {
  const TriMesh m = test_meshes::make_icosphere(2);
  const std::vector<DirectionConstraint> c = {{5, Vec3(1, 0, 0), 1.0}, {200, Vec3(0, 1, 0), 2.0}};
  const CrossField a = compute_cross_field(m, c), b = compute_cross_field(m, c);
  ASSERT_EQ(a.directions.size(), b.directions.size());
  EXPECT_EQ(0, std::memcmp(a.directions.data(), b.directions.data(), a.directions.size() * sizeof(Vec3)));
  EXPECT_EQ(a.confidence, b.confidence);
  const CrossField e1 = compute_cross_field(m, {}), e2 = compute_cross_field(m, {});
  EXPECT_EQ(0, std::memcmp(e1.directions.data(), e2.directions.data(), e1.directions.size() * sizeof(Vec3)));
}

TEST(CrossField, PolylineSegmentsGoToTheFacesTheyTouch) {
  const TriMesh m = test_meshes::make_grid(5);  // 4 x 4 cells of side 0.25
  const SurfacePoint a = locate(m, 0.10, 0.05), b = locate(m, 0.20, 0.05), c = locate(m, 0.40, 0.05);
  ASSERT_EQ(a.triangle, b.triangle);
  ASSERT_NE(b.triangle, c.triangle);
  const double h = mean_edge_length(m);
  const std::vector<DirectionConstraint> out = constraints_from_polylines(m, {{a, b, b, c}}, 2.0);
  // a-b: one face; b-b: zero length, skipped; b-c: both end faces.
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].face, a.triangle);
  EXPECT_EQ(out[1].face, b.triangle);
  EXPECT_EQ(out[2].face, c.triangle);
  EXPECT_NEAR(out[0].weight, 2.0 * 0.10 / h, 1e-12);
  EXPECT_NEAR(out[2].weight, 2.0 * 0.20 / h, 1e-12);
  for (const auto& d : out) EXPECT_LT((d.direction - Vec3::UnitX()).norm(), 1e-12);
  EXPECT_TRUE(constraints_from_polylines(m, {{a}, {}}).empty());
}

TEST(CrossField, InvalidInput) {
  const TriMesh m = test_meshes::make_grid(5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string msg;
  auto run = [&](const std::vector<DirectionConstraint>& c, const CrossFieldOptions& o = {}) {
    return status_of([&] { compute_cross_field(m, c, o); }, &msg);
  };
  EXPECT_EQ(run({{32, Vec3::UnitX(), 1.0}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(msg.find("face 32 is out of range"), std::string::npos) << msg;
  EXPECT_EQ(run({{-1, Vec3::UnitX(), 1.0}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(run({{0, Vec3(nan, 0, 0), 1.0}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
  EXPECT_EQ(run({{0, Vec3::UnitX(), 0.0}, {3, Vec3::UnitY(), 0.0}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(msg.find("weights are zero"), std::string::npos) << msg;
  EXPECT_EQ(run({{0, Vec3::UnitX(), -1.0}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(run({{0, Vec3::UnitX(), nan}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(run({{0, Vec3::Zero(), 1.0}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(run({{0, Vec3::UnitZ(), 1.0}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(msg.find("normal to face 0"), std::string::npos) << msg;
  CrossFieldOptions o;
  o.alignment_weight = 0;
  EXPECT_EQ(run({{0, Vec3::UnitX(), 1.0}}, o), MCON_ERROR_INVALID_ARGUMENT);
  o = {};
  o.boundary_weight = -1;
  EXPECT_EQ(run({}, o), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([] { compute_cross_field(TriMesh{}, {}); }), MCON_ERROR_EMPTY_MESH);
  // Zero-weight constraints next to a positive one are fine.
  EXPECT_EQ(run({{0, Vec3::UnitX(), 0.0}, {1, Vec3::UnitY(), 1.0}}), MCON_OK);

  auto poly = [&](const std::vector<std::vector<SurfacePoint>>& p, double w = 1.0) {
    return status_of([&] { constraints_from_polylines(m, p, w); }, &msg);
  };
  EXPECT_EQ(poly({{{0, Vec3(1, 0, 0)}, {99, Vec3(1, 0, 0)}}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(msg.find("polyline 0 point 1"), std::string::npos) << msg;
  EXPECT_EQ(poly({{{0, Vec3(0.5, 0.6, 0)}}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(poly({{{0, Vec3(nan, 0.5, 0.5)}}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(poly({{{0, Vec3(-0.5, 1.0, 0.5)}}}), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(poly({}, -1.0), MCON_ERROR_INVALID_ARGUMENT);
}

class QuadWildFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("macrocon_cross_field_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read_bytes(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  void write_text(const std::string& p, const std::string& text) const { std::ofstream(p, std::ios::binary) << text; }

  fs::path dir_;
};

TEST_F(QuadWildFiles, RosyExactFormat) {
  TriMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(2, 0, 0)};
  m.triangles = {{0, 1, 2}, {1, 3, 2}, {1, 4, 3}};
  io::write_rosy(path("f.rosy"), m, {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0.6, 0.8, 0)});
  EXPECT_EQ(read_bytes(path("f.rosy")),
            "3\n4\n1.000000 0.000000 0.000000 \n0.000000 -1.000000 0.000000 \n0.600000 0.800000 0.000000 \n");
  // Byte-identical to vcglib's fprintf("%f %f %f \n", (float)x, ...) on arbitrary values.
  std::vector<Vec3> dirs;
  TriMesh big = test_meshes::make_grid(6);
  for (int t = 0; t < big.num_triangles(); ++t) {
    const double a = 0.37 * t * t + 0.1;
    dirs.push_back(Vec3(std::cos(a) * 1e-3 * t, -std::sin(a), 1e-7 * (t - 20)));
  }
  io::write_rosy(path("g.rosy"), big, dirs);
  std::string expected = std::to_string(dirs.size()) + "\n4\n";
  char line[128];
  for (const Vec3& d : dirs) {
    std::snprintf(line, sizeof(line), "%f %f %f \n", static_cast<float>(d.x()), static_cast<float>(d.y()),
                  static_cast<float>(d.z()));
    expected += line;
  }
  EXPECT_EQ(read_bytes(path("g.rosy")), expected);
}

TEST_F(QuadWildFiles, RosyRoundTrip) {
  const TriMesh m = test_meshes::make_cylinder(1.0, 2.0, 16, 6);
  std::vector<DirectionConstraint> c;
  for (int t = 0; t < 10; ++t) c.push_back({t, Vec3::UnitZ(), 1.0});
  const CrossField f = compute_cross_field(m, c);
  io::write_rosy(path("c.rosy"), m, f.directions);
  const std::vector<Vec3> back = io::read_rosy(path("c.rosy"));
  ASSERT_EQ(back.size(), f.directions.size());
  for (std::size_t t = 0; t < back.size(); ++t) EXPECT_LT((back[t] - f.directions[t]).norm(), 2e-6) << t;
  // QuadWild reads a .rosy.gz as zeros: writing one is refused, by name.
  std::string message;
  EXPECT_EQ(status_of([&] { io::write_rosy(path("c.rosy.gz"), m, f.directions); }, &message),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find("without .gz"), std::string::npos) << message;
  EXPECT_EQ(status_of([&] { io::write_sharp(path("c.sharp.GZ"), m, {}); }), MCON_ERROR_INVALID_ARGUMENT);
}

TEST_F(QuadWildFiles, RosyErrors) {
  const TriMesh m = test_meshes::make_grid(3);
  EXPECT_EQ(status_of([&] { io::write_rosy(path("a.rosy"), m, {Vec3::UnitX()}); }), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Vec3> dirs(m.triangles.size(), Vec3::UnitX());
  dirs[2].x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(status_of([&] { io::write_rosy(path("a.rosy"), m, dirs); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { io::write_rosy(path("no/such/dir/a.rosy"), m, std::vector<Vec3>(8, Vec3::UnitX())); }),
            MCON_ERROR_IO);
  write_text(path("sym.rosy"), "1\n2\n1 0 0\n");
  EXPECT_EQ(status_of([&] { io::read_rosy(path("sym.rosy")); }), MCON_ERROR_UNSUPPORTED);
  write_text(path("short.rosy"), "2\n4\n1 0 0\n0 1\n");
  std::string msg;
  EXPECT_EQ(status_of([&] { io::read_rosy(path("short.rosy")); }, &msg), MCON_ERROR_IO);
  EXPECT_NE(msg.find("short.rosy:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("found end of file"), std::string::npos) << msg;
  write_text(path("long.rosy"), "1\n4\n1 0 0\n0 1 0\n");
  EXPECT_EQ(status_of([&] { io::read_rosy(path("long.rosy")); }), MCON_ERROR_IO);
  write_text(path("nan.rosy"), "1\n4\nnan 0 0\n");
  EXPECT_EQ(status_of([&] { io::read_rosy(path("nan.rosy")); }), MCON_ERROR_IO);
  write_text(path("huge.rosy"), "99999999999\n4\n");
  EXPECT_EQ(status_of([&] { io::read_rosy(path("huge.rosy")); }), MCON_ERROR_IO);
  EXPECT_EQ(status_of([&] { io::read_rosy(path("missing.rosy")); }), MCON_ERROR_IO);
}

TEST_F(QuadWildFiles, SharpFormatAndConvexity) {
  // A roof: two triangles folded up along the ridge (convex seen from above), then a valley.
  TriMesh roof;
  roof.positions = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0)};
  roof.triangles = {{0, 1, 2}, {1, 0, 3}};  // both CCW seen from above
  ASSERT_GT(triangle_normal(roof, 0).z(), 0);
  ASSERT_GT(triangle_normal(roof, 1).z(), 0);
  io::write_sharp(path("roof.sharp"), roof, {{1, 0}, {2, 1}, {0, 1}});
  // Ridge (0,1): face 0, VCG edge 0 (corner 0 -> corner 1), convex. Boundary edge (1,2): face 0
  // edge 1, convex. The repeated ridge is written once.
  EXPECT_EQ(read_bytes(path("roof.sharp")), "2\n1,0,0\n1,0,1\n");

  TriMesh valley = roof;
  for (Vec3& p : valley.positions) p.z() = -p.z();
  valley.triangles = {{0, 1, 2}, {1, 0, 3}};
  ASSERT_GT(triangle_normal(valley, 0).z(), 0);
  io::write_sharp(path("valley.sharp"), valley, {{0, 1}});
  EXPECT_EQ(read_bytes(path("valley.sharp")), "1\n0,0,0\n");

  const std::vector<io::SharpEdge> edges = io::read_sharp(path("roof.sharp"));
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_TRUE(edges[0].convex);
  EXPECT_EQ(edges[0].face, 0);
  EXPECT_EQ(edges[0].edge, 0);
  EXPECT_EQ(edges[1].edge, 1);
  const std::vector<io::SharpEdge> v = io::read_sharp(path("valley.sharp"));
  ASSERT_EQ(v.size(), 1u);
  EXPECT_FALSE(v[0].convex);
}

TEST_F(QuadWildFiles, SharpOnACubeMarksEveryFoldConvex) {
  // Closed cube (outward): all 12 fold edges convex, and each maps back to its vertex pair.
  TriMesh cube;
  for (int v = 0; v < 8; ++v) cube.positions.push_back(Vec3(v & 1, (v >> 1) & 1, (v >> 2) & 1));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    cube.triangles.push_back({q[0], q[1], q[2]});
    cube.triangles.push_back({q[0], q[2], q[3]});
  }
  std::vector<std::array<int, 2>> folds;
  for (int a = 0; a < 8; ++a)
    for (int b = a + 1; b < 8; ++b)
      if (__builtin_popcount(static_cast<unsigned>(a ^ b)) == 1) folds.push_back({a, b});
  ASSERT_EQ(folds.size(), 12u);
  io::write_sharp(path("cube.sharp"), cube, folds);
  const std::vector<io::SharpEdge> edges = io::read_sharp(path("cube.sharp"));
  ASSERT_EQ(edges.size(), 12u);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    EXPECT_TRUE(edges[i].convex);
    const Tri& tri = cube.triangles[edges[i].face];
    const int a = tri[edges[i].edge], b = tri[(edges[i].edge + 1) % 3];
    EXPECT_EQ(std::min(a, b), folds[i][0]);
    EXPECT_EQ(std::max(a, b), folds[i][1]);
  }
}

TEST_F(QuadWildFiles, SharpErrors) {
  const TriMesh m = test_meshes::make_grid(3);
  std::string msg;
  EXPECT_EQ(status_of([&] { io::write_sharp(path("a.sharp"), m, {{0, 8}}); }, &msg), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(msg.find("(0, 8) is not an edge"), std::string::npos) << msg;
  EXPECT_EQ(status_of([&] { io::write_sharp(path("a.sharp"), m, {{0, 0}}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { io::write_sharp(path("a.sharp"), m, {{0, 99}}); }), MCON_ERROR_INVALID_ARGUMENT);
  io::write_sharp(path("empty.sharp"), m, {});
  EXPECT_EQ(read_bytes(path("empty.sharp")), "0\n");
  EXPECT_TRUE(io::read_sharp(path("empty.sharp")).empty());
  write_text(path("bad.sharp"), "1\n2,0,0\n");
  EXPECT_EQ(status_of([&] { io::read_sharp(path("bad.sharp")); }), MCON_ERROR_IO);
  write_text(path("bad2.sharp"), "1\n1,0,3\n");
  EXPECT_EQ(status_of([&] { io::read_sharp(path("bad2.sharp")); }), MCON_ERROR_IO);
  write_text(path("bad3.sharp"), "2\n1,0,1\n");
  EXPECT_EQ(status_of([&] { io::read_sharp(path("bad3.sharp")); }), MCON_ERROR_IO);
  write_text(path("bad4.sharp"), "1\n1 0 1\n");
  EXPECT_EQ(status_of([&] { io::read_sharp(path("bad4.sharp")); }), MCON_ERROR_IO);
}

}  // namespace
