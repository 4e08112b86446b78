#include "mesh/mesh_topology.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "base/error.h"

namespace mcon {

MeshTopology build_topology(const TriMesh& mesh) {
  MeshTopology topo;
  const int nt = mesh.num_triangles();
  topo.triangle_edges.resize(nt);
  topo.vertex_triangles.resize(mesh.num_vertices());
  std::unordered_map<std::uint64_t, int> edge_of;
  edge_of.reserve(static_cast<std::size_t>(nt) * 2);
  for (int t = 0; t < nt; ++t) {
    const Tri& tri = mesh.triangles[t];
    for (int i = 0; i < 3; ++i) {
      topo.vertex_triangles[tri[i]].push_back(t);
      int a = tri[(i + 1) % 3], b = tri[(i + 2) % 3];
      if (a > b) std::swap(a, b);
      const std::uint64_t key = (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
      auto [it, inserted] = edge_of.emplace(key, static_cast<int>(topo.edges.size()));
      if (inserted) {
        topo.edges.push_back({a, b});
        topo.edge_triangles.push_back({t, -1});
      } else {
        auto& et = topo.edge_triangles[it->second];
        require(et[1] < 0, MCON_ERROR_NON_MANIFOLD_EDGE,
                "edge (" + std::to_string(a) + ", " + std::to_string(b) + ") has more than two triangles");
        et[1] = t;
      }
      topo.triangle_edges[t][i] = it->second;
    }
  }

  // Boundary loops: follow directed boundary half-edges (a -> b in triangle winding). On a
  // manifold mesh each boundary vertex has exactly one outgoing boundary half-edge.
  std::unordered_map<int, int> next_on_boundary;
  for (int e = 0; e < topo.num_edges(); ++e) {
    if (!topo.is_boundary_edge(e)) continue;
    const Tri& tri = mesh.triangles[topo.edge_triangles[e][0]];
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      if (std::min(a, b) == topo.edges[e][0] && std::max(a, b) == topo.edges[e][1]) {
        next_on_boundary[a] = b;
        break;
      }
    }
  }
  std::vector<int> starts;
  starts.reserve(next_on_boundary.size());
  for (const auto& kv : next_on_boundary) starts.push_back(kv.first);
  std::sort(starts.begin(), starts.end());  // deterministic loop order
  std::unordered_map<int, bool> visited;
  for (int s : starts) {
    if (visited[s]) continue;
    std::vector<int> loop;
    int v = s;
    while (!visited[v]) {
      visited[v] = true;
      loop.push_back(v);
      auto it = next_on_boundary.find(v);
      if (it == next_on_boundary.end()) break;
      v = it->second;
    }
    topo.boundary_loops.push_back(std::move(loop));
  }
  return topo;
}

int triangle_components(const TriMesh& mesh, const MeshTopology& topo, std::vector<int>& component_of) {
  const int nt = mesh.num_triangles();
  component_of.assign(nt, -1);
  int count = 0;
  std::vector<int> stack;
  for (int seed = 0; seed < nt; ++seed) {
    if (component_of[seed] >= 0) continue;
    component_of[seed] = count;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int e : topo.triangle_edges[t])
        for (int u : topo.edge_triangles[e])
          if (u >= 0 && component_of[u] < 0) {
            component_of[u] = count;
            stack.push_back(u);
          }
    }
    ++count;
  }
  return count;
}

int euler_characteristic(const TriMesh& mesh, const MeshTopology& topo) {
  return mesh.num_vertices() - topo.num_edges() + mesh.num_triangles();
}

std::vector<std::vector<int>> vertex_neighbors(const TriMesh& mesh, const MeshTopology& topo) {
  std::vector<std::vector<int>> nbrs(mesh.num_vertices());
  for (const auto& e : topo.edges) {
    nbrs[e[0]].push_back(e[1]);
    nbrs[e[1]].push_back(e[0]);
  }
  for (auto& n : nbrs) std::sort(n.begin(), n.end());
  return nbrs;
}

}  // namespace mcon
