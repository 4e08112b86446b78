// Guides that cross themselves are refused before they are cut into a mesh: a self-crossing
// guide has no consistent left and right side, so the feature edges and the field aligned to them
// would fold (issue 16). Two segments of one polyline that lie in one triangle and cross properly
// there are found in that triangle's barycentric coordinates (an affine frame, so crossing is
// exact there). Segments that only touch, or meet exactly on an edge or vertex, are not refused.
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

struct SelfCrossing {
  int triangle = -1;  // -1: the polyline does not cross itself
  int segment_a = -1, segment_b = -1;
};

// The first proper crossing of two non-neighbouring segments of one polyline (closed: the last
// point joins the first), in the order of the triangles' numbers.
SelfCrossing find_self_crossing(const TriMesh& mesh, const std::vector<SurfacePoint>& line, bool closed);

// Throws INVALID_ARGUMENT naming the guide, its two segments and the triangle where it crosses
// itself. Points must be valid (checked_barycentric); segments whose ends share no triangle are
// skipped here (the cutter refuses them).
void refuse_self_crossing_guides(const TriMesh& mesh, const std::vector<std::vector<SurfacePoint>>& polylines,
                                 const std::vector<bool>& closed);

}  // namespace mcon
