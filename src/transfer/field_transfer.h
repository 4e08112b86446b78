// Per-vertex fields of the source patch -> the target patch's vertices through the map's
// target_to_source correspondences (thesis §4.4: the map is dense, C0 and locally injective, so
// anything that can be linearly interpolated transfers). One function per kind of field:
//  - interpolated (scalar channels, vector3 in patch coordinates, uv): the barycentric blend of
//    the source triangle's corners at Phi^-1(w);
//  - integer labels: the label of the corner with the largest barycentric weight, never a blend
//    (ties: the lowest corner slot of the triangle);
//  - tangent vectors: pushed forward by the map's Jacobian J_Phi = J_g^-1 · J_phi · J_f (the
//    composition of eq. 4.1, thesis §4.1.2) and re-projected onto the target vertex's tangent plane.
// Target vertices without a preimage (outside the overlap, outside_mask = 1) get zeros, or the
// caller's outside label.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "transfer/map_view.h"

namespace mcon {

// 1 for target vertices with no source preimage, else 0.
std::vector<std::uint8_t> outside_mask(const MapView& map);

// rows = source vertices, any number of columns -> rows = target vertices. Throws
// INVALID_ARGUMENT on a row count mismatch, NON_FINITE on a NaN or infinite value.
Eigen::MatrixXd transfer_interpolated(const MapView& map, const Eigen::MatrixXd& source_values);

// `dimension` labels per source vertex (vertex-major) -> `dimension` per target vertex.
std::vector<std::int32_t> transfer_labels(const MapView& map, int dimension, const std::vector<std::int32_t>& labels,
                                          std::int32_t outside_label);

// Tangent vectors (3D, one per source vertex, in normalized patch coordinates) -> tangent vectors
// of the target vertices. At a target vertex w whose preimage lies in source triangle s:
//   v   = the barycentric blend of the corners' vectors, projected into the plane of s;
//   d   = J_phi · J_f · v, the image in the target disk's plane (phi is affine on s, so this is
//         the affine map from the 3D triangle s onto its image triangle phi(s));
//   u   = J_g^-1 · d, lifted onto every target triangle around w (J_g^-1 is constant per target
//         triangle, the C0 discontinuity the thesis notes: the lifts are averaged with the
//         triangles' angles at w), then projected onto w's tangent plane (angle-weighted normal).
// Length: the result keeps the length of v (the source vector's own magnitude, e.g. a guide
// direction or a sizing-weighted direction), not the map's stretch |J v|, which on conformal maps
// between differently sized features is an arbitrary scale. Only the direction comes from J.
// A zero vector stays zero; if the push-forward degenerates (|u| tiny) the result is zero.
// Throws INVALID_ARGUMENT on a size mismatch, NON_FINITE on NaN.
std::vector<Vec3> transfer_tangent_vectors(const MapView& map, const std::vector<Vec3>& source_vectors);

// Angle-weighted unit vertex normals of a mesh (zero for a vertex whose triangles cancel).
std::vector<Vec3> vertex_normals(const TriMesh& mesh);

}  // namespace mcon
