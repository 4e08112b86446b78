// A per-vertex descriptor (d values per vertex) of the target patch seen as a function on the
// target's disk parametrization: linear inside each triangle, so its value and d x 2 gradient are
// exact there and the Gauss-Newton model of a squared descriptor difference is the exact second
// order model (docs/design.md §2). Points a little outside the triangulation (between the
// boundary polygon and the unit circle) get the value at their nearest point of the
// triangulation, which keeps the field continuous.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh/point_location_2d.h"

namespace mcon {

class DescriptorField2D {
 public:
  DescriptorField2D() = default;
  // `values` has one row per point of the locator (the target's vertices); the locator must
  // outlive the field.
  DescriptorField2D(const TriangleLocator2D& locator, const Eigen::MatrixXd& values);

  int dimension() const { return dim_; }

  // Writes the value (d entries) and the gradient (d entries d/dx, then d entries d/dy) at p.
  // Returns the location: triangle -1 (and nothing written) if p is neither inside nor within
  // `max_outside` of a triangle. Outside the triangulation the gradient is that of the
  // nearest-point extension (along the nearest edge, zero at a nearest vertex).
  PointLocation evaluate(const Vec2& p, double max_outside, double* value, double* grad_x, double* grad_y) const;

  // The two halves of evaluate, so fields on the same triangulation (the levels of a pyramid)
  // can share one lookup. evaluate_at requires loc.triangle >= 0.
  // `hint`: the triangle of a nearby earlier query, or -1 (TriangleLocator2D::locate).
  PointLocation locate(const Vec2& p, double max_outside, int hint = -1) const;
  void evaluate_at(const PointLocation& loc, double* value, double* grad_x, double* grad_y) const;
  const TriangleLocator2D& locator() const { return *locator_; }

 private:
  const TriangleLocator2D* locator_ = nullptr;
  int dim_ = 0;
  std::vector<double> corner_values_;  // per triangle: 3 * d values (corner-major)
  std::vector<double> gradients_;      // per triangle: 2 * d values (d/dx block, d/dy block)
};

}  // namespace mcon
