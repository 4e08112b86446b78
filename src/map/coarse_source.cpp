// Coarsening a source disk by halfedge collapses in uv (coarse_source.h).
#include "map/coarse_source.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <queue>
#include <tuple>

#include "base/error.h"
#include "map/injective_step.h"
#include "mesh/mesh_topology.h"
#include "mesh/point_location_2d.h"
#include "patch/disk_parametrization.h"

namespace mcon {
namespace {

// Whether (a, b, c) is counter-clockwise with every angle >= the one whose sine is min_sin
// (the sine of each angle from the doubled area and its two sides; angles above 90 degrees are
// bounded through the other two).
bool well_shaped(const Vec2& a, const Vec2& b, const Vec2& c, double min_sin) {
  const double area2 = cross2(b - a, c - a);
  if (!(area2 > 0)) return false;
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const double s[3] = {area2 / (ab * ca), area2 / (ab * bc), area2 / (bc * ca)};  // sines at a, b, c
  // The largest angle may be obtuse (its sine small yet the angle large): the other two bound it.
  const double lengths[3] = {bc, ca, ab};  // opposite a, b, c
  const int largest = static_cast<int>(std::max_element(lengths, lengths + 3) - lengths);
  for (int k = 0; k < 3; ++k)
    if (k != largest && s[k] < min_sin) return false;
  return true;
}

class Collapser {
 public:
  Collapser(const TriMesh& mesh, const std::vector<Vec2>& uv, double min_angle_degrees)
      : uv_(uv), tris_(mesh.triangles), alive_tri_(mesh.triangles.size(), true),
        alive_(static_cast<std::size_t>(mesh.num_vertices()), true),
        interior_(static_cast<std::size_t>(mesh.num_vertices()), true),
        star_(static_cast<std::size_t>(mesh.num_vertices())),
        into_(static_cast<std::size_t>(mesh.num_vertices()), -1),
        min_sin_(std::sin(min_angle_degrees * 3.14159265358979323846 / 180)) {
    const MeshTopology topology = build_topology(mesh);
    for (int e = 0; e < topology.num_edges(); ++e)
      if (topology.is_boundary_edge(e)) interior_[topology.edges[e][0]] = interior_[topology.edges[e][1]] = false;
    for (int t = 0; t < mesh.num_triangles(); ++t)
      for (int v : tris_[t]) star_[v].push_back(t);
    for (int v = 0; v < mesh.num_vertices(); ++v)
      for (int u : neighbours(v)) push(v, u);
  }

  // Collapses shortest edges first until `target` vertices remain or no collapse is valid.
  void run(int target) {
    int count = static_cast<int>(alive_.size());
    while (count > target && !queue_.empty()) {
      const auto [length2, v, u] = queue_.top();
      queue_.pop();
      (void)length2;
      if (collapse(v, u)) --count;
    }
  }

  const std::vector<bool>& alive() const { return alive_; }
  // The surviving vertex a removed one was collapsed onto, through later collapses.
  int survivor(int v) const {
    while (!alive_[v]) v = into_[v];
    return v;
  }
  std::vector<Tri> triangles() const {
    std::vector<Tri> out;
    for (std::size_t t = 0; t < tris_.size(); ++t)
      if (alive_tri_[t]) out.push_back(tris_[t]);
    return out;
  }

