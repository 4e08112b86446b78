// Edge-based adjacency of a validated manifold triangle mesh: unique edges, the (at most two)
// triangles of each edge, and the boundary loops. Everything that walks the mesh uses this.
#pragma once

#include <array>
#include <vector>

#include "mesh/mesh.h"

namespace mcon {

struct MeshTopology {
  // Unique undirected edges, each as (a, b) with a < b.
  std::vector<std::array<int, 2>> edges;
  // For each edge, its triangles; [1] is -1 on a boundary edge.
  std::vector<std::array<int, 2>> edge_triangles;
  // For each triangle, the edge opposite each corner: triangle_edges[t][i] joins corners i+1, i+2.
  std::vector<std::array<int, 3>> triangle_edges;
  // For each vertex, its incident triangles (unordered).
  std::vector<std::vector<int>> vertex_triangles;
  // Boundary loops as vertex cycles, each oriented so the mesh lies on its left (as in the
  // triangles' own winding).
  std::vector<std::vector<int>> boundary_loops;

  bool is_boundary_edge(int e) const { return edge_triangles[e][1] < 0; }
  int num_edges() const { return static_cast<int>(edges.size()); }
};

MeshTopology build_topology(const TriMesh& mesh);

// Number of connected components through shared edges, and each triangle's component.
int triangle_components(const TriMesh& mesh, const MeshTopology& topology, std::vector<int>& component_of);

// V - E + F.
int euler_characteristic(const TriMesh& mesh, const MeshTopology& topology);

// Vertex neighbours (one ring) from the edge list, sorted by index.
std::vector<std::vector<int>> vertex_neighbors(const TriMesh& mesh, const MeshTopology& topology);

}  // namespace mcon
