// The per-vertex input of retrieval for one normalized patch (thesis §3.1-3.2): its descriptor
// values (CURV9, HKS or WKS), its vertex areas A_v and the geodesic distance of every vertex from
// the patch center (for the ringed bag-of-features). Library entries, queries and the retrieval
// evaluation all describe patches through this one function, so they agree bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "retrieval/bag_of_features.h"
#include "descriptors/curvature_descriptors.h"
#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

// One built-in retrieval descriptor. Adding a descriptor = one row of builtin_descriptors()
// (retrieval_descriptors.cpp) plus its mcon_retrieval_descriptor value in the public header; the
// library validator, the C API, the CLI and the evaluation all read this table.
struct BuiltinDescriptor {
  const char* name;     // as stored in RetrievalConfig::descriptor and in library files
  std::uint32_t code;   // its mcon_retrieval_descriptor value
  std::uint32_t values; // per vertex
  Eigen::MatrixXd (*compute)(const TriMesh& mesh, PatchBoundary boundary);
};

// Every built-in descriptor, in C API code order.
const std::vector<BuiltinDescriptor>& builtin_descriptors();
// The row named `name` (or with C API code `code`), or nullptr.
const BuiltinDescriptor* find_builtin_descriptor(const std::string& name);
const BuiltinDescriptor* find_builtin_descriptor_code(std::uint32_t code);
// The row named `name`; throws INVALID_ARGUMENT "unknown retrieval descriptor 'x' (curv9, hks or
// wks)" (the name escaped) otherwise.
const BuiltinDescriptor& builtin_descriptor(const std::string& name);
// "curv9, hks or wks": the names for error messages.
std::string builtin_descriptor_names();

// True for a name of builtin_descriptors().
bool is_builtin_descriptor(const std::string& name);
// Values per vertex of a built-in descriptor, 0 for any other name.
std::uint32_t builtin_descriptor_values(const std::string& name);
// Values per vertex of a built-in descriptor; throws INVALID_ARGUMENT otherwise.
int builtin_descriptor_dimension(const std::string& name);

// Per-vertex values of a built-in descriptor on a patch normalized to geodesic radius 1.
// Throws mcon::Error: INVALID_ARGUMENT (unknown name), the mesh's validation errors, NUMERICAL.
Eigen::MatrixXd compute_retrieval_descriptor(const TriMesh& mesh, const std::string& name,
                                             PatchBoundary boundary = PatchBoundary::kCutThroughTriangles);

// Vertex areas and heat-method distances from the center (triangle + barycentric) of the patch;
// `values` is left empty for the caller (compute_retrieval_descriptor or its own descriptors).
PatchDescriptors patch_areas_and_center_distance(const TriMesh& mesh, const SurfacePoint& center);

// Both of the above.
PatchDescriptors describe_patch(const TriMesh& mesh, const SurfacePoint& center,
                                const std::string& descriptor,
                                PatchBoundary boundary = PatchBoundary::kCutThroughTriangles);

}  // namespace mcon
