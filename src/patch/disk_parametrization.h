// Tutte embedding with Floater's mean-value weights: a bijective map of a disk-topology mesh onto
// the unit disk. Mean-value weights are positive for every triangle mesh, so with a convex
// boundary the result has no flipped triangle (Floater 2003). Then, by default, a few rounds of
// stretch-reducing reweighting (Yoshizawa, Belyaev, Seidel 2004), which keep the weights positive
// and therefore the embedding bijective: the plain mean-value map squeezes protrusions
// exponentially (on a hand patch, whose boundary is the wrist loop, 80% of the 3D area lay in
// 1.4% of the disk and all five fingertips within 0.003 of each other), which no 2D deformation
// with a distortion term can undo.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace mcon {

// `boundary_loop` is the mesh's single boundary loop in its own winding order (mesh on the left).
// Boundary vertices go onto the unit circle by arc length, counter-clockwise, starting at
// boundary_loop[0] at angle 0. The interior solves the (non-symmetric) mean-value system with a
// sparse LU. Throws mcon::Error: INVALID_ARGUMENT if `boundary_loop` is not a complete boundary
// loop of the mesh in its winding (any start vertex), NOT_A_DISK if the mesh is not one
// topological disk (several loops or components, handles), NUMERICAL if the solve fails.
struct DiskParametrizationOptions {
  // Reweighting rounds after the mean-value solve, w_ij <- w_ij / sigma_j^exponent with sigma_j
  // the area-weighted L2 stretch (Sander et al. 2001) around j; the rounds stop as soon as the
  // total L2 stretch no longer falls, and the least-stretched iterate is returned. 0: the plain
  // mean-value Tutte embedding.
  int stretch_iterations = 30;
  double stretch_exponent = 0.5;  // in (0, 1]
  // The rounds stop once a round lowers the total stretch by less than this fraction (that
  // round's iterate is kept); 0: only when the stretch no longer falls. In [0, 1).
  double stretch_min_decrease = 0.06;
  // The rounds run only if the mean-value map's L2 stretch (1: equal-area) exceeds this; 0: on
  // every patch (measured plain stretch on MakeHuman patches: arm 1.01, nose 1.05, ear 1.2,
  // eye 5.8, face 9.2, mouth 10.2, foot 447, hand 15851). Maps between patches matched better
  // with the rounds on every class, most across families and densities (docs/design.md §17).
  double stretch_threshold = 0.0;
};

// INVALID_ARGUMENT also for stretch_iterations < 0, stretch_exponent outside (0, 1], a negative
// or non-finite stretch_threshold, or stretch_min_decrease outside [0, 1).
std::vector<Vec2> disk_parametrization(const TriMesh& mesh, const std::vector<int>& boundary_loop,
                                       const DiskParametrizationOptions& options = {});

// Moves the vertices with movable[v] != 0 to the mean-value convex combination of their
// neighbours (weights from mesh.positions), the others fixed at their `uv`: the Tutte embedding of
// the movable part inside the rest, one sparse LU. With weights from an embedded rest shape it
// reproduces every affine map of that shape. INVALID_ARGUMENT if `uv` or `movable` does not have
// one entry per vertex; NUMERICAL if a movable vertex has no neighbour or the solve fails.
void mean_value_solve(const TriMesh& mesh, const std::vector<char>& movable, std::vector<Vec2>& uv);

// Triangles whose signed area in `uv` is <= 0 (inverted or degenerate). INVALID_ARGUMENT if `uv`
// does not have one entry per vertex.
int count_flipped_triangles(const TriMesh& mesh, const std::vector<Vec2>& uv);

}  // namespace mcon
