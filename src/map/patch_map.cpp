#include "map/patch_map.h"

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "descriptors/descriptor_pyramid.h"
#include "base/error.h"
#include "base/parallel_blocks.h"
#include "map/map_channels.h"
#include "map/similarity_icp.h"
#include "mesh/mesh_topology.h"

namespace mcon {

namespace {

// Per-vertex channels of one patch before the joint normalization (map_channels(), in column
// order); the center-based ones only when `center_channels`.
Eigen::MatrixXd raw_channels(const Patch& patch, bool center_channels) {
  const std::vector<MapChannel>& channels = map_channels();
  Eigen::MatrixXd c(patch.mesh.num_vertices(), center_channels ? static_cast<Eigen::Index>(channels.size()) : 1);
  PatchCenterFrame frame;
  frame.patch = &patch;
  if (center_channels) frame = patch_center_frame(patch);
  Eigen::Index k = 0;
  for (const MapChannel& channel : channels)
    if (center_channels || !channel.center_based) c.col(k++) = channel.compute(frame);
  require(c.allFinite(), MCON_ERROR_NUMERICAL, "map_patches: non-finite descriptor channel");
  return c;
}

// One orientation's weighted 2D Procrustes fit taking a (mirrored (x, -y) first if `reflected`)
// onto b: the 2D case of Umeyama's eqs. 40-42 without scale, angle = atan2(sum w (a x b),
// sum w (a . b)) over the centered sets, t = mean_b - R mean_a; returns the weighted squared residual.
double fit_rigid_2d(const std::vector<Vec2>& a0, const std::vector<Vec2>& b, const std::vector<double>& w,
                    bool reflected, RigidTransform2D& T) {
  std::vector<Vec2> a(a0);
  if (reflected)
    for (Vec2& p : a) p.y() = -p.y();
  double total = 0;
  Vec2 ma = Vec2::Zero(), mb = Vec2::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    total += w[i];
    ma += w[i] * a[i];
    mb += w[i] * b[i];
  }
  ma /= total;
  mb /= total;
  double sx = 0, sd = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sx += w[i] * cross2(a[i] - ma, b[i] - mb);
    sd += w[i] * (a[i] - ma).dot(b[i] - mb);
  }
  T.reflected = reflected;
  T.angle = std::atan2(sx, sd);
  T.translation = Vec2::Zero();
  T.translation = mb - T.apply(reflected ? Vec2(ma.x(), -ma.y()) : ma);  // apply() mirrors its argument
  double residual = 0;
  for (std::size_t i = 0; i < a.size(); ++i) residual += w[i] * (T.apply(a0[i]) - b[i]).squaredNorm();
  return residual;
}

// Whether a closest point lies on the target's boundary: its nonzero barycentric corners are all
// boundary vertices (a boundary vertex, or a point on an edge between two of them).
bool on_rim(const Tri& t, const Vec3& w, const std::vector<char>& boundary) {
  for (int c = 0; c < 3; ++c)
    if (w[c] > 1e-9 && !boundary[t[c]]) return false;
  return true;
}

}  // namespace

WorldFrame world_frame(const Patch& source, const Patch& target, bool mirror_x) {
  TriMesh s = host_mesh(source);
  if (mirror_x)
    for (Vec3& p : s.positions) p.x() = -p.x();
  const SimilarityIcpResult icp = similarity_icp(s, host_mesh(target));
  std::vector<char> boundary(target.uv.size(), 0);
  for (const std::vector<int>& loop : build_topology(target.mesh).boundary_loops)
    for (const int v : loop) boundary[v] = 1;
  WorldFrame frame;
  std::vector<Vec2>& b = frame.anchor.position;
  b.resize(icp.closest.size());
  frame.anchor.weight.resize(icp.closest.size());
  for (std::size_t v = 0; v < b.size(); ++v) {
    const Tri& t = target.mesh.triangles[icp.closest[v].triangle];
    const Vec3& w = icp.closest[v].barycentric;
    b[v] = w[0] * target.uv[t[0]] + w[1] * target.uv[t[1]] + w[2] * target.uv[t[2]];
    frame.anchor.weight[v] = on_rim(t, w, boundary) ? 0.0 : 1.0;
  }
  std::vector<double> weight(source.mesh.positions.size(), 0.0);
  for (int t = 0; t < source.mesh.num_triangles(); ++t)
    for (const int v : source.mesh.triangles[t]) weight[v] += triangle_area(source.mesh, t);
  RigidTransform2D plain, mirrored;
  const double rp = fit_rigid_2d(source.uv, b, weight, false, plain);
  const double rm = fit_rigid_2d(source.uv, b, weight, true, mirrored);
  frame.start = rm < rp ? mirrored : plain;
  return frame;
}

