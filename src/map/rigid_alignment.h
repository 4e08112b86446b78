// Initialization of the re-embedding (thesis §4.3.1): the rigid 2D motion of the source disk,
// possibly mirrored, that maximizes the area-weighted Gaussian matching score (thesis eq. 4.14)
// against the target disk. Mirroring can only be decided here (the non-rigid optimization keeps
// orientation), which is how a left eye maps onto a right one.
//
// Search: `samples` candidate motions (half of them mirrored, every one a pure function of
// (seed, index) through a counter-based RNG, so any thread count gives the same candidates): a
// ring of rotations without translation (patches share their center, so this is the likely
// answer) plus random ones with uniform rotation and translation ~ N(0, 1) truncated to [-2, 2]
// per axis (thesis: clipped). Each is scored cheaply on a subsample of source points against a
// rasterized image of the smoothest target descriptor, in parallel with fixed chunks; the best
// few distinct candidates are then refined by damped Newton steps over (angle, translation) on
// the exact score (a larger area-weighted subsample, no raster) averaged over all descriptor levels, and the best refined one wins (ties: the
// lower sample index). A mirrored motion wins only if it beats the best plain one by
// `reflection_margin` (orientation-blind descriptors cannot tell a symmetric patch from its mirror
// image).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "map/matching_score.h"

namespace mcon {

struct RigidTransform2D {
  double angle = 0;                    // counter-clockwise rotation (radians)
  Vec2 translation = Vec2::Zero();
  bool reflected = false;              // mirror across the x axis first: (x, y) -> (x, -y)

  Vec2 apply(const Vec2& p) const;
};

// One descriptor level: the source's values (one row per source vertex) and the target's field.
// All levels' fields must live on the same target triangulation (lookups are shared).
struct MatchLevel {
  const Eigen::MatrixXd* source_values = nullptr;
  // The source's values as a mirrored candidate sees them (chiral channels change sign under a
  // reflection); nullptr: the same as source_values.
  const Eigen::MatrixXd* source_values_reflected = nullptr;
  const DescriptorField2D* target_field = nullptr;
  ScoreSettings score;
};

struct RigidAlignmentOptions {
  int samples = 10000;               // candidate motions (thesis: 10,000)
  std::uint64_t seed = 0;
  int zero_translation_angles = 90;  // angles of the deterministic ring (each with and without mirror)
  double translation_sigma = 1.0;
  double translation_bound = 2.0;
  int subsample = 384;               // source points used for the cheap score
  int raster_resolution = 128;       // pixels per side of the target descriptor image over [-1, 1]^2
  int refine_count = 8;              // distinct best candidates refined on the full score
  int refine_subsample = 1024;       // source points of the "full" score (all if fewer)
  int refine_iterations = 20;
  bool allow_reflection = true;      // false: only orientation-preserving motions win
  double reflection_margin = 0.01;   // a mirrored motion must out-score the best plain one by this
  // An up hint (PatchMapOptions::source_up / target_up): per orientation, the rotation that turns
  // the source's up direction in uv onto the target's. Candidates whose angle is farther than
  // up_tolerance from their orientation's are not considered, and a refinement that drifts
  // beyond it keeps its candidate's motion: the search stays within the hint's half-plane.
  bool use_up_prior = false;
  double up_angle_unreflected = 0;
  double up_angle_reflected = 0;
  double up_tolerance = 1.0471975511965976;  // 60 degrees
};

// Whether T's rotation lies within the up prior's tolerance (always true without a prior).
bool within_up_prior(const RigidAlignmentOptions& options, const RigidTransform2D& T);

struct RigidAlignmentResult {
  RigidTransform2D transform;
  double score = 0;          // refined full score in [0, 1] (mean over levels)
  double sampled_score = 0;  // best cheap score among the candidates
  // The best refined candidate of each orientation (score -1 if that orientation was not tried).
  RigidTransform2D best_unreflected, best_reflected;
  double score_unreflected = -1;
  double score_reflected = -1;
  int best_sample = -1;      // index of the candidate the winner was refined from
};

// The candidate motion with the given index (exposed for tests).
RigidTransform2D rigid_candidate(const RigidAlignmentOptions& options, int index);

// Area-weighted matching score (sum of weight_v * score_v) of the source points `points` (already
// moved) against one level.
double matching_score_sum(const std::vector<Vec2>& points, const std::vector<double>& vertex_weight,
                          const MatchLevel& level);

// uv: the source's disk parametrization; vertex_weight: A_v / A; levels: smoothest first.
// progress(fraction in [0, 1]) runs on the calling thread; returning false throws CANCELLED.
RigidAlignmentResult align_rigid(const std::vector<Vec2>& uv, const std::vector<double>& vertex_weight,
                                 const std::vector<MatchLevel>& levels, const RigidAlignmentOptions& options,
                                 const std::function<bool(double)>& progress = {});

}  // namespace mcon
