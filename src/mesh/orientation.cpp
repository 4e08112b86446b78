#include "mesh/orientation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numeric>
#include <string>

#include "base/error.h"
#include "mesh/edge_key.h"

namespace mcon {
namespace {

// Half-edge h = 3 t + i runs from corner i of triangle t to corner i + 1.
int from_vertex(const TriMesh& m, int h) { return m.triangles[h / 3][h % 3]; }
int to_vertex(const TriMesh& m, int h) { return m.triangles[h / 3][(h % 3 + 1) % 3]; }

// Triangle adjacency across manifold edges, with whether the two triangles run the shared edge in
// the same direction (then one of them must be reversed), and the boundary half-edges in edge-key
// order (an order that does not depend on the winding, so volumes of opposite windings are exact
// negatives of each other).
struct EdgeLinks {
  std::vector<std::array<int, 3>> neighbour;  // per half-edge: the other triangle, or -1
  std::vector<std::array<char, 3>> same_direction;
  std::vector<int> boundary;  // boundary half-edges
};

EdgeLinks link_triangles(const TriMesh& m, DefectPolicy defects) {
  const int nt = m.num_triangles();
  std::vector<std::pair<std::uint64_t, int>> half(static_cast<std::size_t>(nt) * 3);
  for (int h = 0; h < 3 * nt; ++h) half[h] = {edge_key(from_vertex(m, h), to_vertex(m, h)), h};
  std::sort(half.begin(), half.end());
  EdgeLinks links;
  links.neighbour.assign(nt, {-1, -1, -1});
  links.same_direction.assign(nt, {0, 0, 0});
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while (j < half.size() && half[j].first == half[i].first) ++j;
    const int h0 = half[i].second;
    if (j - i > 2 && defects == DefectPolicy::defer) {
      i = j;  // a non-manifold edge: left unlinked, the operations that read it report it
      continue;
    }
    if (j - i > 2) {
      const int a = std::min(from_vertex(m, h0), to_vertex(m, h0)), b = std::max(from_vertex(m, h0), to_vertex(m, h0));
      fail(MCON_ERROR_NON_MANIFOLD_EDGE, "edge (" + std::to_string(a) + ", " + std::to_string(b) + ") is used by " +
                                             std::to_string(j - i) + " triangles (" + std::to_string(h0 / 3) + ", " +
                                             std::to_string(half[i + 1].second / 3) + ", " +
                                             std::to_string(half[i + 2].second / 3) +
                                             "...); a surface edge has at most two: remove the extra triangles or "
                                             "split the mesh along that edge");
    }
    if (j - i == 1) {
      links.boundary.push_back(h0);
    } else {
      const int h1 = half[i + 1].second;
      const char same = from_vertex(m, h0) == from_vertex(m, h1);
      links.neighbour[h0 / 3][h0 % 3] = h1 / 3;
      links.neighbour[h1 / 3][h1 % 3] = h0 / 3;
      links.same_direction[h0 / 3][h0 % 3] = links.same_direction[h1 / 3][h1 % 3] = same;
    }
    i = j;
  }
  return links;
}

// Components by BFS from their lowest triangle, each triangle's orientation relative to that seed
// (reversed[t] = 1: reverse it to agree with the seed).
struct Propagation {
  std::vector<int> component_of;
  std::vector<int> seed;  // per component
  std::vector<unsigned char> reversed;
};

Propagation propagate_orientation(const TriMesh& m, const EdgeLinks& links) {
  const int nt = m.num_triangles();
  Propagation p;
  p.component_of.assign(nt, -1);
  p.reversed.assign(nt, 0);
  std::deque<int> queue;
  for (int s = 0; s < nt; ++s) {
    if (p.component_of[s] >= 0) continue;
    const int c = static_cast<int>(p.seed.size());
    p.seed.push_back(s);
    p.component_of[s] = c;
    queue.push_back(s);
    while (!queue.empty()) {
      const int t = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        const int n = links.neighbour[t][i];
        if (n < 0) continue;
        const unsigned char want = p.reversed[t] ^ static_cast<unsigned char>(links.same_direction[t][i]);
        if (p.component_of[n] < 0) {
          p.component_of[n] = c;
          p.reversed[n] = want;
          queue.push_back(n);
        } else if (p.reversed[n] != want) {
          fail(MCON_ERROR_NON_ORIENTABLE,
               "the component of triangle " + std::to_string(s) +
                   " is not orientable (a Moebius strip or Klein bottle): triangles " + std::to_string(t) + " and " +
                   std::to_string(n) +
                   " cannot agree on a side; cut the surface along a seam (duplicate the vertices of an edge path "
                   "across the strip) so that every piece has two sides");
        }
      }
    }
  }
  return p;
}

double triple(const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)); }

