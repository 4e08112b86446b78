// A per-face 4-RoSy cross field on the target patch that follows the transferred guide polylines:
// what a quad mesher (QuadWild `.rosy`, libigl MIQ) takes as orientation input (docs/design.md §7).
// Smoothest field with soft alignment constraints, in the complex representation z_f = e^{4i theta}
// (Knoppel et al. 2013, "Globally optimal direction fields"; Ray et al. 2008):
//   minimize  sum_edges w_e |z_f - r_fg z_g|^2  +  lambda sum_constraints w_c |z_f - c|^2,
// one sparse SPD solve. Without any constraint a component gets the smoothest unit field (the
// smallest eigenvector of the connection Laplacian).
#pragma once

#include <array>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

// "In face `face`, the cross should contain `direction`." The direction is projected into the
// face's plane (so a tangent of a guide that bends over an edge is fine); only its angle counts,
// modulo 90 degrees.
struct DirectionConstraint {
  int face = -1;
  Vec3 direction = Vec3::Zero();
  double weight = 1.0;  // >= 0; relative importance among constraints
};

struct CrossFieldOptions {
  // lambda: strength of the constraints against smoothness (the smoothness weights are
  // dimensionless, about 1-3 per edge). Larger follows the guides more tightly.
  double alignment_weight = 10.0;
  // Also align the cross with the boundary edges (each boundary edge adds a constraint of weight
  // boundary_weight to its face), as quad meshers want on a patch border.
  bool align_to_boundary = false;
  double boundary_weight = 1.0;
};

struct CrossField {
  // Per face: one of the four directions of the cross, unit length, in the face plane. The other
  // three are its rotations by 90 degrees about the face normal.
  std::vector<Vec3> directions;
  // Per face in [0, 1]: the magnitude of the solved complex value, i.e. how well the constraints
  // that reach this face agree after transport (1 = all agree; near 0 = conflicting guides or a
  // singularity). 0 on components without any constraint (the field there is only the smoothest).
  std::vector<double> confidence;
};

// Throws mcon::Error(INVALID_ARGUMENT) for a face out of range, a non-finite direction or weight,
// a negative weight, a direction (nearly) normal to its face, a non-empty constraint list whose
// weights are all zero, or bad options; EMPTY_MESH for a mesh without triangles; NUMERICAL if the
// solve fails. Deterministic: the same input gives bit-identical output.
CrossField compute_cross_field(const TriMesh& mesh, const std::vector<DirectionConstraint>& constraints,
                               const CrossFieldOptions& options = {});

// Constraints from guide polylines given as surface points: each segment's direction goes to the
// face it lies in, or to both end faces when its ends lie in different faces (a face where the
// segment is nearly normal to the plane, i.e. across a sharp fold, is skipped). Weight of a
// segment = weight * length / mean edge length, so a guide crossing a face counts about `weight`
// regardless of how densely it is sampled. Zero-length segments are skipped. Throws
// INVALID_ARGUMENT for a face out of range, bad barycentric coordinates or a bad weight.
std::vector<DirectionConstraint> constraints_from_polylines(const TriMesh& mesh,
                                                            const std::vector<std::vector<SurfacePoint>>& polylines,
                                                            double weight = 1.0);

// Constraints along mesh edges (guides cut into the mesh): each edge's direction goes to both of
// its faces with weight `weight`. Throws INVALID_ARGUMENT for a pair that is not an edge.
std::vector<DirectionConstraint> constraints_from_edges(const TriMesh& mesh,
                                                        const std::vector<std::array<int, 2>>& edges,
                                                        double weight = 1.0);

// Makes the field follow `edges` exactly: every face with one of them as a side gets that edge's
// direction (the first such edge in the list), its confidence unchanged.
void align_field_to_edges(const TriMesh& mesh, const std::vector<std::array<int, 2>>& edges, CrossField& field);

}  // namespace mcon
