#include <gtest/gtest.h>

#include <cmath>

#include "base/counter_rng.h"

using namespace mcon;

TEST(CounterRng, StreamsArePureFunctionsOfSeedAndIndex) {
  CounterRng a(42, 7), b(42, 7), c(42, 8), d(43, 7);
  int same_c = 0, same_d = 0;
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next_u64();
    EXPECT_EQ(x, b.next_u64());
    same_c += x == c.next_u64();
    same_d += x == d.next_u64();
  }
  EXPECT_EQ(same_c, 0);
  EXPECT_EQ(same_d, 0);
}

TEST(CounterRng, MomentsOfUniformAndNormal) {
  const int n = 200000;
  double su = 0, su2 = 0, sn = 0, sn2 = 0;
  for (int i = 0; i < n; ++i) {
    CounterRng r(1, static_cast<std::uint64_t>(i));  // one draw per stream: streams are independent
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u;
    su2 += u * u;
    const double z = r.normal();
    sn += z;
    sn2 += z * z;
  }
  EXPECT_NEAR(su / n, 0.5, 0.005);
  EXPECT_NEAR(su2 / n - (su / n) * (su / n), 1.0 / 12, 0.002);
  EXPECT_NEAR(sn / n, 0.0, 0.01);
  EXPECT_NEAR(sn2 / n, 1.0, 0.02);
}

TEST(CounterRng, TruncatedNormalStaysInBounds) {
  CounterRng r(9, 0);
  int beyond_one = 0;
  for (int i = 0; i < 20000; ++i) {
    const double z = r.truncated_normal(2.0);
    ASSERT_LE(std::abs(z), 2.0);
    beyond_one += std::abs(z) > 1;
  }
  // P(|Z| > 1 given |Z| <= 2) = (0.9545 - 0.6827) / 0.9545 = 0.285
  EXPECT_NEAR(beyond_one / 20000.0, 0.285, 0.02);
}
