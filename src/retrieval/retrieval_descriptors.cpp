#include "retrieval/retrieval_descriptors.h"

#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "operators/heat_geodesics.h"
#include "descriptors/spectral_descriptors.h"

namespace mcon {

bool is_builtin_descriptor(const std::string& name) { return builtin_descriptor_values(name) > 0; }

int builtin_descriptor_dimension(const std::string& name) {
  if (const std::uint32_t d = builtin_descriptor_values(name)) return static_cast<int>(d);
  fail(MCON_ERROR_INVALID_ARGUMENT, "unknown retrieval descriptor '" + name + "' (curv9, hks or wks)");
}

Eigen::MatrixXd compute_retrieval_descriptor(const TriMesh& mesh, const std::string& name, PatchBoundary boundary) {
  if (name == kDescriptorCurv9) return curv9_descriptor(mesh, boundary);
  // 100 eigenpairs and 100 samples: the thesis' setting (§3.1), fixed samplings for radius-1
  // patches so that histograms of different patches are comparable.
  if (name == kDescriptorHks) return patch_hks(mesh, 100, 100);
  if (name == kDescriptorWks) return patch_wks(mesh, 100, 100);
  fail(MCON_ERROR_INVALID_ARGUMENT, "unknown retrieval descriptor '" + name + "' (curv9, hks or wks)");
}

PatchDescriptors patch_areas_and_center_distance(const TriMesh& mesh, const SurfacePoint& center) {
  require(center.triangle >= 0 && center.triangle < mesh.num_triangles(), MCON_ERROR_INVALID_ARGUMENT,
          "patch center triangle " + std::to_string(center.triangle) + " is outside the patch");
  PatchDescriptors out;
  out.areas = vertex_areas(mesh);
  out.center_distance = HeatGeodesics(mesh).from_point(center.triangle, center.barycentric).cwiseMax(0.0);
  return out;
}

PatchDescriptors describe_patch(const TriMesh& mesh, const SurfacePoint& center,
                                const std::string& descriptor, PatchBoundary boundary) {
  PatchDescriptors out = patch_areas_and_center_distance(mesh, center);
  out.values = compute_retrieval_descriptor(mesh, descriptor, boundary);
  return out;
}

}  // namespace mcon
