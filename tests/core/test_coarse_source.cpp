// The coarse copy of a source disk (map/coarse_source.h): a valid triangulation of the same uv
// disk with the rim kept, an exact prolongation of affine maps, and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "base/error.h"
#include "map/coarse_source.h"
#include "mesh/mesh_topology.h"
#include "synthetic_maps.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

double signed_area(const std::vector<Vec2>& uv, const Tri& t) {
  const Vec2 a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

std::set<int> boundary_vertices(const TriMesh& m) {
  const MeshTopology topology = build_topology(m);
  std::set<int> out;
  for (int e = 0; e < topology.num_edges(); ++e)
    if (topology.is_boundary_edge(e)) out.insert({topology.edges[e][0], topology.edges[e][1]});
  return out;
}

struct Disk {
  TriMesh mesh = synthetic::make_jittered_disk(24, 0.3);
  std::vector<Vec2> uv = synthetic::planar_uv(mesh);
};

}  // namespace

TEST(CoarseSource, ACoarseDiskKeepsTheRimAndCoversTheSameUvArea) {
  const Disk d;
  const int n = d.mesh.num_vertices();  // 1801
  const std::optional<CoarseSource> c = coarsen_source(d.mesh, d.uv, n / 4);
  ASSERT_TRUE(c.has_value());
  EXPECT_LE(c->num_vertices(), n / 3) << "collapses stopped early";
  EXPECT_GE(c->num_vertices(), n / 4);
  // The rim: every fine boundary vertex survives and is a coarse boundary vertex.
  std::set<int> rim;
  for (int v : boundary_vertices(c->mesh)) rim.insert(c->to_fine[v]);
  EXPECT_EQ(rim, boundary_vertices(d.mesh));
  // One disk of the same area, every triangle positive; new triangles at least 15 degrees.
  const MeshTopology topology = build_topology(c->mesh);
  EXPECT_EQ(euler_characteristic(c->mesh, topology), 1);
  EXPECT_EQ(topology.boundary_loops.size(), 1u);
  double fine_area = 0, coarse_area = 0, smallest_new = 180;
  for (const Tri& t : d.mesh.triangles) fine_area += signed_area(d.uv, t);
  std::set<std::array<int, 3>> fine_triangles;
  for (Tri t : d.mesh.triangles) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    fine_triangles.insert(t);
  }
  for (const Tri& t : c->mesh.triangles) {
    const double a = signed_area(c->uv, t);
    ASSERT_GT(a, 0);
    coarse_area += a;
    Tri f{c->to_fine[t[0]], c->to_fine[t[1]], c->to_fine[t[2]]};
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    if (fine_triangles.count(f)) continue;
    for (int k = 0; k < 3; ++k) {
      const Vec2 e1 = c->uv[t[(k + 1) % 3]] - c->uv[t[k]], e2 = c->uv[t[(k + 2) % 3]] - c->uv[t[k]];
      smallest_new = std::min(smallest_new, std::acos(e1.dot(e2) / (e1.norm() * e2.norm())) * 180 / 3.141592653589793);
    }
  }
  EXPECT_NEAR(coarse_area, fine_area, 1e-12 * fine_area);
  EXPECT_GE(smallest_new, 15 - 1e-9);
  // Surviving vertices keep their uv and 3D position.
  for (int k = 0; k < c->num_vertices(); ++k) {
    EXPECT_EQ(c->uv[k], d.uv[c->to_fine[k]]);
    EXPECT_EQ(c->mesh.positions[k], d.mesh.positions[c->to_fine[k]]);
  }
}

TEST(CoarseSource, ProlongationIsExactForAffineMapsAndKeepsTheCoarseVertices) {
  const Disk d;
  const std::optional<CoarseSource> c = coarsen_source(d.mesh, d.uv, 500);
  ASSERT_TRUE(c.has_value());
  Eigen::Matrix2d A;
  A << 0.8, -0.3, 0.4, 1.1;
  const Vec2 b(0.2, -0.1);
  Eigen::VectorXd xc(2 * c->num_vertices());
  for (int k = 0; k < c->num_vertices(); ++k) xc.segment<2>(2 * k) = A * c->uv[k] + b;
  const Eigen::VectorXd xf = c->prolong(xc);
  ASSERT_EQ(xf.size(), 2 * d.mesh.num_vertices());
  for (int v = 0; v < d.mesh.num_vertices(); ++v)
    ASSERT_LE((xf.segment<2>(2 * v) - (A * d.uv[v] + b)).norm(), 1e-12) << v;
  for (int k = 0; k < c->num_vertices(); ++k) EXPECT_EQ(xf.segment<2>(2 * c->to_fine[k]), xc.segment<2>(2 * k));
  Eigen::MatrixXd rows(d.mesh.num_vertices(), 2);
  for (int v = 0; v < d.mesh.num_vertices(); ++v) rows.row(v) << v, -v;
  const Eigen::MatrixXd r = c->restrict_rows(rows);
  for (int k = 0; k < c->num_vertices(); ++k) EXPECT_EQ(r(k, 0), c->to_fine[k]);
}

