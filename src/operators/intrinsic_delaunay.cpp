#include "operators/intrinsic_delaunay.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mcon {
namespace {

// Half the cotangent of the angle opposite side a in a triangle with sides a, b, c: the cotan
// weight that triangle gives edge a.
double half_cot_opposite(double a, double b, double c, double area) {
  return area > 0 ? (b * b + c * c - a * a) / (8.0 * area) : 0.0;
}

// Edges whose opposite half-cotangents sum to less than this are flipped. A small negative
// tolerance stops co-circular quads (e.g. a regular grid) from flipping back and forth.
constexpr double kDelaunayTolerance = -1e-10;

}  // namespace

double triangle_area_from_lengths(double a, double b, double c) {
  // Kahan: sort a >= b >= c, then the parenthesization below is exact enough for slivers.
  if (a < b) std::swap(a, b);
  if (a < c) std::swap(a, c);
  if (b < c) std::swap(b, c);
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return p > 0 ? 0.25 * std::sqrt(p) : 0.0;
}

IntrinsicTriangulation intrinsic_triangulation(const TriMesh& mesh, const MeshTopology& topology) {
  IntrinsicTriangulation it;
  const int nt = mesh.num_triangles();
  it.num_vertices = mesh.num_vertices();
  it.triangles = mesh.triangles;
  it.lengths.resize(nt);
  it.across.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const Tri& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) {
      it.lengths[t][c] = (mesh.positions[tri[(c + 1) % 3]] - mesh.positions[tri[c]]).norm();
      // Slot c joins corners c and c + 1, i.e. it is the edge opposite corner c + 2.
      const int e = topology.triangle_edges[t][(c + 2) % 3];
      const auto& et = topology.edge_triangles[e];
      const int other = et[0] == t ? et[1] : et[0];
      it.across[t][c] = -1;
      if (other < 0) continue;
      for (int c2 = 0; c2 < 3; ++c2)
        if (topology.triangle_edges[other][(c2 + 2) % 3] == e) it.across[t][c] = 3 * other + c2;
    }
  }
  return it;
}

void make_delaunay(IntrinsicTriangulation& it) {
  const int nt = static_cast<int>(it.triangles.size());
  auto slot = [](int t, int c) { return 3 * t + c; };
  auto needs_flip = [&](int h) {
    const int f0 = h / 3, c0 = h % 3, g = it.across[f0][c0];
    if (g < 0 || g / 3 == f0) return false;
    const int f1 = g / 3, c1 = g % 3;
    const auto& l0 = it.lengths[f0];
    const auto& l1 = it.lengths[f1];
    const double a = l0[c0];
    const double area0 = triangle_area_from_lengths(l0[0], l0[1], l0[2]);
    const double area1 = triangle_area_from_lengths(l1[0], l1[1], l1[2]);
    if (!(area0 > 0) || !(area1 > 0)) return false;
    return half_cot_opposite(a, l0[(c0 + 1) % 3], l0[(c0 + 2) % 3], area0) +
               half_cot_opposite(a, l1[(c1 + 1) % 3], l1[(c1 + 2) % 3], area1) <
           kDelaunayTolerance;
  };

  std::vector<int> stack;
  for (int t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c)
      if (it.across[t][c] > slot(t, c)) stack.push_back(slot(t, c));  // each interior edge once
  // Lawson flipping terminates on an intrinsic triangulation (Indermitte et al. 2001); the cap
  // only guards against round-off cycling and leaves a valid (nearly Delaunay) triangulation.
  const long max_flips = 100L * nt + 1000;
  while (!stack.empty() && it.flips < max_flips) {
    const int h = stack.back();
    stack.pop_back();
    if (!needs_flip(h)) continue;
    const int f0 = h / 3, c0 = h % 3, f1 = it.across[f0][c0] / 3, c1 = it.across[f0][c0] % 3;
    // f0 = (i, j, k), f1 = (j, i, l); the quad i, l, j, k is convex since ij is not Delaunay.
    const int i = it.triangles[f0][c0], j = it.triangles[f0][(c0 + 1) % 3], k = it.triangles[f0][(c0 + 2) % 3];
    const int l = it.triangles[f1][(c1 + 2) % 3];
    const double a = it.lengths[f0][c0];
    const double jk = it.lengths[f0][(c0 + 1) % 3], ki = it.lengths[f0][(c0 + 2) % 3];
    const double il = it.lengths[f1][(c1 + 1) % 3], lj = it.lengths[f1][(c1 + 2) % 3];
    const int across_jk = it.across[f0][(c0 + 1) % 3], across_ki = it.across[f0][(c0 + 2) % 3];
    const int across_il = it.across[f1][(c1 + 1) % 3], across_lj = it.across[f1][(c1 + 2) % 3];
    // Outer edges glued to f0 or f1 themselves (a vertex of degree 2): leave that edge alone.
    bool self_glued = false;
    for (int g : {across_jk, across_ki, across_il, across_lj}) self_glued |= g >= 0 && (g / 3 == f0 || g / 3 == f1);
    if (self_glued) continue;
    // Lay the quad out in the plane: i = (0, 0), j = (a, 0), k above, l below.
    const double area0 = triangle_area_from_lengths(a, jk, ki), area1 = triangle_area_from_lengths(a, il, lj);
    const double xk = (a * a + ki * ki - jk * jk) / (2 * a), yk = 2 * area0 / a;
    const double xl = (a * a + il * il - lj * lj) / (2 * a), yl = -2 * area1 / a;
    const double kl = std::hypot(xk - xl, yk - yl);
    // New triangles f0 = (l, j, k) and f1 = (k, i, l), slot 2 of each being the new edge.
    it.triangles[f0] = {l, j, k};
    it.lengths[f0] = {lj, jk, kl};
    it.triangles[f1] = {k, i, l};
    it.lengths[f1] = {ki, il, kl};
    auto glue = [&](int s, int g) {
      it.across[s / 3][s % 3] = g;
      if (g >= 0) it.across[g / 3][g % 3] = s;
    };
    glue(slot(f0, 0), across_lj);
    glue(slot(f0, 1), across_jk);
    glue(slot(f1, 0), across_ki);
    glue(slot(f1, 1), across_il);
    glue(slot(f0, 2), slot(f1, 2));
    ++it.flips;
    for (int s : {slot(f0, 0), slot(f0, 1), slot(f1, 0), slot(f1, 1)}) stack.push_back(s);
  }
}

