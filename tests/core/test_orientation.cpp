// Winding repair (mesh/orientation.h): consistent and outward per component, reported, and results
// that do not depend on the input's winding.
#include <gtest/gtest.h>

#include <cmath>

#include "base/counter_rng.h"
#include "base/error.h"
#include "descriptors/curvature_descriptors.h"
#include "mesh/orientation.h"
#include "patch/geodesic_disk_patch.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

void reverse(Tri& t) { std::swap(t[1], t[2]); }

TriMesh flipped_all(TriMesh m) {
  for (Tri& t : m.triangles) reverse(t);
  return m;
}

// Reverses about half of the triangles (never none, never all), seeded.
TriMesh flipped_subset(TriMesh m, std::uint64_t seed) {
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (t == 1 || (t != 0 && counter_uniform(seed, 7, t) < 0.5)) reverse(m.triangles[t]);
  return m;
}

// A closed, bumpy, nothing-symmetric surface: an icosphere with radial waves.
TriMesh bumpy_sphere() {
  TriMesh m = test_meshes::make_icosphere(4);
  for (Vec3& p : m.positions)
    p *= 1.0 + 0.15 * std::sin(3 * p.x() + 1) * std::cos(2 * p.y()) +
         0.1 * std::exp(-(p - Vec3(0, 0, 1)).squaredNorm() / 0.05);
  return m;
}

mcon_status status_of_orient(TriMesh m) {
  try {
    orient_and_validate(m);
  } catch (const Error& e) {
    return e.status();
  }
  return MCON_OK;
}

}  // namespace

TEST(Orientation, ConsistentOutwardMeshesAreUnchanged) {
  for (const TriMesh& original : {bumpy_sphere(), test_meshes::make_bumpy_grid(20), test_meshes::make_grid(6)}) {
    TriMesh m = original;
    const OrientationReport r = orient_and_validate(m);
    EXPECT_EQ(m.triangles, original.triangles);
    EXPECT_EQ(r.components, 1);
    EXPECT_EQ(r.reoriented_triangles, 0);
    EXPECT_EQ(r.inconsistent_components, 0);
    EXPECT_EQ(r.components_turned_outward, 0);
  }
}

TEST(Orientation, InwardClosedAndOpenComponentsAreTurnedOutward) {
  for (const TriMesh& original : {bumpy_sphere(), test_meshes::make_bumpy_grid(20)}) {
    TriMesh m = flipped_all(original);
    const OrientationReport r = orient_and_validate(m);
    EXPECT_EQ(m.triangles, original.triangles);  // corners 1 and 2 swapped back: bit-identical
    EXPECT_EQ(r.reoriented_triangles, original.num_triangles());
    EXPECT_EQ(r.components_turned_outward, 1);
    EXPECT_EQ(r.inconsistent_components, 0);
  }
  const OrientationReport closed = [] {
    TriMesh m = flipped_all(bumpy_sphere());
    return orient_mesh(m);
  }();
  EXPECT_EQ(closed.closed_components, 1);
}

TEST(Orientation, InconsistentTrianglesAreRepairedAndReported) {
  const TriMesh original = bumpy_sphere();
  const TriMesh input = flipped_subset(original, 3);
  TriMesh m = input;
  int flipped = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) flipped += m.triangles[t] != original.triangles[t];
  // Without the repair this mesh is rejected (two triangles run an edge the same way).
  TriMesh unrepaired = m;
  EXPECT_THROW(validate_mesh(unrepaired), Error);
  const OrientationReport r = orient_and_validate(m);
  EXPECT_EQ(m.triangles, original.triangles);
  EXPECT_EQ(r.reoriented_triangles, flipped);
  EXPECT_EQ(r.inconsistent_components, 1);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    EXPECT_EQ(r.reoriented[t] != 0, input.triangles[t] != original.triangles[t]) << "triangle " << t;
}

TEST(Orientation, FlatOpenComponentsKeepTheirMajority) {
  // A plane has no outside: the majority of its triangles decides, an all-flipped plane stays.
  const TriMesh grid = test_meshes::make_grid(8);
  TriMesh all = flipped_all(grid);
  EXPECT_EQ(orient_and_validate(all).reoriented_triangles, 0);
  EXPECT_EQ(all.triangles, flipped_all(grid).triangles);
  TriMesh few = grid;
  reverse(few.triangles[5]);
  reverse(few.triangles[17]);
  const OrientationReport r = orient_and_validate(few);
  EXPECT_EQ(r.reoriented_triangles, 2);
  EXPECT_EQ(few.triangles, grid.triangles);
}

