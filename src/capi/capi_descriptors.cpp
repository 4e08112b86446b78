// Descriptors: per-vertex curvature descriptors of a patch (curvature_descriptors.h, thesis §3.1).
#include <cmath>

#include "capi/capi_handles.h"
#include "descriptors/curvature_descriptors.h"

using namespace mcon;
using namespace mcon::capi;

namespace {

// `code` is the raw value a caller passed for an mcon_descriptor (see enum_bits).
std::uint32_t descriptor_dimension(std::int32_t code) {
  if (code == MCON_DESCRIPTOR_CURV9) return 9;
  if (code == MCON_DESCRIPTOR_MEAN_CURVATURE) return 1;
  fail(MCON_ERROR_INVALID_ARGUMENT, "descriptor " + std::to_string(code) +
                                        " is not an mcon_descriptor (MCON_DESCRIPTOR_CURV9 = 1, "
                                        "MCON_DESCRIPTOR_MEAN_CURVATURE = 2)");
}

// Vertex-major values, vertex_count x dimension.
// (`code` has been checked by descriptor_dimension.)
Eigen::MatrixXd compute(const TriMesh& mesh, std::int32_t code) {
  if (code == MCON_DESCRIPTOR_CURV9) return curv9_descriptor(mesh);
  return mean_curvature_descriptor(mesh);
}

}  // namespace

extern "C" {

mcon_status mcon_descriptor_get_dimension(mcon_descriptor descriptor, uint32_t* out_dimension) {
  return guard("mcon_descriptor_get_dimension", [&] {
    require_pointer(out_dimension, "out_dimension");
    *out_dimension = descriptor_dimension(enum_bits(descriptor));
  });
}

mcon_status mcon_patch_compute_descriptors(mcon_patch patch, mcon_descriptor descriptor, double* out_values,
                                           size_t capacity) {
  return guard_object("mcon_patch_compute_descriptors", patch, "patch", [&] {
    const std::int32_t code = enum_bits(descriptor);
    const std::uint32_t dimension = descriptor_dimension(code);
    require_pointer(out_values, "out_values");
    const TriMesh& mesh = patch->patch.mesh;
    const std::size_t n = mesh.positions.size();
    require_capacity(capacity, n * dimension, "out_values (capacity in doubles)");

    const Eigen::MatrixXd values = run_in_arena(patch->context, [&] { return compute(mesh, code); });
    require(static_cast<std::size_t>(values.rows()) == n && values.cols() == dimension, MCON_ERROR_UNKNOWN,
            "descriptor has shape " + std::to_string(values.rows()) + " x " + std::to_string(values.cols()) +
                ", expected " + std::to_string(n) + " x " + std::to_string(dimension));
    for (Eigen::Index v = 0; v < values.rows(); ++v)
      for (Eigen::Index k = 0; k < values.cols(); ++k)
        require(std::isfinite(values(v, k)), MCON_ERROR_NUMERICAL,
                "descriptor value " + std::to_string(k) + " of vertex " + std::to_string(v) + " is not finite");
    // Written only once everything succeeded.
    for (Eigen::Index v = 0; v < values.rows(); ++v)
      for (Eigen::Index k = 0; k < values.cols(); ++k) out_values[v * dimension + k] = values(v, k);
  });
}

}  // extern "C"
