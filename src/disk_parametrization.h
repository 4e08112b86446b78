// Tutte embedding with Floater's mean-value weights: a bijective map of a disk-topology mesh onto
// the unit disk. Mean-value weights are positive for every triangle mesh, so with a convex
// boundary the result has no flipped triangle (Floater 2003).
#pragma once

#include <vector>

#include "mesh.h"

namespace mcon {

// `boundary_loop` is the mesh's single boundary loop in its own winding order (mesh on the left).
// Boundary vertices go onto the unit circle by arc length, counter-clockwise, starting at
// boundary_loop[0] at angle 0. The interior solves the (non-symmetric) mean-value system with a
// sparse LU. Throws mcon::Error: INVALID_ARGUMENT if `boundary_loop` is not a complete boundary
// loop of the mesh in its winding (any start vertex), NOT_A_DISK if the mesh is not one
// topological disk (several loops or components, handles), NUMERICAL if the solve fails.
std::vector<Vec2> disk_parametrization(const TriMesh& mesh, const std::vector<int>& boundary_loop);

// Triangles whose signed area in `uv` is <= 0 (inverted or degenerate). INVALID_ARGUMENT if `uv`
// does not have one entry per vertex.
int count_flipped_triangles(const TriMesh& mesh, const std::vector<Vec2>& uv);

}  // namespace mcon
