#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include <tbb/task_arena.h>

#include "base/error.h"
#include "map/injective_step.h"
#include "map/map_energy.h"
#include "map/surface_map.h"
#include "synthetic_maps.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

constexpr double kPi = 3.141592653589793;

// Small meshes so the suite stays fast under the sanitizers: 469 source, 397 target vertices.
synthetic::Problem problem(const synthetic::GroundTruth& truth, double mismatch = 0) {
  return synthetic::make_problem(12, 11, truth, 2, {0.2, 0.1, 0.0}, mismatch);
}

// The common case: the truth is a rotation by `angle` plus a warp of amplitude `warp`.
synthetic::Problem problem(double angle, double warp, double mismatch = 0) {
  synthetic::GroundTruth truth;
  truth.angle = angle;
  truth.warp = warp;
  return problem(truth, mismatch);
}

// A rotation, a warp and a shift by 0.3: the source strip beyond the target's rim has no partner.
synthetic::GroundTruth warped_partial_overlap() {
  synthetic::GroundTruth truth;
  truth.angle = 70 * kPi / 180;
  truth.warp = 0.05;
  truth.translation = Vec2(0.3, 0.0);
  return truth;
}

SurfaceMap run(const synthetic::Problem& pr, const SurfaceMapOptions& o = {}) {
  return compute_surface_map({pr.source, pr.source_uv, pr.source_levels}, {pr.target, pr.target_uv, pr.target_levels}, o);
}

// Mean error of the rigid start, to show the non-rigid stage improves on it.
double initial_error(const synthetic::Problem& pr, const SurfaceMap& m) {
  std::vector<Vec2> p(pr.source_uv.size());
  for (std::size_t v = 0; v < p.size(); ++v) p[v] = m.alignment.transform.apply(pr.source_uv[v]);
  return synthetic::mean_error(pr, p);
}

// Inverted triangles of phi relative to the map's orientation (a mirrored map reverses all).
int inverted(const synthetic::Problem& pr, const SurfaceMap& m) {
  const SourceDisk disk = make_source_disk(pr.source, pr.source_uv, m.reflected);
  Eigen::VectorXd x(2 * m.phi.size());
  for (std::size_t v = 0; v < m.phi.size(); ++v) x.segment<2>(2 * v) = m.phi[v];
  return count_inverted(disk.triangles, x);
}

// True overlap: share of source area whose true image is inside the unit disk (vertex areas).
double true_overlap(const synthetic::Problem& pr) {
  const SourceDisk disk = make_source_disk(pr.source, pr.source_uv, false);
  double s = 0;
  for (std::size_t v = 0; v < pr.source_uv.size(); ++v)
    if (pr.truth.apply(pr.source_uv[v]).norm() < 1) s += disk.vertex_weight[v];
  return s;
}

void expect_consistent_directions(const synthetic::Problem& pr, const SurfaceMap& m) {
  int mapped = 0;
  for (std::size_t v = 0; v < m.phi.size(); ++v) {
    const SurfacePoint& b = m.source_to_target[v];
    if (b.triangle < 0) {
      EXPECT_GT(m.phi[v].norm(), 0.997) << "an inner point has no target triangle";  // 66-gon rim: cos(pi / 66) = 0.9989
      continue;
    }
    ++mapped;
    const Tri& t = pr.target.triangles[b.triangle];
    const Vec2 p = b.barycentric[0] * pr.target_uv[t[0]] + b.barycentric[1] * pr.target_uv[t[1]] +
                   b.barycentric[2] * pr.target_uv[t[2]];
    EXPECT_LT((p - m.phi[v]).norm(), 1e-12);
  }
  EXPECT_GT(mapped, 0);
  for (std::size_t w = 0; w < pr.target_uv.size(); ++w) {
    const SurfacePoint& b = m.target_to_source[w];
    if (b.triangle < 0) continue;
    const Tri& t = pr.source.triangles[b.triangle];
    const Vec2 p = b.barycentric[0] * m.phi[t[0]] + b.barycentric[1] * m.phi[t[1]] + b.barycentric[2] * m.phi[t[2]];
    EXPECT_LT((p - pr.target_uv[w]).norm(), 1e-12);
  }
}

