// Similarity ICP in 3D (Besl & McKay 1992, with the scale of Umeyama 1991): what a DCC user does
// without Macrocon when two meshes share a world frame (align them, then copy attributes to the
// closest surface point). Source and target are given in their host (world) coordinates.
//
// Start: the area-weighted centroids matched, scale sqrt(target area / source area), identity
// rotation (both meshes sit in the same world frame, so the frame is the orientation cue). Each
// iteration: the closest target surface point of every transformed source vertex (exact,
// mesh/closest_point_3d.h), then the similarity x -> s R x + t minimizing the vertex-area-weighted
// sum of squared distances to those points (weighted Umeyama, eqs. 40-42: R = U D V^T from the
// SVD of the weighted cross-covariance, s = tr(S D) / sigma_x^2, t = mu_y - s R mu_x). R is a
// proper rotation: a mirrored pair must be mirrored by the caller first.
//
// Deterministic: the closest-point queries are independent per vertex, and every sum is taken
// serially in vertex order, so the result is bit-identical for any thread count.
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"
#include "patch/geodesic_disk_patch.h"

namespace mcon {

struct SimilarityTransform3D {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double scale = 1;
  Vec3 translation = Vec3::Zero();

  Vec3 apply(const Vec3& p) const { return scale * (rotation * p) + translation; }
};

struct SimilarityIcpOptions {
  int max_iterations = 200;
  // Stop when the weighted RMS distance changes by less than this fraction of itself.
  double relative_tolerance = 1e-7;
};

struct SimilarityIcpResult {
  SimilarityTransform3D transform;   // source host -> target host
  std::vector<SurfacePoint> closest;  // per source vertex: its closest target point after the last transform
  int iterations = 0;                 // transform updates made
  double rms_distance = 0;            // vertex-area-weighted RMS distance at `closest`
};

// Throws INVALID_ARGUMENT for an empty or zero-area mesh or a bad option.
SimilarityIcpResult similarity_icp(const TriMesh& source, const TriMesh& target,
                                   const SimilarityIcpOptions& options = {});

// The weighted least-squares similarity (Umeyama eqs. 40-42) taking x[i] onto y[i] with weights
// w[i] >= 0 (not all zero). Exact for points related by a similarity.
SimilarityTransform3D weighted_similarity(const std::vector<Vec3>& x, const std::vector<Vec3>& y,
                                          const std::vector<double>& w);

// A patch's mesh in host units: center_position + radius * p (the patch stores p normalized).
TriMesh host_mesh(const Patch& patch);

}  // namespace mcon