// Centroid of each boundary loop's vertices (summed in vertex order), per boundary vertex of a
// component: keys are component * vertex_count + vertex, so that two components meeting at a
// vertex (a pinched vertex, accepted with DefectPolicy::defer) keep their loops apart.
std::vector<Vec3> loop_centroids(const TriMesh& m, const EdgeLinks& links, const Propagation& p,
                                 std::vector<std::int64_t>& vertices) {
  const std::int64_t nv = m.num_vertices();
  const auto key = [&](int h, int v) { return p.component_of[h / 3] * nv + v; };
  vertices.clear();
  for (int h : links.boundary) vertices.insert(vertices.end(), {key(h, from_vertex(m, h)), key(h, to_vertex(m, h))});
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  const auto slot = [&](std::int64_t k) {
    return static_cast<int>(std::lower_bound(vertices.begin(), vertices.end(), k) - vertices.begin());
  };
  std::vector<int> parent(vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (int h : links.boundary) parent[root(slot(key(h, from_vertex(m, h))))] = root(slot(key(h, to_vertex(m, h))));
  std::vector<Vec3> sum(vertices.size(), Vec3::Zero());
  std::vector<int> count(vertices.size(), 0);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    sum[root(static_cast<int>(i))] += m.positions[static_cast<std::size_t>(vertices[i] % nv)];
    ++count[root(static_cast<int>(i))];
  }
  std::vector<Vec3> centroid(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const int r = root(static_cast<int>(i));
    centroid[i] = sum[r] / count[r];
  }
  return centroid;
}

// Per component, in the seed's orientation: 6 x the signed volume (boundary loops closed by fans
// around their centroids) and the area. Terms are measured from the component's bounding-box
// centre, which keeps them small and does not depend on the winding.
void component_volumes(const TriMesh& m, const EdgeLinks& links, const Propagation& p, std::vector<double>& volume,
                       std::vector<double>& area) {
  const std::size_t nc = p.seed.size();
  std::vector<Vec3> lo(nc, Vec3::Constant(INFINITY)), hi(nc, Vec3::Constant(-INFINITY));
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int v : m.triangles[t]) {
      lo[p.component_of[t]] = lo[p.component_of[t]].cwiseMin(m.positions[v]);
      hi[p.component_of[t]] = hi[p.component_of[t]].cwiseMax(m.positions[v]);
    }
  volume.assign(nc, 0.0);
  area.assign(nc, 0.0);
  for (int t = 0; t < m.num_triangles(); ++t) {
    const int c = p.component_of[t];
    const Vec3 o = 0.5 * (lo[c] + hi[c]);
    const Tri& tri = m.triangles[t];
    const Vec3 a = m.positions[tri[0]] - o, b = m.positions[tri[1]] - o, cc = m.positions[tri[2]] - o;
    volume[c] += p.reversed[t] ? triple(a, cc, b) : triple(a, b, cc);
    area[c] += triangle_area(m, t);
  }
  std::vector<std::int64_t> loop_vertices;
  const std::vector<Vec3> centroid = loop_centroids(m, links, p, loop_vertices);
  for (int h : links.boundary) {
    const int t = h / 3, c = p.component_of[t];
    const Vec3 o = 0.5 * (lo[c] + hi[c]);
    int from = from_vertex(m, h), to = to_vertex(m, h);
    if (p.reversed[t]) std::swap(from, to);
    const int u = std::min(from, to), v = std::max(from, to);
    const std::int64_t k = c * static_cast<std::int64_t>(m.num_vertices()) + u;
    const auto slot = std::lower_bound(loop_vertices.begin(), loop_vertices.end(), k) - loop_vertices.begin();
    // The fan triangle (to, from, centroid) closes the edge from -> to with the mesh's winding.
    const double d = triple(m.positions[u] - o, m.positions[v] - o, centroid[slot] - o);
    volume[c] += from > to ? d : -d;
  }
}

}  // namespace

OrientationReport orient_mesh(TriMesh& mesh, OrientationRule rule, DefectPolicy defects) {
  const EdgeLinks links = link_triangles(mesh, defects);
  const Propagation p = propagate_orientation(mesh, links);
  std::vector<double> volume, area;
  component_volumes(mesh, links, p, volume, area);
  const std::size_t nc = p.seed.size();
  std::vector<int> reversed_count(nc, 0), size(nc, 0);
  std::vector<char> open(nc, 0);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    reversed_count[p.component_of[t]] += p.reversed[t];
    ++size[p.component_of[t]];
  }
  for (int h : links.boundary) open[p.component_of[h / 3]] = 1;

  OrientationReport report;
  report.components = static_cast<int>(nc);
  std::vector<unsigned char> turn(nc, 0);  // reverse the seed's orientation
  for (std::size_t c = 0; c < nc; ++c) {
    report.closed_components += !open[c];
    report.inconsistent_components += reversed_count[c] > 0 && reversed_count[c] < size[c];
    const bool majority = 2 * reversed_count[c] > size[c];
    turn[c] = majority;
    const bool decisive = std::abs(volume[c]) > 6e-6 * std::pow(area[c], 1.5);
    if (rule == OrientationRule::outward && decisive) {
      turn[c] = volume[c] < 0;
      report.components_turned_outward += turn[c] != majority;
    }
  }
  report.reoriented.assign(mesh.triangles.size(), 0);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    if (!(p.reversed[t] ^ turn[p.component_of[t]])) continue;
    std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
    report.reoriented[t] = 1;
    ++report.reoriented_triangles;
  }
  return report;
}

OrientationReport orient_and_validate(TriMesh& mesh, OrientationRule rule, DefectPolicy defects) {
  if (defects == DefectPolicy::defer) {
    validate_mesh_indices(mesh);
    return orient_mesh(mesh, rule, defects);
  }
  validate_mesh_elements(mesh);
  OrientationReport report = orient_mesh(mesh, rule);
  validate_mesh(mesh);
  return report;
}

}  // namespace mcon
