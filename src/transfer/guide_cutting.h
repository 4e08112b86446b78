// Guides cut into the mesh: the triangles a traced polyline crosses are split so that every guide
// becomes a chain of mesh edges, which is what a quad mesher's feature edges (QuadWild `.sharp`)
// need (docs/design.md §14). Crossings close to a vertex snap to it, crossings of one edge that
// lie close together merge into one vertex, and points inside a triangle that add no shape
// (within a tolerance of the chord) are dropped, so no sliver or needle is made; each cut triangle
// is retriangulated with its guide pieces as forced edges (a greedy, shortest-edge-first
// constrained triangulation of the few points it holds). Every vertex of the result keeps its
// point on the input mesh, so any per-vertex field can be carried over.
#pragma once

#include <array>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

struct GuideCutOptions {
  // A crossing closer than snap_fraction * edge length to an end of its edge snaps to that vertex;
  // crossings of one edge closer than that to each other merge; a point inside a triangle closer
  // than snap_fraction * (the triangle's mean edge length) to an edge moves onto it. In [0, 0.45].
  // 0.25 keeps the smallest angle made at about half the input's (docs/design.md §14).
  double snap_fraction = 0.25;
  // Points inside one triangle closer than simplify_fraction * (mean edge length) to the chord of
  // their run are dropped (Douglas-Peucker). In [0, 1].
  double simplify_fraction = 0.05;
  // Passes of chain fairing after the cut (docs/design.md §14, step 6): each chain vertex moves
  // halfway to the midpoint of its chain neighbours, staying on the input surface, within
  // fair_max_shift * (mean edge length) of where the cut put it and without folding or thinning its
  // star. In [0, 100], 0: off; fair_max_shift in [0, 0.5].
  int fair_passes = 3;
  double fair_max_shift = 0.1;
};

struct CutMesh {
  TriMesh mesh;
  // Per vertex of `mesh`: its point on the input mesh (an input vertex has weight 1 at its corner,
  // unless it was moved onto a guide).
  std::vector<SurfacePoint> host;
  // Per triangle of `mesh`: the input triangle it lies in.
  std::vector<int> triangle_origin;
  // Per input polyline: its vertices on `mesh` in order (closed: the first repeated at the end);
  // consecutive ones are joined by an edge of `mesh`. Empty if the guide collapsed to a point.
  std::vector<std::vector<int>> guides;
  // The distinct guide edges (a < b).
  std::vector<std::array<int, 2>> guide_edges;
  int input_triangles_cut = 0;       // input triangles that were retriangulated
  double min_angle_created = 180;    // degrees, smallest angle of a triangle made by the cut
  double min_angle_of_cut_input = 180;  // degrees, smallest angle of the input triangles that were cut
  int snapped_to_vertices = 0;       // crossings moved onto an input vertex
  int merged_crossings = 0;          // crossings merged with another of the same edge
  int dropped_points = 0;            // points inside triangles dropped as adding no shape
  int shortcuts = 0;                 // steps through a snapped vertex replaced by the edge across
  int moved_vertices = 0;            // snapped input vertices moved onto their guide
  int faired_vertices = 0;           // chain vertices moved by fairing
};

// `polylines[i]` are surface points of `mesh`, consecutive points in one common triangle (as
// mcon::PolylineTransfer traces them: split at every edge); closed[i] joins the last to the first
// (closed may be empty: all open). Throws INVALID_ARGUMENT for a bad point (triangle, weights), a
// polyline with fewer than 2 points, a segment whose ends share no triangle (trace it first),
// options out of range, or polylines and closed of different sizes; NUMERICAL if a triangle could
// not be retriangulated (reported with its index). Deterministic.
CutMesh cut_guides_into_mesh(const TriMesh& mesh, const std::vector<std::vector<SurfacePoint>>& polylines,
                             const std::vector<bool>& closed, const GuideCutOptions& options = {});

// Per-vertex values of the input mesh (one row per input vertex) carried to the cut mesh by
// barycentric interpolation at each vertex's host point. Throws INVALID_ARGUMENT on a row-count
// mismatch.
Eigen::MatrixXd carry_vertex_values(const CutMesh& cut, const TriMesh& input, const Eigen::MatrixXd& values);

}  // namespace mcon
