// Geodesic distance by the heat method (Crane, Weischedel, Wardetzky 2013): one short heat flow,
// normalize its gradient, then a Poisson solve. Both linear systems are factored once, so many
// sources are cheap. Boundaries use the average of the Neumann and Dirichlet heat flows (§3.2.2
// of the paper), which keeps distances accurate near open boundaries.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace mcon {

struct HeatGeodesicsOptions {
  // Heat time t = time_factor * h^2 with h the mean edge length (the paper's recommendation).
  double time_factor = 1.0;
  // Average Neumann and Dirichlet heat flows on meshes with a boundary.
  bool boundary_average = true;
  // Build the operators on the intrinsic Delaunay triangulation (src/intrinsic_delaunay.h)
  // instead of the mesh's own triangles: same result on Delaunay meshes, and robust (no negative
  // heat, ~4x smaller errors on the MakeHuman body) on obtuse or quad-split triangulations.
  bool intrinsic_delaunay = true;
};

// Accuracy (t = h^2): about 1% mean relative error on regular and jittered meshes, 2.5% on the
// MakeHuman body (tests, bench/heat_geodesics_bench.cpp). Reach: the heat decays by about e per
// edge, so beyond roughly 1300 * sqrt(time_factor) mean edge lengths from every source the field
// has no usable gradient and distances there are underestimated. Vertices in connected components
// without a source get +infinity. The query functions are const and may be called concurrently;
// sources are validated (mcon::Error with MCON_ERROR_INVALID_ARGUMENT).
class HeatGeodesics {
 public:
  // Factors the operators (throws mcon::Error: EMPTY_MESH, NON_FINITE, INDEX_OUT_OF_RANGE,
  // ISOLATED_VERTEX, NON_MANIFOLD_EDGE, INVALID_ARGUMENT for a bad time_factor, NUMERICAL).
  explicit HeatGeodesics(const TriMesh& mesh, const HeatGeodesicsOptions& options = {});
  ~HeatGeodesics();
  HeatGeodesics(HeatGeodesics&&) noexcept;
  HeatGeodesics& operator=(HeatGeodesics&&) noexcept;

  // Distance from a set of source vertices (distance 0 at each; order and repeats are ignored).
  Eigen::VectorXd from_vertices(const std::vector<int>& sources) const;
  // Distance from a point inside triangle t at barycentric coordinates bary (each >= 0, sum 1,
  // within 1e-6). The constant is fixed so that the triangle's corners carry, in the barycentric
  // mean, their straight-line distances to the point.
  Eigen::VectorXd from_point(int triangle, const Vec3& barycentric) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mcon
