// Geodesic distance by the heat method (Crane, Weischedel, Wardetzky 2013): one short heat flow,
// normalize its gradient, then a Poisson solve. Both linear systems are factored once, so many
// sources are cheap. Boundaries use the average of the Neumann and Dirichlet heat flows (§3.2.2
// of the paper), which keeps distances accurate near open boundaries.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "mesh.h"

namespace mcon {

struct HeatGeodesicsOptions {
  // Heat time t = time_factor * h^2 with h the mean edge length (the paper's recommendation).
  double time_factor = 1.0;
  // Average Neumann and Dirichlet heat flows on meshes with a boundary.
  bool boundary_average = true;
};

class HeatGeodesics {
 public:
  explicit HeatGeodesics(const TriMesh& mesh, const HeatGeodesicsOptions& options = {});
  ~HeatGeodesics();
  HeatGeodesics(HeatGeodesics&&) noexcept;
  HeatGeodesics& operator=(HeatGeodesics&&) noexcept;

  // Distance from a set of source vertices (distance 0 at each).
  Eigen::VectorXd from_vertices(const std::vector<int>& sources) const;
  // Distance from a point inside triangle t at barycentric coordinates bary.
  Eigen::VectorXd from_point(int triangle, const Vec3& barycentric) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mcon
