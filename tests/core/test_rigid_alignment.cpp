#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <tbb/task_arena.h>

#include "base/error.h"
#include "map/map_energy.h"
#include "map/rigid_alignment.h"
#include "synthetic_maps.h"

using namespace mcon;

namespace {

constexpr double kPi = 3.141592653589793;

double angle_error(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 2 * kPi);
  return std::min(d, 2 * kPi - d);
}

struct AlignmentCase {
  synthetic::Problem pr;
  std::unique_ptr<TriangleLocator2D> locator;
  std::vector<std::unique_ptr<DescriptorField2D>> fields;
  std::vector<MatchLevel> levels;
  std::vector<double> weights;

  explicit AlignmentCase(const synthetic::GroundTruth& truth) : pr(synthetic::make_problem(12, 11, truth, 2)) {
    locator = std::make_unique<TriangleLocator2D>(pr.target_uv, pr.target.triangles);
    for (std::size_t l = 0; l < pr.source_levels.size(); ++l) {
      fields.push_back(std::make_unique<DescriptorField2D>(*locator, pr.target_levels[l]));
      MatchLevel level;
      level.source_values = &pr.source_levels[l];
      level.target_field = fields.back().get();
      level.score.sigma = descriptor_sigma(pr.source_levels[l], pr.target_levels[l]);
      levels.push_back(level);
    }
    weights = make_source_disk(pr.source, pr.source_uv, false).vertex_weight;
  }

  RigidAlignmentResult align(const RigidAlignmentOptions& o = {}) const {
    return align_rigid(pr.source_uv, weights, levels, o);
  }
};

}  // namespace

TEST(RigidAlignment, CandidatesFollowTheSamplingRule) {
  RigidAlignmentOptions o;
  int reflected = 0;
  double sum_t2 = 0;
  int random = 0;
  for (int i = 0; i < o.samples; ++i) {
    const RigidTransform2D T = rigid_candidate(o, i);
    reflected += T.reflected;
    ASSERT_LE(T.translation.cwiseAbs().maxCoeff(), o.translation_bound);
    ASSERT_GE(T.angle, 0.0);
    ASSERT_LT(T.angle, 2 * kPi);
    if (i < 2 * o.zero_translation_angles) {
      EXPECT_EQ(T.translation.norm(), 0.0);
    } else {
      sum_t2 += T.translation.squaredNorm();
      ++random;
    }
    const RigidTransform2D again = rigid_candidate(o, i);
    EXPECT_EQ(again.angle, T.angle);
    EXPECT_EQ(again.translation, T.translation);
  }
  EXPECT_EQ(reflected, o.samples / 2);
  // Truncated N(0,1) on [-2, 2] has variance 0.774 per axis.
  EXPECT_NEAR(sum_t2 / random, 2 * 0.774, 0.08);
}

TEST(RigidAlignment, FindsRotationTranslationAndReflection) {
  for (bool mirrored : {false, true}) {
    synthetic::GroundTruth truth;
    truth.angle = 70 * kPi / 180;
    truth.translation = Vec2(0.15, -0.1);
    truth.reflected = mirrored;
    const AlignmentCase s(truth);
    const RigidAlignmentResult r = s.align();
    EXPECT_EQ(r.transform.reflected, mirrored);
    EXPECT_LT(angle_error(r.transform.angle, truth.angle), 3 * kPi / 180) << r.transform.angle * 180 / kPi;
    EXPECT_LT((r.transform.translation - truth.translation).norm(), 0.05);
    EXPECT_GT(r.score, 0.85);
    EXPECT_GE(r.best_sample, 0);
  }
}

TEST(RigidAlignment, SameResultOnAnyThreadCount) {
  synthetic::GroundTruth truth;
  truth.angle = 2.0;
  truth.reflected = true;
  truth.warp = 0.05;
  const AlignmentCase s(truth);
  RigidAlignmentOptions o;
  o.samples = 3000;
  RigidAlignmentResult ref;
  for (int threads : {1, 2, 4}) {
    RigidAlignmentResult r;
    tbb::task_arena(threads).execute([&] { r = s.align(o); });
    if (threads == 1) {
      ref = r;
      continue;
    }
    EXPECT_EQ(r.best_sample, ref.best_sample);
    EXPECT_EQ(r.transform.angle, ref.transform.angle);
    EXPECT_EQ(r.transform.translation, ref.transform.translation);
    EXPECT_EQ(r.transform.reflected, ref.transform.reflected);
    EXPECT_EQ(r.score, ref.score);
  }
}

TEST(RigidAlignment, ProgressCanCancel) {
  synthetic::GroundTruth truth;
  const AlignmentCase s(truth);
  int calls = 0;
  try {
    align_rigid(s.pr.source_uv, s.weights, s.levels, {}, [&](double f) {
      EXPECT_GE(f, 0.0);
      EXPECT_LE(f, 1.0);
      return ++calls < 2;
    });
    FAIL() << "not cancelled";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_CANCELLED);
  }
  EXPECT_EQ(calls, 2);
}