Vec2 up_direction_in_uv(const Patch& patch, const Vec3& up, const char* what) {
  const std::string name(what);
  require(up.allFinite(), MCON_ERROR_INVALID_ARGUMENT, name + ": the up vector must be finite");
  require(up.norm() > 0, MCON_ERROR_INVALID_ARGUMENT, name + ": the up vector must not be zero");
  const TriMesh& m = patch.mesh;
  // Triangles near the center (all of them if the innermost ring is wider than 0.3).
  std::vector<int> near;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Tri& tri = m.triangles[t];
    const double r = ((m.positions[tri[0]] + m.positions[tri[1]] + m.positions[tri[2]]) / 3).norm();
    if (r < 0.3) near.push_back(t);
  }
  if (near.empty())
    for (int t = 0; t < m.num_triangles(); ++t) near.push_back(t);
  Vec3 normal = Vec3::Zero();
  // The least-squares linear map J (2x3) with J e ~ u for the edges (e in 3D, u in uv) of those
  // triangles, area-weighted: the normal equations J (sum a e e^T) = sum a u e^T.
  Eigen::Matrix3d PP = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 2, 3> UP = Eigen::Matrix<double, 2, 3>::Zero();
  for (const int t : near) {
    const Tri& tri = m.triangles[t];
    const Vec3 e1 = m.positions[tri[1]] - m.positions[tri[0]], e2 = m.positions[tri[2]] - m.positions[tri[0]];
    const Vec2 u1 = patch.uv[tri[1]] - patch.uv[tri[0]], u2 = patch.uv[tri[2]] - patch.uv[tri[0]];
    const Vec3 n = e1.cross(e2);
    const double a = 0.5 * n.norm();
    normal += n;
    PP += a * (e1 * e1.transpose() + e2 * e2.transpose());
    UP += a * (u1 * e1.transpose() + u2 * e2.transpose());
  }
  require(normal.norm() > 0, MCON_ERROR_INVALID_ARGUMENT, name + ": the patch has no area at its center");
  normal.normalize();
  const Vec3 d = up.normalized();
  const Vec3 tangent = d - d.dot(normal) * normal;
  // Within ~11.5 degrees of the normal (|tangent| < 0.2) the projection is dominated by noise.
  require(tangent.norm() >= 0.2, MCON_ERROR_INVALID_ARGUMENT,
          name + ": the up vector is (nearly) normal to the patch at its center, so it gives no direction "
                 "in the patch; give the host's up axis only for patches that face sideways, or omit both");
  // PP is rank 2 (tangent edges): regularize its normal direction.
  const Eigen::Matrix3d A = PP + (PP.trace() * 1e-9 + 1e-300) * normal * normal.transpose();
  const Eigen::Matrix<double, 2, 3> J = UP * A.inverse();
  const Vec2 u = J * tangent;
  require(u.allFinite() && u.norm() > 0, MCON_ERROR_NUMERICAL, name + ": the patch's uv is degenerate at its center");
  return u.normalized();
}

RigidTransform2D world_frame_start(const Patch& source, const Patch& target, bool mirror_x) {
  return world_frame(source, target, mirror_x).start;
}