 private:
  std::vector<int> neighbours(int v) const {
    std::vector<int> out;
    for (int t : star_[v])
      for (int w : tris_[t])
        if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  void push(int v, int u) {
    if (interior_[v]) queue_.push({(uv_[v] - uv_[u]).squaredNorm(), v, u});
  }

  // Moves v onto u: the two triangles on edge (v, u) vanish, v's others take u instead.
  bool collapse(int v, int u) {
    if (!alive_[v] || !alive_[u]) return false;
    std::vector<int> shared, others;
    for (int t : star_[v]) (std::find(tris_[t].begin(), tris_[t].end(), u) != tris_[t].end() ? shared : others).push_back(t);
    if (shared.size() != 2) return false;  // no longer an edge, or not an interior one
    // Link condition: the only common neighbours of v and u are the two opposite corners.
    const std::vector<int> nv = neighbours(v), nu = neighbours(u);
    std::vector<int> common;
    std::set_intersection(nv.begin(), nv.end(), nu.begin(), nu.end(), std::back_inserter(common));
    if (common.size() != 2) return false;
    for (int t : others) {
      Tri tri = tris_[t];
      for (int& w : tri)
        if (w == v) w = u;
      if (!well_shaped(uv_[tri[0]], uv_[tri[1]], uv_[tri[2]], min_sin_)) return false;
    }
    for (int t : shared) {
      alive_tri_[t] = false;
      for (int w : tris_[t]) star_[w].erase(std::remove(star_[w].begin(), star_[w].end(), t), star_[w].end());
    }
    for (int t : others) {
      for (int& w : tris_[t])
        if (w == v) w = u;
      star_[u].push_back(t);
    }
    star_[v].clear();
    alive_[v] = false;
    into_[v] = u;
    // Only the edges the collapse created are new candidates (the others are queued already).
    for (int w : nv)
      if (w != u && !std::binary_search(nu.begin(), nu.end(), w)) {
        push(w, u);
        push(u, w);
      }
    return true;
  }

  using Item = std::tuple<double, int, int>;  // squared uv length, vertex removed, vertex kept
  const std::vector<Vec2>& uv_;
  std::vector<Tri> tris_;
  std::vector<bool> alive_tri_, alive_, interior_;
  std::vector<std::vector<int>> star_;
  std::vector<int> into_;  // per removed vertex, the vertex it was collapsed onto
  double min_sin_;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue_;
};

// Prolongation: each fine vertex in the coarse triangle around its uv (the rim is kept, so the
// coarse triangles cover every fine uv). A walk from the star of the vertex it was collapsed onto,
// across the edge of the most negative barycentric coordinate, finds it in a few steps; the
// quadtree locator, whose build is slow on slivers, only if a walk fails.
void locate_fine_vertices(const std::vector<Vec2>& uv, const std::vector<int>& to_coarse, const Collapser& collapser,
                          CoarseSource& c) {
  const std::vector<Tri>& tris = c.mesh.triangles;
  const MeshTopology topology = build_topology(c.mesh);
  // The triangle across the edge opposite corner k of t (-1 on the rim).
  auto across = [&](int t, int k) {
    const std::array<int, 2>& pair = topology.edge_triangles[topology.triangle_edges[t][k]];
    return pair[0] == t ? pair[1] : pair[0];
  };
  std::optional<TriangleLocator2D> locator;
  c.prolong_corners.resize(uv.size());
  c.prolong_weights.resize(uv.size());
  for (std::size_t v = 0; v < uv.size(); ++v) {
    if (to_coarse[v] >= 0) {
      c.prolong_corners[v] = {to_coarse[v], to_coarse[v], to_coarse[v]};
      c.prolong_weights[v] = Vec3(1, 0, 0);
      continue;
    }
    int t = topology.vertex_triangles[to_coarse[collapser.survivor(static_cast<int>(v))]].back();
    Vec3 b = Vec3::Zero();
    bool found = false;
    for (int step = 0; step < static_cast<int>(tris.size()) && t >= 0; ++step) {
      b = barycentric_2d(uv[v], c.uv[tris[t][0]], c.uv[tris[t][1]], c.uv[tris[t][2]]);
      int worst = 0;
      for (int k = 1; k < 3; ++k)
        if (b[k] < b[worst]) worst = k;
      if (b[worst] >= -1e-12 || across(t, worst) < 0) {  // inside, or just outside the rim (rounding)
        found = b[worst] >= -1e-9;
        break;
      }
      t = across(t, worst);
    }
    if (!found) {
      if (!locator) locator.emplace(c.uv, tris);
      PointLocation at = locator->locate(uv[v]);
      if (at.triangle < 0) at = locator->locate_nearest(uv[v], std::numeric_limits<double>::infinity());
      require(at.triangle >= 0, MCON_ERROR_NUMERICAL, "coarsen_source: a fine vertex lies outside the coarse disk");
      t = at.triangle;
      b = at.barycentric;
    }
    b = b.cwiseMax(0.0);
    c.prolong_corners[v] = tris[t];
    c.prolong_weights[v] = b / b.sum();
  }
}

}  // namespace

std::optional<CoarseSource> coarsen_source(const TriMesh& mesh, const std::vector<Vec2>& uv, int target_vertices,
                                           double max_kept_fraction, double min_angle_degrees) {
  require(uv.size() == mesh.positions.size(), MCON_ERROR_INVALID_ARGUMENT, "coarsen_source: one uv per vertex expected");
  Collapser collapser(mesh, uv, min_angle_degrees);
  collapser.run(std::max(target_vertices, 3));
  const auto kept = std::count(collapser.alive().begin(), collapser.alive().end(), true);
  if (static_cast<double>(kept) > max_kept_fraction * mesh.num_vertices()) return std::nullopt;
  CoarseSource c;
  std::vector<int> to_coarse(mesh.positions.size(), -1);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (collapser.alive()[v]) {
      to_coarse[v] = static_cast<int>(c.to_fine.size());
      c.to_fine.push_back(v);
      c.mesh.positions.push_back(mesh.positions[v]);
      c.uv.push_back(uv[v]);
    }
  for (Tri t : collapser.triangles()) {
    for (int& w : t) w = to_coarse[w];
    c.mesh.triangles.push_back(t);
  }
  locate_fine_vertices(uv, to_coarse, collapser, c);
  return c;
}

bool untangle_folds(const std::vector<Tri>& triangles, const std::vector<Vec2>& rest, Eigen::VectorXd& x, int rings) {
  const int n = static_cast<int>(rest.size());
  require(x.size() == 2 * static_cast<Eigen::Index>(n), MCON_ERROR_INVALID_ARGUMENT,
          "untangle_folds: x needs two entries per rest vertex");
  if (count_inverted(triangles, x) == 0) return true;
  TriMesh rest_mesh;  // the weights' shape: the rest disk, flat
  rest_mesh.positions.reserve(rest.size());
  for (const Vec2& p : rest) rest_mesh.positions.emplace_back(p.x(), p.y(), 0.0);
  rest_mesh.triangles = triangles;
  const MeshTopology topology = build_topology(rest_mesh);
  const std::vector<std::vector<int>> neighbours = vertex_neighbors(rest_mesh, topology);
  std::vector<char> border(n, 0), moved(n, 0);
  for (int e = 0; e < topology.num_edges(); ++e)
    if (topology.is_boundary_edge(e)) border[topology.edges[e][0]] = border[topology.edges[e][1]] = 1;
  std::vector<Vec2> y(n);
  for (int v = 0; v < n; ++v) y[v] = x.segment<2>(2 * v);
  Eigen::VectorXd trial = x;
  for (int ring = 0; ring <= rings; ++ring) {
    // The region: the interior corners of every folded triangle, and one more ring each round.
    std::vector<char> grown = moved;
    for (const Tri& tri : triangles)
      if (is_inverted(tri, trial))
        for (int v : tri)
          if (!border[v]) grown[v] = 1;
    for (int v = 0; v < n; ++v)
      if (moved[v])
        for (int w : neighbours[v])
          if (!border[w]) grown[w] = 1;
    moved.swap(grown);
    try {
      mean_value_solve(rest_mesh, moved, y);
    } catch (const Error& e) {
      // A rest vertex on top of a neighbour has no mean-value weights: an optional repair fails,
      // it does not abort the map (the caller falls back to an earlier stage).
      if (e.status() != MCON_ERROR_NUMERICAL) throw;
      return false;
    }
    for (int v = 0; v < n; ++v)
      if (moved[v]) trial.segment<2>(2 * v) = y[v];
    if (count_inverted(triangles, trial) == 0) {
      x = std::move(trial);
      return true;
    }
  }
  return false;
}

Eigen::MatrixXd CoarseSource::restrict_rows(const Eigen::MatrixXd& fine) const {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(to_fine.size()), fine.cols());
  for (std::size_t k = 0; k < to_fine.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = fine.row(to_fine[k]);
  return out;
}

Eigen::VectorXd CoarseSource::prolong(const Eigen::VectorXd& coarse) const {
  Eigen::VectorXd out(2 * static_cast<Eigen::Index>(prolong_corners.size()));
  for (std::size_t v = 0; v < prolong_corners.size(); ++v) {
    const Tri& c = prolong_corners[v];
    const Vec3& w = prolong_weights[v];
    out.segment<2>(2 * v) =
        w[0] * coarse.segment<2>(2 * c[0]) + w[1] * coarse.segment<2>(2 * c[1]) + w[2] * coarse.segment<2>(2 * c[2]);
  }
  return out;
}

}  // namespace mcon
