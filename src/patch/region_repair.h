// The opt-in repair of what a patch reads (PatchOptions::repair_region): zero-area triangles of
// the host region around the center are removed without leaving a hole. A triangle with two
// coincident corners has them merged (the triangles that then repeat a vertex go too); a cap,
// whose third corner lies on its longest edge, is dropped and the triangle across that edge is
// split at the corner, so the two sides meet edge to edge again. A pinched vertex is split into
// one vertex per fan, and what then hangs on to the center's part by no edge (a sheet glued at a
// vertex) is left out of the region.
#pragma once

#include <vector>

#include "mesh/mesh_region.h"

namespace mcon {

struct RegionRepairs {
  int zero_area_triangles_removed = 0;  // degenerate triangles taken out (and those a merge emptied)
  int triangles_split = 0;              // neighbours split at a cap's corner
  int vertices_merged = 0;              // coincident corners merged into one vertex
};

// Repairs `region` in place (mesh, vertex and triangle maps, host_to_vertex). Throws
// DEGENERATE_TRIANGLE naming the region's host triangle when the zero-area triangles cannot all be
// removed (a cluster of them that keeps producing new ones).
RegionRepairs remove_zero_area_triangles(MeshRegion& region);

// Splits vertices whose triangles form several fans into one vertex per fan (the fan that keeps
// the old number is the first one met). Returns, per vertex after the split, the vertex it came from.
std::vector<int> split_nonmanifold_vertices(TriMesh& mesh);

// The region's pinched vertices split, and the triangles no edge path joins to the center's
// (center_vertex a host vertex, else center_triangle a host triangle) dropped. Returns the number of
// vertices the split added.
int separate_pinched_fans(MeshRegion& region, int center_vertex, int center_triangle);

}  // namespace mcon
