#include "map/descriptor_field_2d.h"

#include <cmath>

#include "base/error.h"

namespace mcon {

DescriptorField2D::DescriptorField2D(const TriangleLocator2D& locator, const Eigen::MatrixXd& values)
    : locator_(&locator), dim_(static_cast<int>(values.cols())) {
  require(values.rows() == static_cast<Eigen::Index>(locator.points().size()), MCON_ERROR_INVALID_ARGUMENT,
          "descriptor field: one row per vertex expected");
  require(dim_ > 0, MCON_ERROR_INVALID_ARGUMENT, "descriptor field: dimension 0");
  require(values.allFinite(), MCON_ERROR_NON_FINITE, "descriptor field: non-finite descriptor value");
  const auto& pts = locator.points();
  const auto& tris = locator.triangles();
  corner_values_.resize(tris.size() * 3 * dim_);
  gradients_.resize(tris.size() * 2 * dim_);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const Tri& tri = tris[t];
    const Vec2 e1 = pts[tri[1]] - pts[tri[0]], e2 = pts[tri[2]] - pts[tri[0]];
    Eigen::Matrix2d E;
    E << e1, e2;
    const double det = E.determinant();
    // Rows of E^-1 map a displacement to the barycentric weights of corners 1 and 2.
    Eigen::Matrix2d Einv = Eigen::Matrix2d::Zero();
    if (det != 0 && std::isfinite(det)) Einv = E.inverse();
    double* cv = &corner_values_[t * 3 * dim_];
    double* g = &gradients_[t * 2 * dim_];
    for (int k = 0; k < dim_; ++k) {
      const double v0 = values(tri[0], k), v1 = values(tri[1], k), v2 = values(tri[2], k);
      cv[k] = v0;
      cv[dim_ + k] = v1;
      cv[2 * dim_ + k] = v2;
      // grad = (v1 - v0) * Einv.row(0) + (v2 - v0) * Einv.row(1)
      g[k] = (v1 - v0) * Einv(0, 0) + (v2 - v0) * Einv(1, 0);
      g[dim_ + k] = (v1 - v0) * Einv(0, 1) + (v2 - v0) * Einv(1, 1);
    }
  }
}

PointLocation DescriptorField2D::evaluate(const Vec2& p, double max_outside, double* value, double* grad_x,
                                          double* grad_y) const {
  const PointLocation loc = locate(p, max_outside);
  if (loc.triangle >= 0) evaluate_at(loc, value, grad_x, grad_y);
  return loc;
}

PointLocation DescriptorField2D::locate(const Vec2& p, double max_outside, int hint) const {
  return max_outside > 0 ? locator_->locate_nearest(p, max_outside, hint) : locator_->locate(p, hint);
}

void DescriptorField2D::evaluate_at(const PointLocation& loc, double* value, double* grad_x, double* grad_y) const {
  const int t = loc.triangle;
  const double* cv = &corner_values_[static_cast<std::size_t>(t) * 3 * dim_];
  const double* g = &gradients_[static_cast<std::size_t>(t) * 2 * dim_];
  const Vec3& l = loc.barycentric;
  for (int k = 0; k < dim_; ++k) value[k] = l[0] * cv[k] + l[1] * cv[dim_ + k] + l[2] * cv[2 * dim_ + k];
  if (loc.distance == 0) {
    for (int k = 0; k < dim_; ++k) {
      grad_x[k] = g[k];
      grad_y[k] = g[dim_ + k];
    }
    return;
  }
  // Nearest-point extension: the derivative of the nearest point is the projection onto the
  // nearest edge (one zero weight) or zero (nearest point is a corner).
  int zeros = 0, zero_corner = -1;
  for (int i = 0; i < 3; ++i)
    if (l[i] == 0) {
      ++zeros;
      zero_corner = i;
    }
  if (zeros != 1) {
    for (int k = 0; k < dim_; ++k) grad_x[k] = grad_y[k] = 0;
    return;
  }
  const Tri& tri = locator_->triangles()[t];
  const auto& pts = locator_->points();
  const Vec2 e = pts[tri[(zero_corner + 2) % 3]] - pts[tri[(zero_corner + 1) % 3]];
  const double len2 = e.squaredNorm();
  for (int k = 0; k < dim_; ++k) {
    const double along = (g[k] * e.x() + g[dim_ + k] * e.y()) / len2;  // d value / d (edge parameter * len)
    grad_x[k] = along * e.x();
    grad_y[k] = along * e.y();
  }
}

}  // namespace mcon
