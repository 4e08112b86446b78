// The Gaussian descriptor matching score of one source point placed at x in the target disk's
// plane (thesis eq. 4.6): score = exp(-|I_T(x) - I_S|^2 / (2 sigma^2)), 1 for a perfect match,
// about 0 for a bad one. What a point outside the target scores is the delicate part (thesis
// §4.1.4-4.1.5); two rules:
//
//  OutsideRule::zero (rigid initialization, thesis eq. 4.14): outside scores 0, so maximizing
//    the total score also maximizes the overlap, which is what a rigid search needs (it must not
//    slide the patches apart). A C1 window w(x) = smoothstep((1 - |x|) / band) takes the score
//    to 0 over a thin band inside the unit circle instead of jumping at the rim, so the score is
//    continuous and can be refined by Newton steps.
//
//  OutsideRule::nearest_rim (non-rigid optimization): the target's descriptor is extended beyond
//    its rim by the value at the nearest rim point (x / |x| for |x| > 1). Measured on synthetic
//    partial overlaps (bench/map_bench), "0 outside" made the non-rigid optimizer squeeze the
//    source strip beyond the rim into the target (its descriptors resemble the rim's, so any
//    match beats 0): overlap 0.95 for a true 0.80; and "no term outside" (the thesis' energy)
//    rewards leaving instead. The extension is neutral: a point just outside costs what it costs
//    at the rim, so the descriptors alone decide the overlap, and the energy stays continuous.
#pragma once

#include <Eigen/Core>

#include "map/descriptor_field_2d.h"

namespace mcon {

enum class OutsideRule { zero, nearest_rim };

struct ScoreSettings {
  double sigma = 1;    // Gaussian width in descriptor units (thesis: std of the descriptors)
  double band = 0.05;  // width of the rim window in uv units (OutsideRule::zero)
  OutsideRule outside = OutsideRule::zero;
};

struct ScoreSample {
  double score = 0;                                   // in [0, 1]
  Vec2 gradient = Vec2::Zero();                       // d score / dx
  Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();  // d2 score / dx2 (exact inside a triangle
                                                      // and the band; Gauss-Newton beyond the rim)
  bool inside = false;                                // x lies in a target triangle
  PointLocation location;  // where the field was read (triangle -1 if it was not), reusable by
                           // other fields on the same triangulation via `known_location`
};

// The rim window's value w(|x|): 1 deeper than `band` inside the rim, 0 beyond it, smoothstep
// between. Inline: the rigid search's cheap score calls it for every point of every candidate.
inline double rim_window_value(double radius, double band) {
  const double t = (1.0 - radius) / band;
  return t >= 1 ? 1.0 : t <= 0 ? 0.0 : t * t * (3 - 2 * t);
}

// The rim window and its derivatives along the radius: w(|x|), dw/d|x|, d2w/d|x|2.
void rim_window(double radius, double band, double& w, double& dw, double& d2w);

// Score at x of a source point with descriptor `source_value` (field.dimension() entries).
// `scratch` must hold 3 * field.dimension() doubles. Derivatives only if `derivatives`.
// `known_location`: the `location` of an earlier call with the same x and outside rule on a
// field over the same triangulation (skips the lookup; ignored if its triangle is -1).
// `location_hint`: the triangle of an earlier call with a nearby x (speeds up the lookup only).
ScoreSample match_score(const DescriptorField2D& field, const double* source_value, const Vec2& x,
                        const ScoreSettings& settings, bool derivatives, double* scratch,
                        const PointLocation* known_location = nullptr, int location_hint = -1);

// sigma for a level per thesis §4.1.5: the standard deviation of all descriptor values of both
// patches around their joint mean (root mean squared distance to the mean, over d dimensions);
// a tiny floor keeps constant fields valid.
double descriptor_sigma(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target);

}  // namespace mcon
