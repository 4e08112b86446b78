#include "descriptors/descriptor_pyramid.h"

#include <cmath>
#include <memory>

#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "operators/heat_smoothing.h"

namespace mcon {

std::vector<Eigen::MatrixXd> descriptor_pyramid(const TriMesh& mesh, const Eigen::MatrixXd& values,
                                                const std::vector<double>& sigmas) {
  require(values.rows() == mesh.num_vertices(), MCON_ERROR_INVALID_ARGUMENT,
          "descriptor pyramid: one row per vertex expected");
  require(values.allFinite(), MCON_ERROR_NON_FINITE, "descriptor pyramid: non-finite value");
  for (double s : sigmas)
    require(s >= 0 && std::isfinite(s), MCON_ERROR_INVALID_ARGUMENT, "descriptor pyramid: sigma must be >= 0");
  std::vector<Eigen::MatrixXd> levels;
  levels.reserve(sigmas.size());
  std::unique_ptr<HeatSmoother> smoother;  // one symbolic analysis for all scales
  for (double s : sigmas) {
    if (s == 0) {
      levels.push_back(values);
      continue;
    }
    if (!smoother)
      smoother = std::make_unique<HeatSmoother>(cotan_laplacian(mesh), vertex_areas(mesh), 0.5 * s * s);
    else
      smoother->set_time(0.5 * s * s);
    levels.push_back(smoother->smooth(values));
  }
  return levels;
}

}  // namespace mcon
