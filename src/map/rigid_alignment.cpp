#include "map/rigid_alignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "base/counter_rng.h"
#include "base/error.h"
#include "map/map_energy.h"
#include "base/parallel_blocks.h"

namespace mcon {

namespace {

constexpr double kTwoPi = 6.283185307179586;

Eigen::Matrix2d rotation(double a) {
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R;
}

Vec2 mirror(const Vec2& p, bool reflected) { return reflected ? Vec2(p.x(), -p.y()) : p; }

// The smoothest target level as an image over [-1, 1]^2 (bilinear between pixel nodes); nodes
// outside the target disk take the value at their nearest disk point, so the image is continuous.
class DescriptorImage {
 public:
  DescriptorImage(const DescriptorField2D& field, int resolution) : res_(std::max(resolution, 8)), dim_(field.dimension()) {
    data_.assign(static_cast<std::size_t>(res_) * res_ * dim_, 0.0);
    const double h = 2.0 / (res_ - 1);
    for_each_block(res_, 8, [&](int begin, int end, int) {
      std::vector<double> scratch(3 * static_cast<std::size_t>(dim_));
      for (int j = begin; j < end; ++j)
        for (int i = 0; i < res_; ++i) {
          Vec2 p(-1 + i * h, -1 + j * h);
          const double r = p.norm();
          if (r > 1) p /= r;
          const PointLocation loc = field.evaluate(p, 4.0, scratch.data(), scratch.data() + dim_, scratch.data() + 2 * dim_);
          double* out = &data_[(static_cast<std::size_t>(j) * res_ + i) * dim_];
          if (loc.triangle >= 0)
            for (int k = 0; k < dim_; ++k) out[k] = scratch[k];
        }
    });
  }

  // Writes the bilinear value at p (inside [-1, 1]^2).
  void sample(const Vec2& p, double* value) const {
    const double s = 0.5 * (res_ - 1);
    const double fx = std::clamp((p.x() + 1) * s, 0.0, res_ - 1.000001);
    const double fy = std::clamp((p.y() + 1) * s, 0.0, res_ - 1.000001);
    const int i = static_cast<int>(fx), j = static_cast<int>(fy);
    const double ax = fx - i, ay = fy - j;
    const double* p00 = &data_[(static_cast<std::size_t>(j) * res_ + i) * dim_];
    const double* p10 = p00 + dim_;
    const double* p01 = p00 + static_cast<std::size_t>(res_) * dim_;
    const double* p11 = p01 + dim_;
    for (int k = 0; k < dim_; ++k)
      value[k] = (1 - ay) * ((1 - ax) * p00[k] + ax * p10[k]) + ay * ((1 - ax) * p01[k] + ax * p11[k]);
  }