SparseMatrix cotan_laplacian(const IntrinsicTriangulation& it) {
  // Assembled straight into compressed columns (a triplet list costs several times more here):
  // one weight per intrinsic edge, the two half-cotangents of its sides.
  const int n = it.num_vertices;
  const int nt = static_cast<int>(it.triangles.size());
  std::vector<std::array<double, 3>> half_cot(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& l = it.lengths[t];
    const double area = triangle_area_from_lengths(l[0], l[1], l[2]);
    for (int c = 0; c < 3; ++c) half_cot[t][c] = half_cot_opposite(l[c], l[(c + 1) % 3], l[(c + 2) % 3], area);
  }
  struct Edge {
    int a, b;
    double w;
  };
  std::vector<Edge> edges;
  edges.reserve(static_cast<std::size_t>(nt) * 3 / 2 + 3);
  std::vector<int> column_size(n, 1);  // the diagonal
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n);
  for (int t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c) {
      const int g = it.across[t][c];
      if (g >= 0 && g < 3 * t + c) continue;  // each edge once
      const int a = it.triangles[t][c], b = it.triangles[t][(c + 1) % 3];
      if (a == b) continue;  // a loop edge has no effect on the Dirichlet energy
      const double w = half_cot[t][c] + (g >= 0 ? half_cot[g / 3][g % 3] : 0.0);
      edges.push_back({a, b, w});
      ++column_size[a];
      ++column_size[b];
      diagonal[a] += w;
      diagonal[b] += w;
    }
  // Columns: rows sorted, parallel edges (possible between intrinsic vertices) merged.
  std::vector<int> start(n + 1, 0);
  for (int v = 0; v < n; ++v) start[v + 1] = start[v] + column_size[v];
  std::vector<std::pair<int, double>> entries(start[n]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int v = 0; v < n; ++v) entries[fill[v]++] = {v, diagonal[v]};
  for (const Edge& e : edges) {
    entries[fill[e.a]++] = {e.b, -e.w};
    entries[fill[e.b]++] = {e.a, -e.w};
  }
  SparseMatrix L(n, n);
  L.reserve(Eigen::VectorXi::Map(column_size.data(), n));
  for (int v = 0; v < n; ++v) {
    auto first = entries.begin() + start[v], last = entries.begin() + start[v + 1];
    std::sort(first, last, [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto e = first; e != last; ++e) {
      if (e != first && e->first == (e - 1)->first)
        L.coeffRef(e->first, v) += e->second;
      else
        L.insert(e->first, v) = e->second;
    }
  }
  L.makeCompressed();
  return L;
}

Eigen::VectorXd vertex_areas(const IntrinsicTriangulation& it) {
  Eigen::VectorXd areas = Eigen::VectorXd::Zero(it.num_vertices);
  for (std::size_t t = 0; t < it.triangles.size(); ++t) {
    const auto& l = it.lengths[t];
    const double a = triangle_area_from_lengths(l[0], l[1], l[2]) / 3.0;
    for (int v : it.triangles[t]) areas[v] += a;
  }
  return areas;
}

}  // namespace mcon
