// The largest step t along a search direction before any triangle of a planar mesh inverts
// (Smith & Schaefer 2015, "Bijective parameterization with free boundaries", §4.1): per
// triangle det(t) = a t^2 + b t + c is the signed area along the line, and the first positive
// root over all triangles bounds the step. Line searches that start below it never leave the
// region where the injectivity barrier is finite.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace mcon {

// Smallest positive root of a t^2 + b t + c (c > 0 assumed), +infinity if there is none.
double smallest_positive_root(double a, double b, double c);

// x and direction are 2 * num_vertices (x0, y0, x1, y1, ...). Triangles are assumed positively
// oriented at x. Returns +infinity if no triangle ever inverts along the ray.
double max_injective_step(const std::vector<Tri>& triangles, const Eigen::VectorXd& x,
                          const Eigen::VectorXd& direction);

// Whether a triangle's signed area at x is <= 0 (or not a number).
bool is_inverted(const Tri& tri, const Eigen::VectorXd& x);

// Triangles whose signed area at x is <= 0.
int count_inverted(const std::vector<Tri>& triangles, const Eigen::VectorXd& x);

}  // namespace mcon
