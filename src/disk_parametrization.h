// Tutte embedding with Floater's mean-value weights: a bijective map of a disk-topology mesh onto
// the unit disk. Mean-value weights are positive for every triangle mesh, so with a convex
// boundary the result has no flipped triangle (Floater 2003).
#pragma once

#include <vector>

#include "mesh.h"

namespace mcon {

// `boundary_loop` is the mesh's single boundary loop in its own winding order (mesh on the left).
// Boundary vertices go onto the unit circle by arc length, counter-clockwise, starting at
// boundary_loop[0] at angle 0. Throws mcon::Error(MCON_ERROR_NUMERICAL) if the solve fails.
std::vector<Vec2> disk_parametrization(const TriMesh& mesh, const std::vector<int>& boundary_loop);

// Triangles whose signed area in `uv` is <= 0 (inverted or degenerate).
int count_flipped_triangles(const TriMesh& mesh, const std::vector<Vec2>& uv);

}  // namespace mcon
