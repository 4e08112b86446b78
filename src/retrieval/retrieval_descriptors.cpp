#include "retrieval/retrieval_descriptors.h"

#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "base/text.h"
#include "operators/heat_geodesics.h"
#include "descriptors/spectral_descriptors.h"

namespace mcon {

namespace {

Eigen::MatrixXd compute_curv9(const TriMesh& mesh, PatchBoundary boundary) { return curv9_descriptor(mesh, boundary); }
// 100 eigenpairs and 100 samples: the thesis' setting (§3.1), fixed samplings for radius-1
// patches so that histograms of different patches are comparable. Closed-form in the spectrum,
// so the boundary treatment does not apply.
Eigen::MatrixXd compute_hks(const TriMesh& mesh, PatchBoundary) { return patch_hks(mesh, 100, 100); }
Eigen::MatrixXd compute_wks(const TriMesh& mesh, PatchBoundary) { return patch_wks(mesh, 100, 100); }

}  // namespace

const std::vector<BuiltinDescriptor>& builtin_descriptors() {
  static const std::vector<BuiltinDescriptor> table = {
      {kDescriptorCurv9, MCON_RETRIEVAL_DESCRIPTOR_CURV9, 9, compute_curv9},
      {"hks", MCON_RETRIEVAL_DESCRIPTOR_HKS, 100, compute_hks},
      {"wks", MCON_RETRIEVAL_DESCRIPTOR_WKS, 100, compute_wks},
  };
  return table;
}

const BuiltinDescriptor* find_builtin_descriptor(const std::string& name) {
  for (const BuiltinDescriptor& d : builtin_descriptors())
    if (name == d.name) return &d;
  return nullptr;
}

const BuiltinDescriptor* find_builtin_descriptor_code(std::uint32_t code) {
  for (const BuiltinDescriptor& d : builtin_descriptors())
    if (code == d.code) return &d;
  return nullptr;
}

std::string builtin_descriptor_names() {
  const auto& table = builtin_descriptors();
  std::string out;
  for (std::size_t i = 0; i < table.size(); ++i)
    out += (i == 0 ? "" : i + 1 == table.size() ? " or " : ", ") + std::string(table[i].name);
  return out;
}

bool is_builtin_descriptor(const std::string& name) { return find_builtin_descriptor(name) != nullptr; }

std::uint32_t builtin_descriptor_values(const std::string& name) {
  const BuiltinDescriptor* d = find_builtin_descriptor(name);
  return d ? d->values : 0;
}

const BuiltinDescriptor& builtin_descriptor(const std::string& name) {
  if (const BuiltinDescriptor* d = find_builtin_descriptor(name)) return *d;
  fail(MCON_ERROR_INVALID_ARGUMENT,
       "unknown retrieval descriptor '" + printable_text(name) + "' (" + builtin_descriptor_names() + ")");
}

int builtin_descriptor_dimension(const std::string& name) { return static_cast<int>(builtin_descriptor(name).values); }

Eigen::MatrixXd compute_retrieval_descriptor(const TriMesh& mesh, const std::string& name, PatchBoundary boundary) {
  return builtin_descriptor(name).compute(mesh, boundary);
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