void expect_monotone_per_level(const SurfaceMap& m) {
  ASSERT_EQ(m.energy_history.size(), m.energy_history_level.size());
  for (std::size_t i = 1; i < m.energy_history.size(); ++i)
    if (m.energy_history_level[i] == m.energy_history_level[i - 1]) {
      EXPECT_LE(m.energy_history[i], m.energy_history[i - 1]) << "energy rose at history entry " << i;
    }
}

}  // namespace

TEST(SurfaceMap, RecoversARotation) {
  const synthetic::Problem pr = problem(70 * kPi / 180, 0);
  const SurfaceMap m = run(pr);
  EXPECT_FALSE(m.reflected);
  EXPECT_EQ(inverted(pr, m), 0);
  // Measured 0.0015 (ring spacing 0.083).
  EXPECT_LT(synthetic::mean_error(pr, m.phi), 0.005);
  EXPECT_GT(m.overlap_ratio, 0.99);
  EXPECT_GT(m.matching_score, 0.99);
  for (const LevelReport& l : m.levels) EXPECT_EQ(l.stop_reason, StopReason::converged);
  expect_consistent_directions(pr, m);
  expect_monotone_per_level(m);
}

TEST(SurfaceMap, RecoversAWarpAndAPartialOverlap) {
  const synthetic::Problem pr = problem(warped_partial_overlap());
  const SurfaceMap m = run(pr);
  EXPECT_EQ(inverted(pr, m), 0);
  const double err = synthetic::mean_error(pr, m.phi);
  // Measured 0.013 against 0.045 for the rigid start.
  EXPECT_LT(err, 0.025);
  EXPECT_LT(err, 0.5 * initial_error(pr, m));
  // Measured 0.810 against 0.803: the source strip beyond the target's rim stays outside.
  EXPECT_NEAR(m.overlap_ratio, true_overlap(pr), 0.03);
  int outside = 0;
  for (const SurfacePoint& b : m.source_to_target) outside += b.triangle < 0;
  EXPECT_GT(outside, 20);
  expect_consistent_directions(pr, m);
  expect_monotone_per_level(m);
}

TEST(SurfaceMap, FindsAReflection) {
  synthetic::GroundTruth truth;
  truth.angle = 70 * kPi / 180;
  truth.warp = 0.05;
  truth.reflected = true;
  truth.translation = Vec2(0.1, 0.05);
  const synthetic::Problem pr = problem(truth);
  const SurfaceMap m = run(pr);
  EXPECT_TRUE(m.reflected);
  EXPECT_TRUE(m.alignment.transform.reflected);
  EXPECT_EQ(inverted(pr, m), 0);
  // Measured 0.011.
  EXPECT_LT(synthetic::mean_error(pr, m.phi), 0.025);
  expect_consistent_directions(pr, m);
}

TEST(SurfaceMap, PrefersThePlainMapForAMirrorSymmetricPatch) {
  // A field symmetric under y -> -y: the plain and the mirrored rotation fit equally well (as a
  // nose does for curvature); the orientation-preserving map must win.
  synthetic::GroundTruth truth;
  truth.angle = 0.8;
  synthetic::Problem pr = problem(truth);
  auto sym = [](const Vec2& p) {
    auto bump = [&p](double cx, double cy, double s) { return std::exp(-((p - Vec2(cx, cy)).squaredNorm()) / (2 * s * s)); };
    return bump(0.4, 0.0, 0.25) + 0.6 * bump(-0.35, 0.35, 0.2) + 0.6 * bump(-0.35, -0.35, 0.2) - 0.5 * bump(0, 0, 0.15);
  };
  Eigen::MatrixXd fs(pr.source.num_vertices(), 1), ft(pr.target.num_vertices(), 1);
  for (int v = 0; v < pr.source.num_vertices(); ++v) fs(v, 0) = sym(truth.apply(pr.source_uv[v]));
  for (int v = 0; v < pr.target.num_vertices(); ++v) ft(v, 0) = sym(pr.target_uv[v]);
  pr.source_levels = descriptor_pyramid(pr.source, fs, {0.2, 0.1, 0.0});
  pr.target_levels = descriptor_pyramid(pr.target, ft, {0.2, 0.1, 0.0});
  const SurfaceMap m = run(pr);
  EXPECT_TRUE(m.orientation_compared);
  EXPECT_FALSE(m.reflected);
  EXPECT_FALSE(m.alignment.transform.reflected);
  EXPECT_LT(synthetic::mean_error(pr, m.phi), 0.01);
}