TEST(Orientation, MajorityRuleNeverTurnsAConsistentComponent) {
  const TriMesh inward = flipped_all(test_meshes::make_bumpy_grid(20));
  TriMesh m = inward;
  const OrientationReport r = orient_and_validate(m, OrientationRule::majority);
  EXPECT_EQ(r.reoriented_triangles, 0);
  EXPECT_EQ(m.triangles, inward.triangles);
}

TEST(Orientation, ComponentsAreOrientedIndependently) {
  const TriMesh a = bumpy_sphere();
  TriMesh both = a;
  const int offset = a.num_vertices();
  for (const Vec3& p : a.positions) both.positions.push_back(p + Vec3(5, 0, 0));
  for (Tri t : a.triangles) {
    for (int& v : t) v += offset;
    reverse(t);  // the second copy faces inward
    both.triangles.push_back(t);
  }
  const OrientationReport r = orient_and_validate(both);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.components_turned_outward, 1);
  EXPECT_EQ(r.reoriented_triangles, a.num_triangles());
  for (int t = 0; t < a.num_triangles(); ++t) EXPECT_EQ(r.reoriented[t], 0);
}

TEST(Orientation, MoebiusStripIsNotOrientable) {
  TriMesh m;
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double u = 2 * M_PI * i / n;
    for (const double s : {-0.3, 0.3})
      m.positions.emplace_back((1 + s * std::cos(u / 2)) * std::cos(u), (1 + s * std::cos(u / 2)) * std::sin(u),
                               s * std::sin(u / 2));
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    // The last quad joins the strip with a half twist: bottom meets top.
    const int c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    m.triangles.push_back({a, c, d});
    m.triangles.push_back({a, d, b});
  }
  EXPECT_EQ(status_of_orient(m), MCON_ERROR_NON_ORIENTABLE);
  try {
    orient_mesh(m);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not orientable"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cut the surface"), std::string::npos) << e.what();
  }
}

TEST(Orientation, BadElementsKeepTheirOwnErrors) {
  TriMesh m = test_meshes::make_grid(4);
  m.triangles.push_back(m.triangles[0]);
  reverse(m.triangles.back());  // a third triangle on two edges of triangle 0
  m.triangles.push_back(m.triangles[0]);
  EXPECT_EQ(status_of_orient(m), MCON_ERROR_NON_MANIFOLD_EDGE);
  TriMesh r = test_meshes::make_grid(4);
  r.triangles[2][1] = r.triangles[2][0];
  EXPECT_EQ(status_of_orient(r), MCON_ERROR_REPEATED_INDEX);
  TriMesh o = test_meshes::make_grid(4);
  o.triangles[2][1] = 99;
  EXPECT_EQ(status_of_orient(o), MCON_ERROR_INDEX_OUT_OF_RANGE);
  TriMesh nan = test_meshes::make_grid(4);
  nan.positions[3].x() = NAN;
  EXPECT_EQ(status_of_orient(nan), MCON_ERROR_NON_FINITE);
}

// The regression test of the issue: a host whose triangles face inward (all of them, or a random
// half) gives the same patch and the same descriptors, bit for bit.
TEST(Orientation, PatchAndDescriptorsDoNotDependOnTheInputWinding) {
  const TriMesh original = bumpy_sphere();
  PatchOptions po;
  po.center.vertex = 17;
  po.radius = 0.8;
  TriMesh reference = original;
  orient_and_validate(reference);
  const Patch want = extract_geodesic_disk(reference, po);
  const Eigen::MatrixXd want_curv9 = curv9_descriptor(want.mesh);
  for (int variant = 0; variant < 3; ++variant) {
    TriMesh m = variant == 0 ? flipped_all(original) : flipped_subset(original, static_cast<std::uint64_t>(variant));
    const OrientationReport r = orient_and_validate(m);
    EXPECT_GT(r.reoriented_triangles, 0);
    const Patch got = extract_geodesic_disk(m, po);
    ASSERT_EQ(got.mesh.triangles, want.mesh.triangles) << "variant " << variant;
    ASSERT_EQ(got.mesh.positions, want.mesh.positions) << "variant " << variant;
    EXPECT_EQ(got.uv, want.uv);
    const Eigen::MatrixXd curv9 = curv9_descriptor(got.mesh);
    EXPECT_EQ((curv9 - want_curv9).cwiseAbs().maxCoeff(), 0.0) << "variant " << variant;
  }
  // Without the repair the flipped host's descriptors differ (the mean curvature changes sign).
  const Patch unrepaired = extract_geodesic_disk(flipped_all(original), po);
  EXPECT_GT((curv9_descriptor(unrepaired.mesh) - want_curv9).cwiseAbs().maxCoeff(), 1e-3);
}
