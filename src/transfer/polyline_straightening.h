// A traced polyline made as short as it can be inside the triangles it already crosses: every
// point where it crosses an edge slides along that edge until the path through it is straight
// when the two triangles are unfolded into one plane (a discrete geodesic through a fixed triangle
// strip). The other points (the mapped source points, the ends of a piece) stay. Why: the trace
// is straight in the target's disk parametrization, whose Jacobian jumps from triangle to
// triangle; where that parametrization is squeezed (fingers) the straight line in it zig-zags on
// the surface, turning 60-120 degrees at single edge crossings (docs/design.md §16).
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

struct StripPoint {
  SurfacePoint point;  // the triangle holds the segment to the next point
  bool fixed = true;   // false: a crossing of the edge shared with the previous point's triangle
};

// Straightens `points` in place (closed: the last point joins the first). A free point must have
// exactly one zero weight, on the corner of its triangle opposite the edge it shares with the
// previous point's triangle; a point that does not is treated as fixed. Consecutive points that
// end at the same place are merged (the later one's triangle kept), so every segment still lies in
// the triangle of its first point. Deterministic.
void straighten_polyline(const TriMesh& mesh, std::vector<StripPoint>& points, bool closed);

}  // namespace mcon
