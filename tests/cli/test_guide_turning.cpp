// The product CLI's own helpers (tools/cli): the guide turning measure of `macrocon embed`.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cli/guide_turning.h"

namespace {

using mcon::Vec3;
using mcon::cli::mean_turning;
using mcon::cli::turning_per_length;

const double kPi = std::acos(-1.0);

TEST(GuideTurning, TurningPerLengthMeasuresZigZag) {
  const std::vector<Vec3> straight{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  EXPECT_DOUBLE_EQ(turning_per_length(straight, false), 0.0);
  const std::vector<Vec3> step{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(2, 1, 0)};
  EXPECT_NEAR(turning_per_length(step, false), kPi / 3, 1e-12);  // two right angles over length 3
  const std::vector<Vec3> square{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  EXPECT_NEAR(turning_per_length(square, true), 2 * kPi / 4, 1e-12);
}

TEST(GuideTurning, TheMeanSkipsPolylinesTooShortToTurn) {
  const std::vector<Vec3> square{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  const std::vector<Vec3> segment{Vec3(0, 0, 0), Vec3(5, 0, 0)};
  EXPECT_NEAR(mean_turning({square, segment}, {true, false}), kPi / 2, 1e-12);
  EXPECT_EQ(mean_turning({segment}, {false}), 0.0);
  EXPECT_EQ(mean_turning({}, {}), 0.0);
}

}  // namespace
