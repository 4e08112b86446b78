#include "mesh/mesh_region.h"

#include <algorithm>
#include <limits>
#include <queue>

namespace mcon {
namespace {

// Dijkstra from the center (a vertex, or the corners of its triangle at their Euclidean
// distance): the vertices within the bound, in settling order.
std::vector<int> vertices_within(const TriMesh& host, const std::vector<std::vector<int>>& vertex_triangles,
                                 int center_vertex, int center_triangle, const Vec3& center_point, double bound) {
  const int n = host.num_vertices();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(n, inf);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  std::vector<int> touched;
  auto relax = [&](int v, double d) {
    if (d < dist[v]) {
      if (dist[v] == inf) touched.push_back(v);
      dist[v] = d;
      queue.emplace(d, v);
    }
  };
  if (center_vertex >= 0) {
    relax(center_vertex, 0.0);
  } else {
    for (int v : host.triangles[center_triangle]) relax(v, (host.positions[v] - center_point).norm());
  }
  // Settled vertices within the bound; neighbours come from the triangles so no edge list of
  // the whole host is needed.
  std::vector<char> settled(n, 0);
  std::vector<int> inside;
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (settled[v] || d > dist[v]) continue;
    settled[v] = 1;
    if (d > bound) break;
    inside.push_back(v);
    for (int t : vertex_triangles[v])
      for (int w : host.triangles[t])
        if (!settled[w]) relax(w, d + (host.positions[w] - host.positions[v]).norm());
  }
  return inside;
}

// Region triangles: every host triangle with a vertex within the bound (this keeps the region
// closed around the bound, and connected: Dijkstra only walks from the center). Marks the taken
// host triangles in tri_taken.
void collect_triangles(const TriMesh& host, const std::vector<std::vector<int>>& vertex_triangles,
                       const std::vector<int>& inside, MeshRegion& region, std::vector<char>& tri_taken) {
  region.host_to_vertex.assign(host.num_vertices(), -1);
  tri_taken.assign(host.num_triangles(), 0);
  for (int v : inside)
    for (int t : vertex_triangles[v]) {
      if (tri_taken[t]) continue;
      tri_taken[t] = 1;
      Tri tri;
      for (int k = 0; k < 3; ++k) {
        const int hv = host.triangles[t][k];
        if (region.host_to_vertex[hv] < 0) {
          region.host_to_vertex[hv] = static_cast<int>(region.vertex_to_host.size());
          region.vertex_to_host.push_back(hv);
          region.mesh.positions.push_back(host.positions[hv]);
        }
        tri[k] = region.host_to_vertex[hv];
      }
      region.mesh.triangles.push_back(tri);
      region.triangle_to_host.push_back(t);
    }
}

// Which region vertices have a host triangle outside the region (on the cut) or lie on the
// host's own boundary; and whether there is no cut at all.
void mark_cut_and_boundary(const TriMesh& host, const std::vector<std::vector<int>>& vertex_triangles,
                           const std::vector<char>& tri_taken, MeshRegion& region) {
  region.vertex_on_cut.assign(region.vertex_to_host.size(), 0);
  region.vertex_on_host_boundary.assign(region.vertex_to_host.size(), 0);
  bool any_cut = false;
  std::vector<int> ring;
  for (std::size_t rv = 0; rv < region.vertex_to_host.size(); ++rv) {
    const int hv = region.vertex_to_host[rv];
    ring.clear();
    for (int t : vertex_triangles[hv]) {
      if (!tri_taken[t] && !region.vertex_on_cut[rv]) {
        region.vertex_on_cut[rv] = 1;
        any_cut = true;
      }
      for (int w : host.triangles[t])
        if (w != hv) ring.push_back(w);
    }
    // On a manifold mesh an interior vertex has as many distinct neighbours as triangles; a
    // boundary vertex has one more.
    std::sort(ring.begin(), ring.end());
    const auto distinct = std::unique(ring.begin(), ring.end()) - ring.begin();
    region.vertex_on_host_boundary[rv] = distinct > static_cast<long>(vertex_triangles[hv].size());
  }
  region.is_whole_component = !any_cut;
}

}  // namespace

MeshRegion mesh_region_around(const TriMesh& host, const std::vector<std::vector<int>>& vertex_triangles,
                              int center_vertex, int center_triangle, const Vec3& center_point, double bound) {
  const std::vector<int> inside =
      vertices_within(host, vertex_triangles, center_vertex, center_triangle, center_point, bound);
  MeshRegion region;
  std::vector<char> tri_taken;
  collect_triangles(host, vertex_triangles, inside, region, tri_taken);
  mark_cut_and_boundary(host, vertex_triangles, tri_taken, region);
  return region;
}

}  // namespace mcon
