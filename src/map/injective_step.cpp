#include "map/injective_step.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/parallel_blocks.h"

namespace mcon {

double smallest_positive_root(double a, double b, double c) {
  const double inf = std::numeric_limits<double>::infinity();
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(c)});
  if (scale == 0) return inf;
  if (std::abs(a) <= 1e-14 * scale) {  // linear
    return b < 0 ? -c / b : inf;
  }
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return inf;
  // Numerically stable roots: q = -(b + sign(b) sqrt(disc)) / 2, roots q / a and c / q.
  const double sq = std::sqrt(disc);
  const double q = -0.5 * (b + (b >= 0 ? sq : -sq));
  double best = inf;
  if (q != 0) {
    const double r1 = q / a, r2 = c / q;
    if (r1 > 0) best = std::min(best, r1);
    if (r2 > 0) best = std::min(best, r2);
  } else {
    // b == 0 and disc == 0 (so a c == 0): no positive root since c > 0 means a == 0 (handled).
  }
  return best;
}

double max_injective_step(const std::vector<Tri>& triangles, const Eigen::VectorXd& x,
                          const Eigen::VectorXd& direction) {
  const int n = static_cast<int>(triangles.size());
  constexpr int kBlock = 1024;
  const int blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> block_min(static_cast<std::size_t>(std::max(blocks, 0)),
                                std::numeric_limits<double>::infinity());
  for_each_block(n, kBlock, [&](int begin, int end, int b) {
    double m = std::numeric_limits<double>::infinity();
    for (int t = begin; t < end; ++t) {
      const Tri& tri = triangles[t];
      const int i = 2 * tri[0], j = 2 * tri[1], k = 2 * tri[2];
      const double x1 = x[j] - x[i], y1 = x[j + 1] - x[i + 1], x2 = x[k] - x[i], y2 = x[k + 1] - x[i + 1];
      const double u1 = direction[j] - direction[i], v1 = direction[j + 1] - direction[i + 1];
      const double u2 = direction[k] - direction[i], v2 = direction[k + 1] - direction[i + 1];
      const double c = x1 * y2 - y1 * x2;
      const double bb = x1 * v2 + u1 * y2 - y1 * u2 - v1 * x2;
      const double a = u1 * v2 - v1 * u2;
      m = std::min(m, smallest_positive_root(a, bb, c));
    }
    block_min[b] = m;
  });
  double m = std::numeric_limits<double>::infinity();
  for (double v : block_min) m = std::min(m, v);
  return m;
}

bool is_inverted(const Tri& tri, const Eigen::VectorXd& x) {
  const int i = 2 * tri[0], j = 2 * tri[1], k = 2 * tri[2];
  const double det = (x[j] - x[i]) * (x[k + 1] - x[i + 1]) - (x[j + 1] - x[i + 1]) * (x[k] - x[i]);
  return !(det > 0);
}

int count_inverted(const std::vector<Tri>& triangles, const Eigen::VectorXd& x) {
  int count = 0;
  for (const Tri& tri : triangles) count += is_inverted(tri, x);
  return count;
}

}  // namespace mcon
