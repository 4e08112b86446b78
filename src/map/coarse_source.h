// A coarser copy of a map's source disk, for the first (smoothest) stages of a map: coarse to
// fine in mesh resolution (docs/design.md §13). Interior vertices are removed by halfedge
// collapses onto a neighbour in the disk's uv, shortest edge first, so the surviving vertices keep
// their uv, 3D position and descriptors and the rim stays as it is; a stage's result on the
// coarse disk is prolonged to every fine vertex by its barycentric coordinates in the coarse uv
// triangle that contains it.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace mcon {

struct CoarseSource {
  TriMesh mesh;                                   // surviving vertices (their 3D positions), coarse triangles
  std::vector<Vec2> uv;                           // their uv
  std::vector<int> to_fine;                       // coarse vertex -> fine vertex
  std::vector<Tri> prolong_corners;               // per fine vertex: the coarse triangle's corners
  std::vector<Vec3> prolong_weights;              // and its barycentric coordinates there

  int num_vertices() const { return mesh.num_vertices(); }
  // Per-vertex rows of the fine source, for the coarse one.
  Eigen::MatrixXd restrict_rows(const Eigen::MatrixXd& fine) const;
  // A coarse iterate x (2 values per vertex) on every fine vertex.
  Eigen::VectorXd prolong(const Eigen::VectorXd& coarse) const;
};

// Collapses interior vertices of (mesh, uv) until at most target_vertices remain or no collapse
// is valid: a collapse must keep the triangulation a manifold (link condition) and every changed
// triangle positively oriented in uv with angles of at least min_angle_degrees. Nothing if more
// than max_kept_fraction of the vertices remain (the collapses were blocked, as on a hand, whose
// parametrization squeezes the fingers into slivers). Deterministic. Throws INVALID_ARGUMENT if
// uv does not have one entry per vertex.
std::optional<CoarseSource> coarsen_source(const TriMesh& mesh, const std::vector<Vec2>& uv, int target_vertices,
                                           double max_kept_fraction = 1.0, double min_angle_degrees = 15);

// Untangles the few triangles a prolonged iterate x folds (det <= 0 with the triangles' winding):
// the interior corners of the folded triangles move to the mean-value combination of their
// neighbours with weights from the `rest` disk (a local Tutte embedding inside the unfolded rest
// of x, which reproduces x wherever x is affine in rest); while folds remain the region grows by
// one ring, up to `rings` times. Returns whether no triangle is folded; x is unchanged if not
// (also when a rest vertex coincides with a neighbour, which leaves it without weights).
// Deterministic. INVALID_ARGUMENT if x does not have two entries per rest vertex.
bool untangle_folds(const std::vector<Tri>& triangles, const std::vector<Vec2>& rest, Eigen::VectorXd& x,
                    int rings = 10);

}  // namespace mcon
