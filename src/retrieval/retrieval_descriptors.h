// The per-vertex input of retrieval for one normalized patch (thesis §3.1-3.2): its descriptor
// values (CURV9, HKS or WKS), its vertex areas A_v and the geodesic distance of every vertex from
// the patch center (for the ringed bag-of-features). Library entries, queries and the retrieval
// evaluation all describe patches through this one function, so they agree bit for bit.
#pragma once

#include <string>

#include "retrieval/bag_of_features.h"
#include "descriptors/curvature_descriptors.h"
#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

// Built-in descriptor names: kDescriptorCurv9 / kDescriptorHks / kDescriptorWks
// (retrieval/retrieval_config.h). True for "curv9", "hks", "wks".
bool is_builtin_descriptor(const std::string& name);
// Values per vertex of a built-in descriptor (9, 100, 100); throws INVALID_ARGUMENT otherwise.
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