TEST(CoarseSource, DeterministicAndNothingWhenTooFewCollapses) {
  const Disk d;
  const std::optional<CoarseSource> a = coarsen_source(d.mesh, d.uv, 600), b = coarsen_source(d.mesh, d.uv, 600);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->to_fine, b->to_fine);
  EXPECT_EQ(a->mesh.triangles, b->mesh.triangles);
  EXPECT_FALSE(coarsen_source(d.mesh, d.uv, 600, 0.1).has_value());  // 600 of 1801 kept > 10 %
  // A 90-degree minimum angle blocks every collapse.
  EXPECT_FALSE(coarsen_source(d.mesh, d.uv, 600, 0.9, 90).has_value());
  std::vector<Vec2> short_uv(d.uv.begin(), d.uv.end() - 1);
  EXPECT_EQ(status_of([&] { coarsen_source(d.mesh, short_uv, 600); }), MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CoarseSource, UntangleFoldsMendsALocalFoldAndReportsWhatItCannot) {
  const Disk d;
  Eigen::VectorXd x(2 * d.mesh.num_vertices());
  for (int v = 0; v < d.mesh.num_vertices(); ++v) x.segment<2>(2 * v) = 0.9 * d.uv[v];
  Eigen::VectorXd ok = x;
  EXPECT_TRUE(untangle_folds(d.mesh.triangles, d.uv, ok));
  EXPECT_EQ(ok, x);  // nothing folded, nothing moved
  // Push vertex 0 (the center) across its ring: its whole star folds or flips.
  x.segment<2>(0) = Vec2(0.2, 0.1);
  int folded_before = 0;
  for (const Tri& t : d.mesh.triangles) {
    const Vec2 a = x.segment<2>(2 * t[1]) - x.segment<2>(2 * t[0]), b = x.segment<2>(2 * t[2]) - x.segment<2>(2 * t[0]);
    folded_before += !(a.x() * b.y() - a.y() * b.x() > 0);
  }
  ASSERT_GT(folded_before, 0);
  EXPECT_TRUE(untangle_folds(d.mesh.triangles, d.uv, x));
  for (const Tri& t : d.mesh.triangles) {
    const Vec2 a = x.segment<2>(2 * t[1]) - x.segment<2>(2 * t[0]), b = x.segment<2>(2 * t[2]) - x.segment<2>(2 * t[0]);
    ASSERT_GT(a.x() * b.y() - a.y() * b.x(), 0);
  }
  // The mean-value weights of the rest disk reproduce the affine map around the fold: the center
  // lands back where 0.9 uv puts it (uniform weights would not, on this jittered disk).
  EXPECT_NEAR((x.segment<2>(0) - 0.9 * d.uv[0]).norm(), 0.0, 1e-12);
  // The same for a sheared, rotated, translated map.
  const Eigen::Matrix2d a{{0.8, 0.5}, {-0.3, 1.1}};
  const Vec2 b(0.25, -0.4);
  Eigen::VectorXd sheared(2 * d.mesh.num_vertices());
  for (int v = 0; v < d.mesh.num_vertices(); ++v) sheared.segment<2>(2 * v) = a * d.uv[v] + b;
  sheared.segment<2>(0) = a * Vec2(0.3, 0.2) + b;
  EXPECT_TRUE(untangle_folds(d.mesh.triangles, d.uv, sheared, 0));  // the folded corners alone suffice
  EXPECT_NEAR((sheared.segment<2>(0) - (a * d.uv[0] + b)).norm(), 0.0, 1e-12);
  // Everything on one line: no interior move can open it, and x is left as it was.
  Eigen::VectorXd flat = Eigen::VectorXd::Zero(2 * d.mesh.num_vertices());
  for (int v = 0; v < d.mesh.num_vertices(); ++v) flat[2 * v] = d.uv[v].x();
  const Eigen::VectorXd flat_before = flat;
  EXPECT_FALSE(untangle_folds(d.mesh.triangles, d.uv, flat));
  EXPECT_EQ(flat, flat_before);
  // A rest disk with the center on top of a neighbour has no mean-value weights there: the
  // untangling reports failure and leaves x as it was, it does not throw.
  std::vector<Vec2> coincident = d.uv;
  const Tri& first = *std::find_if(d.mesh.triangles.begin(), d.mesh.triangles.end(),
                                   [](const Tri& t) { return t[0] == 0 || t[1] == 0 || t[2] == 0; });
  coincident[0] = d.uv[first[0] == 0 ? first[1] : first[0]];
  Eigen::VectorXd pushed(ok.size());
  for (int v = 0; v < d.mesh.num_vertices(); ++v) pushed.segment<2>(2 * v) = 0.9 * d.uv[v];
  pushed.segment<2>(0) = Vec2(0.2, 0.1);
  const Eigen::VectorXd pushed_before = pushed;
  EXPECT_FALSE(untangle_folds(d.mesh.triangles, coincident, pushed));
  EXPECT_EQ(pushed, pushed_before);
  Eigen::VectorXd too_short = ok.head(4);
  EXPECT_EQ(status_of([&] { untangle_folds(d.mesh.triangles, d.uv, too_short); }), MCON_ERROR_INVALID_ARGUMENT);
}