 private:
  int res_, dim_;
  std::vector<double> data_;
};

// Farthest point sampling in uv (start: the vertex nearest the origin), each sample weighted by
// the area of the vertices closest to it, so the subsample integrates like the full mesh.
void subsample_source(const std::vector<Vec2>& uv, const std::vector<double>& weight, int count,
                      std::vector<int>& picked, std::vector<double>& picked_weight) {
  const int n = static_cast<int>(uv.size());
  count = std::clamp(count, 1, n);
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<int> owner(n, 0);
  int next = 0;
  for (int v = 1; v < n; ++v)
    if (uv[v].squaredNorm() < uv[next].squaredNorm()) next = v;
  picked.clear();
  for (int k = 0; k < count; ++k) {
    picked.push_back(next);
    int far = -1;
    double far_d = -1;
    for (int v = 0; v < n; ++v) {
      const double d = (uv[v] - uv[next]).squaredNorm();
      if (d < dist[v]) {
        dist[v] = d;
        owner[v] = k;
      }
      if (dist[v] > far_d) {
        far_d = dist[v];
        far = v;
      }
    }
    if (far_d <= 0) break;
    next = far;
  }
  picked_weight.assign(picked.size(), 0.0);
  for (int v = 0; v < n; ++v) picked_weight[owner[v]] += weight[v];
}

// The full score of one transform, mean over levels, with derivatives with respect to
// (angle, tx, ty) if requested: gradient g and a positive semi-definite model of -Hessian.
// hints: per point, the target triangle of its previous lookup (updated; a speed-up only).
double full_score(const std::vector<Vec2>& rest, const std::vector<double>& weight,
                  const std::vector<MatchLevel>& levels, double angle, const Vec2& t, Eigen::Vector3d* g,
                  Eigen::Matrix3d* negH, std::vector<int>& hints) {
  const Eigen::Matrix2d R = rotation(angle);
  const bool derivs = g != nullptr;
  if (derivs) {
    g->setZero();
    negH->setZero();
  }
  // All levels live on the same target triangulation: one lookup per point serves them all.
  double total = 0;
  std::vector<double> scratch, value;
  for (std::size_t v = 0; v < rest.size(); ++v) {
    if (weight[v] == 0) continue;
    const Vec2 rr = R * rest[v];
    const Vec2 x = rr + t;
    Eigen::Matrix<double, 2, 3> Jp;
    Jp << -rr.y(), 1, 0, rr.x(), 0, 1;  // d x / d (angle, tx, ty)
    PointLocation location;
    for (const MatchLevel& level : levels) {
      const int d = level.target_field->dimension();
      scratch.resize(3 * static_cast<std::size_t>(d));
      value.resize(d);
      for (int k = 0; k < d; ++k) value[k] = (*level.source_values)(static_cast<Eigen::Index>(v), k);
      const ScoreSample s = match_score(*level.target_field, value.data(), x, level.score, derivs, scratch.data(),
                                        &location, hints[v]);
      location = s.location;
      if (location.triangle >= 0) hints[v] = location.triangle;
      total += weight[v] * s.score;
      if (derivs && s.score > 0) {
        *g += weight[v] * Jp.transpose() * s.gradient;
        *negH += weight[v] * Jp.transpose() * project_psd(Eigen::Matrix2d(-s.hessian)) * Jp;
      }
    }
  }
  const double L = static_cast<double>(levels.size());
  if (derivs) {
    *g /= L;
    *negH /= L;
  }
  return total / L;
}

double wrapped_angle_difference(double a, double b) {
  double d = std::fmod(std::abs(a - b), kTwoPi);
  return std::min(d, kTwoPi - d);
}

}  // namespace

Vec2 RigidTransform2D::apply(const Vec2& p) const { return rotation(angle) * mirror(p, reflected) + translation; }

bool within_up_prior(const RigidAlignmentOptions& o, const RigidTransform2D& T) {
  if (!o.use_up_prior) return true;
  const double prior = T.reflected ? o.up_angle_reflected : o.up_angle_unreflected;
  return wrapped_angle_difference(T.angle, prior) <= o.up_tolerance;
}

RigidTransform2D rigid_candidate(const RigidAlignmentOptions& o, int index) {
  RigidTransform2D T;
  T.reflected = (index % 2) == 1;
  const int ring = std::max(o.zero_translation_angles, 0);
  if (index < 2 * ring) {
    T.angle = kTwoPi * (index / 2) / ring;
    return T;
  }
  CounterRng rng(o.seed, static_cast<std::uint64_t>(index));
  T.angle = kTwoPi * rng.uniform();
  const double b = o.translation_bound / o.translation_sigma;
  T.translation = o.translation_sigma * Vec2(rng.truncated_normal(b), rng.truncated_normal(b));
  return T;
}

double matching_score_sum(const std::vector<Vec2>& points, const std::vector<double>& vertex_weight,
                          const MatchLevel& level) {
  const int d = level.target_field->dimension();
  std::vector<double> scratch(3 * static_cast<std::size_t>(d)), value(d);
  double sum = 0;
  for (std::size_t v = 0; v < points.size(); ++v) {
    for (int k = 0; k < d; ++k) value[k] = (*level.source_values)(static_cast<Eigen::Index>(v), k);
    sum += vertex_weight[v] * match_score(*level.target_field, value.data(), points[v], level.score, false, scratch.data()).score;
  }
  return sum;
}

namespace {

void check_alignment_inputs(const std::vector<Vec2>& uv, const std::vector<double>& vertex_weight,
                            const std::vector<MatchLevel>& levels, const RigidAlignmentOptions& options) {
  require(!levels.empty(), MCON_ERROR_INVALID_ARGUMENT, "rigid alignment: no descriptor level");
  require(uv.size() == vertex_weight.size() && !uv.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "rigid alignment: uv and weights differ in size");
  require(options.samples >= 1 && options.subsample >= 1 && options.refine_count >= 1 &&
              options.translation_sigma > 0 && options.translation_bound >= 0,
          MCON_ERROR_INVALID_ARGUMENT, "rigid alignment: invalid options");
  require(!options.use_up_prior || (std::isfinite(options.up_angle_unreflected) &&
                                    std::isfinite(options.up_angle_reflected) && options.up_tolerance > 0 &&
                                    options.up_tolerance <= 3.2),
          MCON_ERROR_INVALID_ARGUMENT, "rigid alignment: invalid up prior");
}

// The subsample of the cheap score and its smoothest-level values, row-major (m x d), as a plain
// and as a mirrored candidate sees them.
struct CoarseSample {
  std::vector<int> picked;
  std::vector<double> weight;
  int d = 0;
  std::vector<double> values, values_reflected;
};

CoarseSample coarse_sample(const std::vector<Vec2>& uv, const std::vector<double>& vertex_weight,
                           const MatchLevel& coarse, int subsample) {
  CoarseSample s;
  const int d = s.d = coarse.target_field->dimension();
  subsample_source(uv, vertex_weight, subsample, s.picked, s.weight);
  const std::vector<int>& picked = s.picked;
  const int m = static_cast<int>(picked.size());
  s.values.resize(static_cast<std::size_t>(m) * d);
  for (int k = 0; k < m; ++k)
    for (int c = 0; c < d; ++c) s.values[static_cast<std::size_t>(k) * d + c] = (*coarse.source_values)(picked[k], c);
  s.values_reflected = s.values;
  if (coarse.source_values_reflected)
    for (int k = 0; k < m; ++k)
      for (int c = 0; c < d; ++c)
        s.values_reflected[static_cast<std::size_t>(k) * d + c] = (*coarse.source_values_reflected)(picked[k], c);
  return s;
}

// Cheap score: subsample against the rasterized smoothest level. One score per candidate.
std::vector<double> sampled_scores(const std::vector<Vec2>& uv, const std::vector<double>& vertex_weight,
                                   const MatchLevel& coarse, const RigidAlignmentOptions& options,
                                   const std::function<void(double)>& report) {
  const int d = coarse.target_field->dimension();
  const DescriptorImage image(*coarse.target_field, options.raster_resolution);
  const CoarseSample sample = coarse_sample(uv, vertex_weight, coarse, options.subsample);
  const int m = static_cast<int>(sample.picked.size());
  const double inv_2s2 = 0.5 / (coarse.score.sigma * coarse.score.sigma);

  // The subsample's uv as a plain and as a mirrored candidate sees it.
  std::vector<Vec2> rest(m), rest_reflected(m);
  for (int k = 0; k < m; ++k) {
    rest[k] = uv[sample.picked[k]];
    rest_reflected[k] = mirror(rest[k], true);
  }
  const double band = coarse.score.band;
  std::vector<double> scores(options.samples, 0.0);
  constexpr int kBatch = 1024, kChunk = 32;
  for (int start = 0; start < options.samples; start += kBatch) {
    const int count = std::min(kBatch, options.samples - start);
    for_each_block(count, kChunk, [&](int begin, int end, int) {
      std::vector<double> value(d);
      for (int i = start + begin; i < start + end; ++i) {
        const RigidTransform2D T = rigid_candidate(options, i);
        if (!within_up_prior(options, T)) {
          scores[i] = -1;  // outside the up hint: sorted last, never chosen
          continue;
        }
        const Eigen::Matrix2d R = rotation(T.angle);
        const std::vector<double>& pv = T.reflected ? sample.values_reflected : sample.values;
        const std::vector<Vec2>& p = T.reflected ? rest_reflected : rest;
        double sum = 0;
        for (int k = 0; k < m; ++k) {
          const Vec2 x = R * p[k] + T.translation;
          const double w = rim_window_value(x.norm(), band);
          if (w <= 0) continue;
          image.sample(x, value.data());
          const double* pk = &pv[static_cast<std::size_t>(k) * d];
          double r2 = 0;
          for (int c = 0; c < d; ++c) {
            const double r = value[c] - pk[c];
            r2 += r * r;
          }
          sum += sample.weight[k] * w * std::exp(-r2 * inv_2s2);
        }
        scores[i] = sum;
      }
    });
    report(0.7 * (start + count) / options.samples);
  }
  return scores;
}

// The best distinct candidates of each orientation (both are refined, so the mirror decision
// compares refined optima), from `order` (descending score, ties by index).
std::vector<int> distinct_best(const std::vector<int>& order, const RigidAlignmentOptions& options) {
  std::vector<int> chosen;
  const int per_class = std::max(1, (options.refine_count + 1) / 2);
  for (int cls = 0; cls < 2; ++cls) {
    int taken = 0;
    for (int i : order) {
      if (taken >= per_class) break;
      const RigidTransform2D Ti = rigid_candidate(options, i);
      if (static_cast<int>(Ti.reflected) != cls || !within_up_prior(options, Ti)) continue;
      bool distinct = true;
      for (int j : chosen) {
        const RigidTransform2D Tj = rigid_candidate(options, j);
        if (Ti.reflected == Tj.reflected && wrapped_angle_difference(Ti.angle, Tj.angle) < 0.2 &&
            (Ti.translation - Tj.translation).norm() < 0.2) {
          distinct = false;
          break;
        }
      }
      if (distinct) {
        chosen.push_back(i);
        ++taken;
      }
    }
  }
  return chosen;
}

// The larger subsample of the exact score: its uv, weights and values per level, as a plain and
// as a mirrored candidate sees them, each with the exact ("0 outside") and the neutral rule.
struct FineSample {
  std::vector<int> picked;
  std::vector<double> weight;
  std::vector<Vec2> uv;
  std::vector<Eigen::MatrixXd> values, values_reflected;
  std::vector<MatchLevel> levels, levels_reflected;    // exact
  std::vector<MatchLevel> neutral, neutral_reflected;  // nearest rim value outside
};

FineSample fine_sample(const std::vector<Vec2>& uv, const std::vector<double>& vertex_weight,
                       const std::vector<MatchLevel>& levels, int subsample) {
  FineSample s;
  const std::vector<int>& fine = s.picked;
  subsample_source(uv, vertex_weight, subsample, s.picked, s.weight);
  s.uv.resize(fine.size());
  s.values.resize(levels.size());
  s.values_reflected.resize(levels.size());
  s.levels = levels;
  s.levels_reflected = levels;
  for (std::size_t k = 0; k < fine.size(); ++k) s.uv[k] = uv[fine[k]];
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const Eigen::MatrixXd* refl = levels[l].source_values_reflected ? levels[l].source_values_reflected
                                                                    : levels[l].source_values;
    s.values[l].resize(static_cast<Eigen::Index>(fine.size()), levels[l].source_values->cols());
    s.values_reflected[l].resize(static_cast<Eigen::Index>(fine.size()), levels[l].source_values->cols());
    for (std::size_t k = 0; k < fine.size(); ++k) {
      s.values[l].row(k) = levels[l].source_values->row(fine[k]);
      s.values_reflected[l].row(k) = refl->row(fine[k]);
    }
    s.levels[l].source_values = &s.values[l];
    s.levels_reflected[l].source_values = &s.values_reflected[l];
  }
  // Refinement reads the target beyond its rim by the nearest rim value (matching_score.h): the
  // overlap reward of the "0 outside" score, right for choosing among candidates, would pull a
  // partially overlapping alignment toward the center. The winner is still chosen by the
  // "0 outside" score.
  s.neutral = s.levels;
  s.neutral_reflected = s.levels_reflected;
  for (MatchLevel& l : s.neutral) l.score.outside = OutsideRule::nearest_rim;
  for (MatchLevel& l : s.neutral_reflected) l.score.outside = OutsideRule::nearest_rim;
  return s;
}

// Damped Newton steps over (angle, translation) on the full score of `rest` (the fine
// subsample, mirrored for a mirrored T), each step backtracked until the score rises.
void refine_transform(const std::vector<Vec2>& rest, const std::vector<double>& weight,
                      const std::vector<MatchLevel>& neutral, int iterations, RigidTransform2D& T,
                      std::vector<int>& hints) {
  Eigen::Vector3d g;
  Eigen::Matrix3d negH;
  double S = full_score(rest, weight, neutral, T.angle, T.translation, &g, &negH, hints);
  double damping = 1e-3;
  for (int it = 0; it < iterations; ++it) {
    const double scale = std::max(negH.trace() / 3, 1e-12);
    Eigen::Matrix3d A = negH + damping * scale * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d step = A.ldlt().solve(g);
    if (!step.allFinite() || step.norm() < 1e-10) break;
    double alpha = 1;
    bool improved = false;
    for (int k = 0; k < 12; ++k) {
      const double a = T.angle + alpha * step[0];
      const Vec2 t = T.translation + alpha * step.tail<2>();
      // Derivatives at every trial: the first trial is nearly always taken, and this saves
      // scoring it a second time for them.
      Eigen::Vector3d gn;
      Eigen::Matrix3d negHn;
      const double Sn = full_score(rest, weight, neutral, a, t, &gn, &negHn, hints);
      if (Sn > S) {
        const double gain = Sn - S;
        T.angle = a;
        T.translation = t;
        S = Sn;
        g = gn;
        negH = negHn;
        improved = gain > 1e-10 * std::max(S, 1e-12);
        break;
      }
      alpha *= 0.5;
    }
    if (!improved) break;
  }
}

// Refine each on the exact score of a larger subsample (parallel over candidates, each serial).
void refine_candidates(const FineSample& fine, const std::vector<int>& chosen, const RigidAlignmentOptions& options,
                       std::vector<RigidTransform2D>& refined, std::vector<double>& refined_score) {
  const int nc = static_cast<int>(chosen.size());
  refined.assign(nc, RigidTransform2D{});
  refined_score.assign(nc, 0.0);
  for_each_block(nc, 1, [&](int begin, int end, int) {
    for (int c = begin; c < end; ++c) {
      RigidTransform2D T = rigid_candidate(options, chosen[c]);
      const std::vector<MatchLevel>& neutral = T.reflected ? fine.neutral_reflected : fine.neutral;
      const std::vector<MatchLevel>& exact = T.reflected ? fine.levels_reflected : fine.levels;
      std::vector<Vec2> rest(fine.uv.size());
      for (std::size_t v = 0; v < fine.uv.size(); ++v) rest[v] = mirror(fine.uv[v], T.reflected);
      std::vector<int> hints(rest.size(), -1);
      refine_transform(rest, fine.weight, neutral, options.refine_iterations, T, hints);
      T.angle = std::fmod(T.angle, kTwoPi);
      if (T.angle < 0) T.angle += kTwoPi;
      if (!within_up_prior(options, T)) T = rigid_candidate(options, chosen[c]);  // drifted off the hint
      refined[c] = T;
      refined_score[c] = full_score(rest, fine.weight, exact, T.angle, T.translation, nullptr, nullptr, hints);
    }
  });
}

// Best of each orientation; mirroring must win by a margin (nearly symmetric patches such as a
// nose score about the same both ways, and then the orientation-preserving map is the safe one).
RigidAlignmentResult best_refined(const std::vector<int>& chosen, const std::vector<RigidTransform2D>& refined,
                                  const std::vector<double>& refined_score, const RigidAlignmentOptions& options) {
  RigidAlignmentResult result;
  const int nc = static_cast<int>(refined.size());
  int best[2] = {-1, -1};
  for (int c = 0; c < nc; ++c) {
    const int cls = refined[c].reflected ? 1 : 0;
    if (best[cls] < 0 || refined_score[c] > refined_score[best[cls]]) best[cls] = c;
  }
  if (best[0] >= 0) {
    result.best_unreflected = refined[best[0]];
    result.score_unreflected = refined_score[best[0]];
  }
  if (best[1] >= 0) {
    result.best_reflected = refined[best[1]];
    result.score_reflected = refined_score[best[1]];
  }
  const bool mirror = best[0] < 0 || (options.allow_reflection && best[1] >= 0 &&
                                      result.score_reflected > result.score_unreflected + options.reflection_margin);
  const int winner = mirror ? best[1] : best[0];
  result.transform = refined[winner];
  result.score = refined_score[winner];
  result.best_sample = chosen[winner];
  return result;
}

}  // namespace

RigidAlignmentResult align_rigid(const std::vector<Vec2>& uv, const std::vector<double>& vertex_weight,
                                 const std::vector<MatchLevel>& levels, const RigidAlignmentOptions& options,
                                 const std::function<bool(double)>& progress) {
  check_alignment_inputs(uv, vertex_weight, levels, options);
  const std::function<void(double)> report = [&](double f) {
    if (progress && !progress(f)) fail(MCON_ERROR_CANCELLED, "rigid alignment cancelled");
  };

  const std::vector<double> scores = sampled_scores(uv, vertex_weight, levels.front(), options, report);

  // The best distinct candidates (descending score, ties by index).
  std::vector<int> order(options.samples);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return scores[a] > scores[b]; });
  const std::vector<int> chosen = distinct_best(order, options);

  const FineSample fine = fine_sample(uv, vertex_weight, levels, options.refine_subsample);
  std::vector<RigidTransform2D> refined;
  std::vector<double> refined_score;
  refine_candidates(fine, chosen, options, refined, refined_score);
  report(1.0);

  RigidAlignmentResult result = best_refined(chosen, refined, refined_score, options);
  result.sampled_score = scores[order.front()];
  return result;
}

}  // namespace mcon