SurfaceMap map_patches(const Patch& source, const Patch& target, const PatchMapOptions& options) {
  require(!options.pyramid_sigmas.empty(), MCON_ERROR_INVALID_ARGUMENT, "map_patches: no descriptor levels");
  require(options.center_distance_weight >= 0 && options.chord_weight >= 0 &&
              std::isfinite(options.center_distance_weight) && std::isfinite(options.chord_weight),
          MCON_ERROR_INVALID_ARGUMENT, "map_patches: invalid descriptor weights");
  require(options.chirality_weight >= 0 && std::isfinite(options.chirality_weight), MCON_ERROR_INVALID_ARGUMENT,
          "map_patches: invalid chirality weight");
  require((options.source_guidance == nullptr) == (options.target_guidance == nullptr), MCON_ERROR_INVALID_ARGUMENT,
          "map_patches: guidance needs both a source and a target matrix");
  if (options.source_guidance) {
    const Eigen::MatrixXd &gs = *options.source_guidance, &gt = *options.target_guidance;
    require(gs.rows() == source.mesh.num_vertices() && gt.rows() == target.mesh.num_vertices(),
            MCON_ERROR_INVALID_ARGUMENT, "map_patches: guidance needs one row per patch vertex");
    require(gs.cols() == gt.cols() && gs.cols() > 0, MCON_ERROR_INVALID_ARGUMENT,
            "map_patches: source and target guidance need the same (non-zero) number of columns");
    require(gs.allFinite() && gt.allFinite(), MCON_ERROR_NON_FINITE, "map_patches: non-finite guidance value");
    require(options.guidance_weight >= 0 && std::isfinite(options.guidance_weight), MCON_ERROR_INVALID_ARGUMENT,
            "map_patches: invalid guidance weight");
  }
  bool center = false;
  for (const MapChannel& channel : map_channels()) center |= channel.center_based && channel.weight(options) > 0;
  // The two patches' channels, and below their pyramids, side by side (independent, so the same
  // result on any thread count).
  Eigen::MatrixXd s, t;
  for_each_block(2, 1, [&](int b, int, int) { (b == 0 ? s : t) = raw_channels(b == 0 ? source : target, center); });
  // Joint normalization (thesis §3.1: every dimension std 1 over both patches), then weights.
  std::vector<double> weights;
  std::vector<int> chiral_columns;
  for (const MapChannel& channel : map_channels()) {
    if (!center && channel.center_based) continue;
    if (channel.chiral && channel.weight(options) > 0) chiral_columns.push_back(static_cast<int>(weights.size()));
    weights.push_back(channel.weight(options));
  }
  if (options.source_guidance) {
    const Eigen::Index c0 = s.cols(), g = options.source_guidance->cols();
    s.conservativeResize(Eigen::NoChange, c0 + g);
    t.conservativeResize(Eigen::NoChange, c0 + g);
    s.rightCols(g) = *options.source_guidance;
    t.rightCols(g) = *options.target_guidance;
    weights.resize(static_cast<std::size_t>(c0 + g), options.guidance_weight);
  }
  for (int k = 0; k < s.cols(); ++k) {
    const double mean = (s.col(k).sum() + t.col(k).sum()) / static_cast<double>(s.rows() + t.rows());
    const double var = ((s.col(k).array() - mean).square().sum() + (t.col(k).array() - mean).square().sum()) /
                       static_cast<double>(s.rows() + t.rows());
    const double scale = weights[static_cast<std::size_t>(k)] / std::sqrt(std::max(var, 1e-24));
    s.col(k) = (s.col(k).array() - mean) * scale;
    t.col(k) = (t.col(k).array() - mean) * scale;
  }
  std::vector<Eigen::MatrixXd> source_levels, target_levels;
  for_each_block(2, 1, [&](int b, int, int) {
    if (b == 0)
      source_levels = descriptor_pyramid(source.mesh, s, options.pyramid_sigmas);
    else
      target_levels = descriptor_pyramid(target.mesh, t, options.pyramid_sigmas);
  });
  SurfaceMapOptions map_options = options.map;
  if (!chiral_columns.empty()) map_options.chiral_columns = chiral_columns;
  require(options.source_up.has_value() == options.target_up.has_value(), MCON_ERROR_INVALID_ARGUMENT,
          "map_patches: up hints need both a source_up and a target_up (or neither)");
  if (options.source_up) {
    // The rotation turning the source's up (mirrored (x, -y) for a mirrored candidate) onto the target's.
    const Vec2 us = up_direction_in_uv(source, *options.source_up, "source_up");
    const Vec2 ut = up_direction_in_uv(target, *options.target_up, "target_up");
    RigidAlignmentOptions& a = map_options.alignment;
    a.use_up_prior = true;
    a.up_angle_unreflected = std::atan2(ut.y(), ut.x()) - std::atan2(us.y(), us.x());
    a.up_angle_reflected = std::atan2(ut.y(), ut.x()) - std::atan2(-us.y(), us.x());
    require(options.up_start_anchor >= 0 && std::isfinite(options.up_start_anchor), MCON_ERROR_INVALID_ARGUMENT,
            "map_patches: up_start_anchor must be finite and >= 0");
    if (map_options.start_anchor == 0) map_options.start_anchor = options.up_start_anchor;
  }
  require(options.world_frame_anchor >= 0 && std::isfinite(options.world_frame_anchor), MCON_ERROR_INVALID_ARGUMENT,
          "map_patches: the world-frame anchor weight must be finite and >= 0");
  if (options.use_world_frame) {
    WorldFrame frame = world_frame(source, target, options.world_frame_mirror);
    map_options.frame_start = frame.start;
    if (options.world_frame_anchor > 0) {
      map_options.weights.anchor = options.world_frame_anchor;
      map_options.anchor = std::move(frame.anchor);
    }
  }
  return compute_surface_map({source.mesh, source.uv, source_levels}, {target.mesh, target.uv, target_levels},
                             map_options);
}

}  // namespace mcon
