#include "patch/region_repair.h"

#include <algorithm>
#include <numeric>
#include <string>

#include <cstdint>
#include <unordered_map>

#include "base/error.h"
#include "mesh/edge_key.h"
#include "mesh/mesh.h"

namespace mcon {
namespace {

int first_zero_area(const TriMesh& m) {
  for (int t = 0; t < m.num_triangles(); ++t)
    if (has_zero_area(m, t)) return t;
  return -1;
}

void erase_triangle(MeshRegion& region, int t) {
  region.mesh.triangles.erase(region.mesh.triangles.begin() + t);
  region.triangle_to_host.erase(region.triangle_to_host.begin() + t);
}

// Merges q into p everywhere; the triangles that then use p twice are removed. Returns how many.
int merge_vertices(MeshRegion& region, int p, int q) {
  TriMesh& m = region.mesh;
  int removed = 0;
  for (int t = m.num_triangles() - 1; t >= 0; --t) {
    Tri& tri = m.triangles[t];
    for (int& v : tri)
      if (v == q) v = p;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      erase_triangle(region, t);
      ++removed;
    }
  }
  region.vertex_on_cut[p] = region.vertex_on_cut[p] || region.vertex_on_cut[q];
  region.vertex_on_host_boundary[p] = region.vertex_on_host_boundary[p] || region.vertex_on_host_boundary[q];
  return removed;
}

// Drops cap t (corner c on edge a-b) and splits the triangle across a-b, (b, a, x), into
// (b, c, x) and (c, a, x): both lie in the same host triangle. Returns whether one was split.
bool drop_cap(MeshRegion& region, int t, int a, int b, int c) {
  TriMesh& m = region.mesh;
  int across = -1, x = -1;
  for (int u = 0; u < m.num_triangles() && across < 0; ++u)
    for (int k = 0; k < 3; ++k)
      if (u != t && m.triangles[u][k] == b && m.triangles[u][(k + 1) % 3] == a) {
        across = u;
        x = m.triangles[u][(k + 2) % 3];
      }
  const bool split = across >= 0 && x != c;
  if (split) {
    const int host = region.triangle_to_host[across];
    m.triangles[across] = {b, c, x};
    m.triangles.push_back({c, a, x});
    region.triangle_to_host.push_back(host);
  }
  if (across >= 0 && !split) erase_triangle(region, across);  // (a, b, c) and (b, a, c): a closed pillow
  erase_triangle(region, across >= 0 && !split && across < t ? t - 1 : t);
  return split;
}

// Renumbers the region's vertices after the repair: `into` maps each old vertex to its survivor;
// a vertex no triangle uses any more (its only triangles were removed) is dropped, with its host
// vertex no longer in the region.
void compact_vertices(MeshRegion& region, std::vector<int> into) {
  const int n = static_cast<int>(into.size());
  for (int v = 0; v < n; ++v)
    while (into[v] != into[into[v]]) into[v] = into[into[v]];
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  for (const Tri& tri : region.mesh.triangles)
    for (int v : tri) used[v] = 1;
  std::vector<int> index(static_cast<std::size_t>(n), -1);
  MeshRegion out;
  for (int v = 0; v < n; ++v)
    if (into[v] == v && used[v]) {
      index[v] = static_cast<int>(out.vertex_to_host.size());
      out.mesh.positions.push_back(region.mesh.positions[v]);
      out.vertex_to_host.push_back(region.vertex_to_host[v]);
      out.vertex_on_cut.push_back(region.vertex_on_cut[v]);
      out.vertex_on_host_boundary.push_back(region.vertex_on_host_boundary[v]);
    }
  for (Tri& tri : region.mesh.triangles)
    for (int& v : tri) v = index[into[v]];
  // A host vertex keeps the region vertex it had if that survives, else another copy of it (a
  // split fan), else it leaves the region.
  std::vector<char> primary(static_cast<std::size_t>(n), 0);
  for (int v = 0; v < n; ++v) primary[v] = region.host_to_vertex[region.vertex_to_host[v]] == v;
  for (int v = 0; v < n; ++v)
    if (primary[v]) region.host_to_vertex[region.vertex_to_host[v]] = index[into[v]];
  for (int v = 0; v < n; ++v)
    if (!primary[v] && index[into[v]] >= 0 && region.host_to_vertex[region.vertex_to_host[v]] < 0)
      region.host_to_vertex[region.vertex_to_host[v]] = index[into[v]];
  region.mesh.positions = std::move(out.mesh.positions);
  region.vertex_to_host = std::move(out.vertex_to_host);
  region.vertex_on_cut = std::move(out.vertex_on_cut);
  region.vertex_on_host_boundary = std::move(out.vertex_on_host_boundary);
}

// The triangles reached from `seeds` through shared edges.
std::vector<char> edge_connected(const TriMesh& m, const std::vector<int>& seeds) {
  std::unordered_map<std::uint64_t, std::vector<int>> edge_triangles;
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) edge_triangles[edge_key(m.triangles[t][k], m.triangles[t][(k + 1) % 3])].push_back(t);
  std::vector<char> reached(static_cast<std::size_t>(m.num_triangles()), 0);
  std::vector<int> stack;
  for (int t : seeds)
    if (!reached[t]) reached[t] = 1, stack.push_back(t);
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k)
      for (int u : edge_triangles[edge_key(m.triangles[t][k], m.triangles[t][(k + 1) % 3])])
        if (!reached[u]) reached[u] = 1, stack.push_back(u);
  }
  return reached;
}

}  // namespace