TEST(SurfaceMap, OrientationsComparedThroughEveryLevel) {
  // compared_levels = all: both orientations run to the finest level before the energies decide;
  // a mirrored truth must still be found, with per-level reports of the winner only.
  synthetic::GroundTruth truth;
  truth.angle = 70 * kPi / 180;
  truth.warp = 0.05;
  truth.reflected = true;
  const synthetic::Problem pr = problem(truth);
  SurfaceMapOptions o;
  o.compared_levels = 3;
  o.orientation_ambiguity = 1.0;  // always compare
  const SurfaceMap m = run(pr, o);
  EXPECT_TRUE(m.orientation_compared);
  EXPECT_TRUE(m.reflected);
  EXPECT_EQ(inverted(pr, m), 0);
  EXPECT_LT(synthetic::mean_error(pr, m.phi), 0.025);
  ASSERT_EQ(m.levels.size(), 3u + o.refine_sigma_factors.size());
  int sum = 0;
  for (const LevelReport& l : m.levels) sum += l.iterations;
  EXPECT_EQ(sum, m.iterations);
  expect_monotone_per_level(m);
}

TEST(SurfaceMap, ProgressWindowStopsAtTheFirstSlowWindow) {
  // The windowed rule (NewtonOptions::progress_window) ends a level exactly when the last w
  // iterations gained at most progress_fraction of the level's decrease so far, never earlier.
  const synthetic::Problem pr = problem(0.9, 0.08);
  SurfaceMapOptions off;
  off.newton.progress_window = 0;
  off.newton.relative_decrease = 1e-12;  // let the tail run
  SurfaceMapOptions on = off;
  on.newton.progress_window = 3;
  on.newton.progress_fraction = 0.02;
  const SurfaceMap a = run(pr, off), b = run(pr, on);
  EXPECT_LT(b.iterations, a.iterations);
  // Measured: 12 vs 45 iterations, mean error 0.0167 both (the tail gains nothing visible).
  EXPECT_LT(synthetic::mean_error(pr, b.phi), synthetic::mean_error(pr, a.phi) + 0.002);
  const int w = on.newton.progress_window;
  for (int l = 0; l < 3; ++l) {
    std::vector<double> e;
    for (std::size_t i = 0; i < b.energy_history.size(); ++i)
      if (b.energy_history_level[i] == l) e.push_back(b.energy_history[i]);
    const int k_end = static_cast<int>(e.size()) - 1;  // iterations of the level
    for (int k = w + 1; k < k_end; ++k)
      EXPECT_GT(e[k - w] - e[k], on.newton.progress_fraction * (e[0] - e[k])) << "level " << l << " iteration " << k;
  }
}

TEST(SurfaceMap, ForcedOrientationIsObeyed) {
  // A mirrored truth: automatic finds the reflection, preserve must not take it (and still
  // return an injective map), reverse takes it without comparing.
  synthetic::GroundTruth truth;
  truth.angle = 1.2;
  truth.reflected = true;
  const synthetic::Problem pr = problem(truth);
  SurfaceMapOptions o;
  o.orientation = MapOrientation::preserve;
  const SurfaceMap plain = run(pr, o);
  EXPECT_FALSE(plain.reflected);
  EXPECT_FALSE(plain.orientation_compared);
  EXPECT_EQ(inverted(pr, plain), 0);
  o.orientation = MapOrientation::reverse;
  const SurfaceMap mirrored = run(pr, o);
  EXPECT_TRUE(mirrored.reflected);
  EXPECT_FALSE(mirrored.orientation_compared);
  EXPECT_EQ(inverted(pr, mirrored), 0);
  EXPECT_LT(synthetic::mean_error(pr, mirrored.phi), 0.025);
  EXPECT_GT(synthetic::mean_error(pr, plain.phi), 2 * synthetic::mean_error(pr, mirrored.phi));
  // Forcing works even where automatic reflections are switched off.
  o.alignment.allow_reflection = false;
  EXPECT_TRUE(run(pr, o).reflected);
}

