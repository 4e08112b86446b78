#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/error.h"
#include "patch/geodesic_disk_patch.h"
#include "map/patch_map.h"
#include "test_meshes.h"

using namespace mcon;
using mcon::test_meshes::make_disk;

namespace {

// A flat disk: every geometric channel is constant or radially symmetric, so only the guidance
// can tell which rotation is meant.
Patch flat_patch() {
  PatchOptions o;
  o.center.vertex = 0;
  o.radius = 0.9;
  return extract_geodesic_disk(make_disk(12), o);
}

Eigen::MatrixXd planar(const Patch& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::MatrixXd g(p.mesh.num_vertices(), 2);
  for (int v = 0; v < p.mesh.num_vertices(); ++v) {
    const Vec3& q = p.mesh.positions[v];
    g(v, 0) = c * q.x() - s * q.y();
    g(v, 1) = s * q.x() + c * q.y();
  }
  return g;
}

PatchMapOptions quick_options() {
  PatchMapOptions o;
  o.map.alignment.samples = 2000;
  o.map.alignment.seed = 5;
  return o;
}

mcon_status map_status(const Patch& a, const Patch& b, const PatchMapOptions& o) {
  try {
    map_patches(a, b, o);
  } catch (const Error& e) {
    return e.status();
  }
  return MCON_OK;
}

}  // namespace

// The guidance says target vertex w corresponds to the source point R^-1 p_w, i.e. the map is
// the rotation p -> R p; two different rotations must both come out.
TEST(PatchMap, GuidanceSelectsTheRotation) {
  const Patch p = flat_patch();
  for (double angle : {0.5 * M_PI, -2.0 * M_PI / 3}) {
    const Eigen::MatrixXd gs = planar(p, 0.0), gt = planar(p, -angle);
    PatchMapOptions o = quick_options();
    o.source_guidance = &gs;
    o.target_guidance = &gt;
    o.guidance_weight = 3.0;
    const SurfaceMap m = map_patches(p, p, o);
    EXPECT_FALSE(m.reflected);
    double err = 0;
    int inside = 0;
    for (int v = 0; v < p.mesh.num_vertices(); ++v) {
      const SurfacePoint& b = m.source_to_target[v];
      if (b.triangle < 0) continue;
      const Tri& t = p.mesh.triangles[b.triangle];
      const Vec3 q = b.barycentric[0] * p.mesh.positions[t[0]] + b.barycentric[1] * p.mesh.positions[t[1]] +
                     b.barycentric[2] * p.mesh.positions[t[2]];
      const Vec3& s = p.mesh.positions[v];
      const Vec3 want(std::cos(angle) * s.x() - std::sin(angle) * s.y(),
                      std::sin(angle) * s.x() + std::cos(angle) * s.y(), s.z());
      err += (q - want).norm();
      ++inside;
    }
    ASSERT_GT(inside, p.mesh.num_vertices() * 9 / 10) << "angle " << angle;
    EXPECT_LT(err / inside, 0.03) << "angle " << angle;
  }
}

TEST(PatchMap, RejectsBadGuidance) {
  const Patch p = flat_patch();
  const Eigen::MatrixXd good = planar(p, 0.0);
  PatchMapOptions o = quick_options();
  o.source_guidance = &good;
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT) << "only one side";

  const Eigen::MatrixXd short_rows = good.topRows(good.rows() - 1);
  o.target_guidance = &short_rows;
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT) << "row count";

  const Eigen::MatrixXd one_col = good.leftCols(1);
  o.target_guidance = &one_col;
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT) << "column count";

  const Eigen::MatrixXd no_cols(good.rows(), 0);
  o.source_guidance = &no_cols;
  o.target_guidance = &no_cols;
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT) << "no columns";

  Eigen::MatrixXd nan = good;
  nan(3, 1) = std::nan("");
  o.source_guidance = &good;
  o.target_guidance = &nan;
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_NON_FINITE);

  o.target_guidance = &good;
  o.guidance_weight = -1;
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT) << "negative weight";
  o.guidance_weight = std::numeric_limits<double>::infinity();
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT) << "infinite weight";

  o.guidance_weight = 1;
  EXPECT_EQ(map_status(p, p, o), MCON_OK);
}

namespace {

// The same patch with its disk parametrization rotated by `angle` (and mirrored (x, -y) first).
Patch with_rotated_uv(Patch p, double angle, bool mirror) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (Vec2& q : p.uv) {
    const Vec2 m(q.x(), mirror ? -q.y() : q.y());
    q = Vec2(c * m.x() - s * m.y(), s * m.x() + c * m.y());
  }
  return p;
}

