#include "patch_map.h"

#include "curvature_descriptors.h"
#include "descriptor_pyramid.h"
#include "error.h"

namespace mcon {

namespace {

// Mean curvature at sigma 0.1 (thesis §4.2: one smooth, orientation-blind scalar suffices for the
// map; the pyramid adds the coarser scales).
std::vector<Eigen::MatrixXd> map_descriptor_levels(const Patch& patch, const std::vector<double>& sigmas) {
  const Eigen::MatrixXd h = mean_curvature_descriptor(patch.mesh);
  return descriptor_pyramid(patch.mesh, h, sigmas);
}

}  // namespace

SurfaceMap map_patches(const Patch& source, const Patch& target, const PatchMapOptions& options) {
  require(!options.pyramid_sigmas.empty(), MCON_ERROR_INVALID_ARGUMENT, "map_patches: no descriptor levels");
  const std::vector<Eigen::MatrixXd> source_levels = map_descriptor_levels(source, options.pyramid_sigmas);
  const std::vector<Eigen::MatrixXd> target_levels = map_descriptor_levels(target, options.pyramid_sigmas);
  return compute_surface_map({source.mesh, source.uv, source_levels}, {target.mesh, target.uv, target_levels},
                             options.map);
}

}  // namespace mcon