TEST(SurfaceMap, RefinementNarrowsTheKernelAndPullsCloser) {
  // The refinement passes run after the finest level with a narrower Gaussian, each reported as a
  // stage of its own; near the optimum the narrower kernel pulls harder against the distortion
  // prior, so the warped truth is matched more closely.
  const synthetic::Problem pr = problem(warped_partial_overlap());
  SurfaceMapOptions plain_options;
  plain_options.refine_sigma_factors = {};
  const SurfaceMap plain = run(pr, plain_options);
  SurfaceMapOptions refined_options;
  refined_options.refine_sigma_factors = {0.5, 0.25};
  const SurfaceMap refined = run(pr, refined_options);
  ASSERT_EQ(plain.levels.size(), 3u);
  ASSERT_EQ(refined.levels.size(), 5u);
  for (int l = 0; l < 3; ++l) EXPECT_EQ(refined.levels[l].sigma, plain.levels[l].sigma);
  EXPECT_DOUBLE_EQ(refined.levels[3].sigma, 0.5 * plain.levels[2].sigma);
  EXPECT_DOUBLE_EQ(refined.levels[4].sigma, 0.25 * plain.levels[2].sigma);
  int sum = 0;
  for (const LevelReport& l : refined.levels) sum += l.iterations;
  EXPECT_EQ(sum, refined.iterations);
  EXPECT_GT(refined.iterations, plain.iterations);
  for (int l = 3; l < 5; ++l) EXPECT_LE(refined.levels[l].iterations, refined_options.refine_max_iterations);
  EXPECT_EQ(refined.stop_reason, refined.levels[2].stop_reason);  // the finest descriptor level's
  EXPECT_EQ(inverted(pr, refined), 0);
  expect_monotone_per_level(refined);
  expect_consistent_directions(pr, refined);
  const double e_plain = synthetic::mean_error(pr, plain.phi), e_refined = synthetic::mean_error(pr, refined.phi);
  EXPECT_LT(e_refined, e_plain);
  // The reported terms use the finest level's width in both runs, so the scores compare.
  EXPECT_GT(refined.matching_score, 0.9);
  EXPECT_GT(refined.matching_score, plain.matching_score - 0.01);
  std::printf("refinement: mean error %.5f -> %.5f, matching score %.4f -> %.4f\n", e_plain, e_refined,
              plain.matching_score, refined.matching_score);
}

TEST(SurfaceMap, ToleratesDescriptorMismatch) {
  const synthetic::Problem pr = problem(-2.0, 0.05, 0.1);
  const SurfaceMap m = run(pr);
  EXPECT_EQ(inverted(pr, m), 0);
  // Measured 0.041 (rigid start 0.051): the map must not run after the mismatch.
  EXPECT_LT(synthetic::mean_error(pr, m.phi), 0.06);
}

TEST(SurfaceMap, BitIdenticalOnAnyThreadCount) {
  synthetic::GroundTruth truth;
  truth.angle = 1.0;
  truth.warp = 0.05;
  truth.translation = Vec2(0.1, -0.1);
  const synthetic::Problem pr = problem(truth);
  SurfaceMapOptions o;
  o.alignment.samples = 4000;
  SurfaceMap ref;
  for (int threads : {1, 2, 4}) {
    SurfaceMap m;
    tbb::task_arena(threads).execute([&] { m = run(pr, o); });
    if (threads == 1) {
      ref = m;
      continue;
    }
    EXPECT_EQ(m.iterations, ref.iterations);
    EXPECT_EQ(m.energy_history, ref.energy_history);
    ASSERT_EQ(m.phi.size(), ref.phi.size());
    for (std::size_t v = 0; v < m.phi.size(); ++v) {
      ASSERT_EQ(m.phi[v].x(), ref.phi[v].x()) << "threads " << threads << " vertex " << v;
      ASSERT_EQ(m.phi[v].y(), ref.phi[v].y()) << "threads " << threads << " vertex " << v;
    }
  }
}