double angle_difference(double a, double b) { return std::abs(std::remainder(a - b, 2 * M_PI)); }

}  // namespace

// The world-frame start: both patches sit on the same surface in 3D, so the ICP maps every vertex
// onto itself, and the start is the motion between the two parametrizations, mirror included.
TEST(PatchMap, WorldFrameStartIsTheMotionBetweenTheParametrizations) {
  const Patch p = flat_patch();
  for (const bool mirror : {false, true})
    for (const double angle : {0.7, -2.5}) {
      const RigidTransform2D T = world_frame_start(p, with_rotated_uv(p, angle, mirror), false);
      EXPECT_EQ(T.reflected, mirror);
      EXPECT_LT(angle_difference(T.angle, angle), 1e-9) << angle << " " << mirror;
      EXPECT_LT(T.translation.norm(), 1e-9);
    }
}

// With use_world_frame the frame start decides (frame_decided) and is the rigid start; the map of
// a flat disk onto itself with the parametrization turned keeps that turn. Off, the descriptors
// decide as before.
TEST(PatchMap, WorldFrameStartDecidesWhenAsked) {
  const Patch p = flat_patch();
  const Patch q = with_rotated_uv(p, 1.2, false);
  PatchMapOptions o = quick_options();
  o.use_world_frame = true;
  const SurfaceMap m = map_patches(p, q, o);
  EXPECT_TRUE(m.frame_decided);
  EXPECT_FALSE(m.reflected);
  EXPECT_LT(angle_difference(m.alignment.transform.angle, 1.2), 1e-9);
  double worst = 0;
  for (std::size_t v = 0; v < p.uv.size(); ++v) worst = std::max(worst, (m.phi[v] - q.uv[v]).norm());
  EXPECT_LT(worst, 0.05);
  EXPECT_FALSE(map_patches(p, q, quick_options()).frame_decided);
  o.map.orientation = MapOrientation::preserve;
  EXPECT_EQ(map_status(p, q, o), MCON_ERROR_INVALID_ARGUMENT);
}

namespace {

// The same patch with its disk parametrization twisted (angle + 1.2 r (1 - r), centre and rim
// kept): a non-rigid change of the target's uv that a flat disk's descriptors (all functions of
// the distance to the centre) cannot see.
Patch with_warped_uv(Patch p) {
  for (Vec2& q : p.uv) {
    const double r = q.norm(), a = 1.2 * r * (1 - r), c = std::cos(a), s = std::sin(a);
    q = Vec2(c * q.x() - s * q.y(), s * q.x() + c * q.y());
  }
  return p;
}

double worst_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double worst = 0;
  for (std::size_t v = 0; v < a.size(); ++v) worst = std::max(worst, (a[v] - b[v]).norm());
  return worst;
}


// Mean distance over the vertices with |b| < 0.8 (off the rim, which is not anchored).
double interior_mean_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double sum = 0;
  int n = 0;
  for (std::size_t v = 0; v < a.size(); ++v)
    if (b[v].norm() < 0.8) {
      sum += (a[v] - b[v]).norm();
      ++n;
    }
  return sum / std::max(n, 1);
}

}  // namespace

// The world frame's anchor: every vertex onto itself (the same surface in 3D), its position the
// target's uv of that vertex; the rim's vertices are not anchored (their closest point is the rim).
TEST(PatchMap, WorldFrameAnchorIsTheClosestPointsUvOffTheRim) {
  const Patch p = flat_patch();
  const Patch q = with_warped_uv(p);
  const WorldFrame frame = world_frame(p, q, false);
  ASSERT_EQ(frame.anchor.position.size(), p.uv.size());
  EXPECT_LT(worst_distance(frame.anchor.position, q.uv), 1e-9);
  for (std::size_t v = 0; v < p.uv.size(); ++v)
    EXPECT_EQ(frame.anchor.weight[v], std::abs(p.uv[v].norm() - 1) < 1e-9 ? 0.0 : 1.0) << v;
}