std::vector<int> split_nonmanifold_vertices(TriMesh& mesh) {
  const int nv = mesh.num_vertices();
  std::vector<std::vector<int>> corners(nv);  // (triangle * 3 + corner) per vertex
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) corners[mesh.triangles[t][k]].push_back(3 * t + k);
  std::vector<int> origin(nv);
  std::iota(origin.begin(), origin.end(), 0);
  std::vector<int> parent;
  for (int v = 0; v < nv; ++v) {
    const auto& cs = corners[v];
    parent.resize(cs.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::unordered_map<int, int> first_with;  // link vertex -> corner slot
    for (int k = 0; k < static_cast<int>(cs.size()); ++k)
      for (int w : mesh.triangles[cs[k] / 3]) {
        if (w == v) continue;
        auto [it, inserted] = first_with.emplace(w, k);
        if (!inserted) parent[find(k)] = find(it->second);
      }
    std::unordered_map<int, int> fan_vertex;
    for (int k = 0; k < static_cast<int>(cs.size()); ++k) {
      const int root = find(k);
      if (fan_vertex.empty()) fan_vertex[root] = v;
      auto it = fan_vertex.find(root);
      if (it == fan_vertex.end()) {
        it = fan_vertex.emplace(root, mesh.num_vertices()).first;
        mesh.positions.push_back(mesh.positions[v]);
        origin.push_back(v);
      }
      mesh.triangles[cs[k] / 3][cs[k] % 3] = it->second;
    }
  }
  return origin;
}

int separate_pinched_fans(MeshRegion& region, int center_vertex, int center_triangle) {
  TriMesh& m = region.mesh;
  const std::size_t before = region.vertex_to_host.size();
  const std::vector<int> origin = split_nonmanifold_vertices(m);
  for (std::size_t v = before; v < origin.size(); ++v) {
    region.vertex_to_host.push_back(region.vertex_to_host[origin[v]]);
    region.vertex_on_cut.push_back(region.vertex_on_cut[origin[v]]);
    region.vertex_on_host_boundary.push_back(region.vertex_on_host_boundary[origin[v]]);
  }
  std::vector<int> seeds;
  const int v0 = center_vertex >= 0 ? region.host_to_vertex[center_vertex] : -1;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Tri& tri = m.triangles[t];
    if (center_vertex >= 0 ? (tri[0] == v0 || tri[1] == v0 || tri[2] == v0) : region.triangle_to_host[t] == center_triangle)
      seeds.push_back(t);
  }
  const std::vector<char> keep = edge_connected(m, seeds);
  for (int t = m.num_triangles() - 1; t >= 0; --t)
    if (!keep[t]) erase_triangle(region, t);
  std::vector<int> into(region.vertex_to_host.size());
  std::iota(into.begin(), into.end(), 0);
  compact_vertices(region, std::move(into));
  return static_cast<int>(origin.size() - before);
}

RegionRepairs remove_zero_area_triangles(MeshRegion& region) {
  RegionRepairs r;
  TriMesh& m = region.mesh;
  std::vector<int> into(m.positions.size());
  std::iota(into.begin(), into.end(), 0);
  const int limit = 4 * m.num_triangles() + 16;  // every step removes a triangle or splits one
  for (int step = 0;; ++step) {
    const int t = first_zero_area(m);
    if (t < 0) break;
    require(step < limit, MCON_ERROR_DEGENERATE_TRIANGLE,
            "the zero-area triangles around host triangle " + std::to_string(region.triangle_to_host[t]) +
                " could not be repaired: remove them in the modelling tool");
    const Tri tri = m.triangles[t];
    double length[3];
    for (int k = 0; k < 3; ++k) length[k] = (m.positions[tri[(k + 1) % 3]] - m.positions[tri[k]]).norm();
    const int longest = static_cast<int>(std::max_element(length, length + 3) - length);
    const int shortest = static_cast<int>(std::min_element(length, length + 3) - length);
    if (length[shortest] <= 1e-9 * length[longest] || length[longest] == 0) {
      // Coincident corners: one vertex (the lower number survives).
      const int p = std::min(tri[shortest], tri[(shortest + 1) % 3]), q = std::max(tri[shortest], tri[(shortest + 1) % 3]);
      r.zero_area_triangles_removed += merge_vertices(region, p, q);
      into[q] = p;
      ++r.vertices_merged;
      continue;
    }
    r.triangles_split += drop_cap(region, t, tri[longest], tri[(longest + 1) % 3], tri[(longest + 2) % 3]) ? 1 : 0;
    ++r.zero_area_triangles_removed;
  }
  if (r.zero_area_triangles_removed > 0) compact_vertices(region, std::move(into));
  return r;
}

}  // namespace mcon
