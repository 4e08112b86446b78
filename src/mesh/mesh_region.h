// A bounded neighbourhood of a point on a (possibly huge) host mesh, so that work around a user's
// click never touches the whole mesh: the host triangles within an edge-graph distance bound,
// restricted to the component that contains the point.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace mcon {

struct MeshRegion {
  TriMesh mesh;                        // may have non-manifold vertices where the bound pinches
  std::vector<int> vertex_to_host;
  std::vector<int> triangle_to_host;
  std::vector<int> host_to_vertex;     // host vertex -> region vertex or -1 (host-sized)
  std::vector<char> vertex_on_cut;     // region vertex has a host triangle outside the region
  std::vector<char> vertex_on_host_boundary;  // region vertex lies on a boundary of the host mesh
  bool is_whole_component = false;     // no cut: the region is the whole connected component
};

// Dijkstra over edges from the point (a vertex, or a point in a triangle: its three corners
// seeded with their Euclidean distance). Edge-graph distance is never shorter than geodesic
// distance, so `bound` >= the geodesic radius wanted keeps every point of that geodesic disk.
MeshRegion mesh_region_around(const TriMesh& host, const std::vector<std::vector<int>>& vertex_triangles,
                              int center_vertex, int center_triangle, const Vec3& center_point, double bound);

}  // namespace mcon