// The anchor pulls the map towards its positions: here positions shifted off the true
// correspondence (the same disk) by 0.08; a heavy anchor moves the map most of the way there.
TEST(PatchMap, AnchorPullsTheMapTowardsItsPositions) {
  const Patch p = flat_patch();
  PatchMapOptions o = quick_options();
  o.map.orientation = MapOrientation::preserve;
  MapAnchor anchor;
  for (const Vec2& u : p.uv) {
    anchor.position.push_back(u + Vec2(0.08, 0.0));
    anchor.weight.push_back(1.0);
  }
  const SurfaceMap free_map = map_patches(p, p, o);
  o.map.anchor = anchor;
  o.map.weights.anchor = 200;
  const SurfaceMap anchored = map_patches(p, p, o);
  EXPECT_GT(anchored.energy.value("anchor"), 0.0);
  EXPECT_EQ(free_map.energy.value("anchor"), 0.0);
  const double e_free = interior_mean_distance(free_map.phi, anchor.position);
  const double e_anchored = interior_mean_distance(anchored.phi, anchor.position);
  EXPECT_GT(e_free, 0.06);
  EXPECT_LT(e_anchored, 0.5 * e_free) << e_anchored << " vs " << e_free;
  o.map.weights.anchor = -1;
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT);
  o.map.weights.anchor = 1;
  o.map.anchor.weight[3] = 2;  // outside [0, 1]
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT);
  o.map.anchor.position.pop_back();
  EXPECT_EQ(map_status(p, p, o), MCON_ERROR_INVALID_ARGUMENT);
  // The world-frame weight is checked too.
  PatchMapOptions w = quick_options();
  w.use_world_frame = true;
  w.world_frame_anchor = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(map_status(p, p, w), MCON_ERROR_INVALID_ARGUMENT);
}

// The up direction in uv turns with the parametrization (and mirrors with it); zero, non-finite
// and normal vectors are refused.
TEST(PatchMap, UpDirectionInUvFollowsTheParametrization) {
  const Patch p = flat_patch();
  const Vec3 up(0, 1, 0);
  const Vec2 u = up_direction_in_uv(p, up, "up");
  EXPECT_NEAR(u.norm(), 1.0, 1e-12);
  for (const bool mirror : {false, true})
    for (const double angle : {0.9, -2.2}) {
      const Vec2 m(u.x(), mirror ? -u.y() : u.y());
      const Vec2 expected(std::cos(angle) * m.x() - std::sin(angle) * m.y(), std::sin(angle) * m.x() + std::cos(angle) * m.y());
      EXPECT_LT((up_direction_in_uv(with_rotated_uv(p, angle, mirror), up, "up") - expected).norm(), 1e-6)
          << angle << " " << mirror;
    }
  // Length does not matter; the normal component is dropped.
  EXPECT_LT((up_direction_in_uv(p, Vec3(0, 7, 3), "up") - u).norm(), 1e-9);
  for (const Vec3& bad : {Vec3(0, 0, 0), Vec3(0, std::nan(""), 0), Vec3(0, 0, 1), Vec3(0.05, 0, 1)}) {
    try {
      up_direction_in_uv(p, bad, "source_up");
      ADD_FAILURE() << "accepted " << bad.transpose();
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), MCON_ERROR_INVALID_ARGUMENT);
      EXPECT_NE(std::string(e.what()).find("source_up"), std::string::npos) << e.what();
    }
  }
}

// A flat disk's descriptors cannot tell rotations apart; with up hints the rigid start turns the
// source's up onto the target's (within the prior's 60 degrees), whatever the parametrizations.
TEST(PatchMap, UpHintsDecideTheRotationTheDescriptorsCannot) {
  const Patch p = flat_patch();
  for (const double angle : {2.5, -1.4}) {
    const Patch q = with_rotated_uv(p, angle, false);
    PatchMapOptions o = quick_options();
    o.source_up = Vec3(0, 1, 0);
    o.target_up = Vec3(0, 1, 0);
    const SurfaceMap m = map_patches(p, q, o);
    EXPECT_FALSE(m.reflected);
    EXPECT_LT(angle_difference(m.alignment.transform.angle, angle), 1.05) << angle;
    // Every candidate outside the hint was excluded: both orientations' bests respect it.
    EXPECT_LT(angle_difference(m.alignment.best_unreflected.angle, angle), 1.05) << angle;
  }
  PatchMapOptions one = quick_options();
  one.source_up = Vec3(0, 1, 0);
  EXPECT_EQ(map_status(p, p, one), MCON_ERROR_INVALID_ARGUMENT);
  one.target_up = Vec3(0, 0, 2);  // normal to the disk
  EXPECT_EQ(map_status(p, p, one), MCON_ERROR_INVALID_ARGUMENT);
}