TEST(SurfaceMap, ProgressIsMonotoneAndCanCancel) {
  const synthetic::Problem pr = problem(0.5, 0.05);
  SurfaceMapOptions o;
  o.alignment.samples = 2000;
  std::vector<double> seen;
  o.progress = [&](double f) {
    seen.push_back(f);
    return true;
  };
  run(pr, o);
  ASSERT_GE(seen.size(), 3u);
  EXPECT_EQ(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
  // Cancel at the start, during the alignment and during the optimization.
  for (double stop_at : {0.0, 0.05, 0.5}) {
    SurfaceMapOptions c = o;
    c.progress = [stop_at](double f) { return f < stop_at; };
    EXPECT_EQ(status_of([&] { run(pr, c); }), MCON_ERROR_CANCELLED) << stop_at;
  }
}

TEST(SurfaceMap, RejectsBadInput) {
  const synthetic::Problem pr = problem(synthetic::GroundTruth{});
  const MapDomain src{pr.source, pr.source_uv, pr.source_levels};
  const MapDomain dst{pr.target, pr.target_uv, pr.target_levels};
  SurfaceMapOptions o;
  o.alignment.samples = 200;

  for (double bad : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    SurfaceMapOptions r = o;
    r.refine_sigma_factors = {0.5, bad};
    EXPECT_EQ(status_of([&] { compute_surface_map(src, dst, r); }), MCON_ERROR_INVALID_ARGUMENT) << bad;
  }
  SurfaceMapOptions no_iterations = o;
  no_iterations.refine_max_iterations = 0;
  EXPECT_EQ(status_of([&] { compute_surface_map(src, dst, no_iterations); }), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Eigen::MatrixXd> two(pr.target_levels.begin(), pr.target_levels.begin() + 2);
  EXPECT_EQ(status_of([&] { compute_surface_map(src, {pr.target, pr.target_uv, two}, o); }), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Eigen::MatrixXd> none;
  EXPECT_EQ(status_of([&] { compute_surface_map({pr.source, pr.source_uv, none}, dst, o); }), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Eigen::MatrixXd> wide = pr.target_levels;
  for (auto& l : wide) {
    const Eigen::Index d = l.cols();
    l.conservativeResize(Eigen::NoChange, 3);
    l.rightCols(3 - d).setZero();  // conservativeResize leaves new columns uninitialized (NaN -> NON_FINITE)
  }
  EXPECT_EQ(status_of([&] { compute_surface_map(src, {pr.target, pr.target_uv, wide}, o); }), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Eigen::MatrixXd> nan = pr.source_levels;
  nan[1](3, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(status_of([&] { compute_surface_map({pr.source, pr.source_uv, nan}, dst, o); }), MCON_ERROR_NON_FINITE);
  std::vector<Vec2> shrunk = pr.target_uv;
  for (Vec2& p : shrunk) p *= 0.9;
  EXPECT_EQ(status_of([&] { compute_surface_map(src, {pr.target, shrunk, pr.target_levels}, o); }), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Vec2> mirrored = pr.source_uv;
  for (Vec2& p : mirrored) p.y() = -p.y();
  EXPECT_EQ(status_of([&] { compute_surface_map({pr.source, mirrored, pr.source_levels}, dst, o); }), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Vec2> short_uv(pr.source_uv.begin(), pr.source_uv.end() - 1);
  EXPECT_EQ(status_of([&] { compute_surface_map({pr.source, short_uv, pr.source_levels}, dst, o); }), MCON_ERROR_INVALID_ARGUMENT);
  // An annulus (the disk without its center fan) is not a disk.
  TriMesh annulus = pr.target;
  std::vector<Tri> keep;
  for (const Tri& t : annulus.triangles)
    if (t[0] != 0 && t[1] != 0 && t[2] != 0) keep.push_back(t);
  annulus.triangles = keep;
  std::vector<Vec2> annulus_uv = pr.target_uv;
  std::vector<Eigen::MatrixXd> annulus_levels = pr.target_levels;
  const std::vector<int> remap = remove_unreferenced_vertices(annulus);
  std::vector<Vec2> uv2(annulus.positions.size());
  for (std::size_t v = 0; v < remap.size(); ++v)
    if (remap[v] >= 0) uv2[remap[v]] = annulus_uv[v];
  for (auto& l : annulus_levels) l = l.bottomRows(l.rows() - 1).eval();  // vertex 0 was the center
  EXPECT_EQ(status_of([&] { compute_surface_map(src, {annulus, uv2, annulus_levels}, o); }), MCON_ERROR_NOT_A_DISK);
}

// The inexact Newton step (the last factorization preconditioning CG on the current Hessian)
// needs fewer factorizations than plain Newton for the same map.
TEST(SurfaceMap, ReusedFactorizationsGiveTheSameMapWithFewerFactorizations) {
  const synthetic::Problem pr = problem(warped_partial_overlap());
  SurfaceMapOptions newton;
  newton.newton.reuse_factorization = false;
  const SurfaceMap exact = run(pr, newton), reused = run(pr);
  EXPECT_GE(exact.factorizations, exact.iterations);
  EXPECT_EQ(exact.inner_iterations, 0);
  EXPECT_GT(reused.inner_iterations, 0);
  EXPECT_LT(reused.factorizations, exact.factorizations / 2) << reused.factorizations << " vs " << exact.factorizations;
  // Warm start: a stage starts from the previous stage's factorization, so fewer factorizations
  // than stages that iterated (each would factorize at its first step otherwise).
  int stages_run = 0;
  for (const LevelReport& l : reused.levels) stages_run += l.iterations > 0;
  EXPECT_LT(reused.factorizations, stages_run);
  EXPECT_EQ(inverted(pr, reused), 0);
  EXPECT_NEAR(synthetic::mean_error(pr, reused.phi), synthetic::mean_error(pr, exact.phi), 0.002);
  EXPECT_NEAR(reused.matching_score, exact.matching_score, 0.005);
  SurfaceMapOptions bad;
  bad.newton.inexact_tolerance = 1.5;
  EXPECT_EQ(status_of([&] { run(pr, bad); }), MCON_ERROR_INVALID_ARGUMENT);
}

// Coarse to fine in mesh resolution: a 1,261-vertex source with coarse_vertices 300 runs its first
// two stages on a coarse copy; the map is as good as the full-resolution one, flip-free, and
// bit-identical on any thread count. Below 2 * coarse_vertices the full source is used.
TEST(SurfaceMap, CoarseSourceStagesKeepTheQualityOfTheFullResolutionMap) {
  synthetic::GroundTruth truth = warped_partial_overlap();
  const synthetic::Problem pr = synthetic::make_problem(20, 11, truth, 2, {0.2, 0.1, 0.0});
  SurfaceMapOptions full, coarse;
  full.coarse_stages = 0;
  coarse.coarse_vertices = 300;
  const SurfaceMap f = run(pr, full);
  SurfaceMap c;
  tbb::task_arena(1).execute([&] { c = run(pr, coarse); });
  EXPECT_EQ(f.coarse_vertices, 0);
  EXPECT_EQ(c.coarse_stages, 3);
  EXPECT_GE(c.coarse_vertices, 300);
  EXPECT_LE(c.coarse_vertices, 0.6 * pr.source.num_vertices());
  EXPECT_FALSE(c.coarse_fallback);
  EXPECT_EQ(inverted(pr, c), 0);
  const double ef = synthetic::mean_error(pr, f.phi), ec = synthetic::mean_error(pr, c.phi);
  // Measured 0.00980 against 0.00979 at full resolution (315 coarse vertices).
  EXPECT_LT(ec, 0.025);
  EXPECT_NEAR(ec, ef, 0.003) << "coarse " << ec << " full " << ef;
  EXPECT_NEAR(c.overlap_ratio, f.overlap_ratio, 0.01);
  expect_consistent_directions(pr, c);
  SurfaceMap c2;
  tbb::task_arena(2).execute([&] { c2 = run(pr, coarse); });
  EXPECT_EQ(c2.energy_history, c.energy_history);
  for (std::size_t v = 0; v < c.phi.size(); ++v) ASSERT_EQ(c2.phi[v], c.phi[v]) << v;
  SurfaceMapOptions small = coarse;
  small.coarse_vertices = 700;  // 1,261 < 2 * 700
  EXPECT_EQ(run(pr, small).coarse_vertices, 0);
}
