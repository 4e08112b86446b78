// How much guide polylines zig-zag: the summary's guide_turning of `macrocon embed` compares the
// source's guides with their traces and their cut chains (docs/design.md §14, §16).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "io/mesh_io.h"

namespace mcon::cli {

// Sum of the absolute turning angles (radians) at the interior points of a polyline (and at every
// point of a closed one) divided by its length. 0 for fewer than 3 points.
inline double turning_per_length(const std::vector<Vec3>& points, bool closed) {
  const std::size_t n = points.size();
  if (n < 3) return 0;
  double length = 0, turning = 0;
  const std::size_t segments = closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) length += (points[(i + 1) % n] - points[i]).norm();
  for (std::size_t i = closed ? 0 : 1; i < (closed ? n : n - 1); ++i) {
    const Vec3 a = points[i] - points[(i + n - 1) % n], b = points[(i + 1) % n] - points[i];
    if (a.norm() == 0 || b.norm() == 0) continue;
    turning += std::atan2(a.cross(b).norm(), a.dot(b));
  }
  return length > 0 ? turning / length : 0;
}

// The mean of turning_per_length over the polylines with >= 3 points (0 if there is none).
inline double mean_turning(const std::vector<std::vector<Vec3>>& lines, const std::vector<bool>& closed) {
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].size() >= 3) {
      sum += turning_per_length(lines[i], closed[i]);
      ++count;
    }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace mcon::cli
