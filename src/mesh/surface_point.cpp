#include "mesh/surface_point.h"

#include <cmath>

#include "base/error.h"

namespace mcon {

Vec3 checked_barycentric(int triangle, const Vec3& b, int triangle_count, const std::string& what) {
  require(triangle >= 0 && triangle < triangle_count, MCON_ERROR_INVALID_ARGUMENT,
          what + ": triangle " + std::to_string(triangle) + " is out of range (the patch has " +
              std::to_string(triangle_count) + " triangles)");
  require(b.allFinite(), MCON_ERROR_NON_FINITE, what + ": barycentric weights are not finite");
  const double sum = b.sum();
  require(b.minCoeff() >= -1e-9 && std::abs(sum - 1.0) <= 1e-6, MCON_ERROR_INVALID_ARGUMENT,
          what + ": barycentric weights (" + std::to_string(b[0]) + ", " + std::to_string(b[1]) + ", " +
              std::to_string(b[2]) + ") are not a point of the triangle (each >= 0, sum 1)");
  const Vec3 c = b.cwiseMax(0.0);
  return c / c.sum();
}

}  // namespace mcon
