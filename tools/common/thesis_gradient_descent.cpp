#include "common/thesis_gradient_descent.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>

#include <Eigen/Dense>

#include "base/error.h"
#include "base/parallel_blocks.h"
#include "mesh/point_location_2d.h"

namespace mcon::tools {

namespace {

constexpr int kBlock = 256;

// The 2x2 edge matrix of a 3D triangle in its own orthonormal frame (thesis §4.2.2: origin a,
// e_u = (b - a) / |b - a|, e_v = n x e_u).
Eigen::Matrix2d local_edge_matrix(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const double l1 = e1.norm();
  const Vec3 eu = e1 / l1;
  const Vec3 n = e1.cross(e2);
  const Vec3 ev = n.normalized().cross(eu);
  Eigen::Matrix2d m;
  m << l1, e2.dot(eu), 0.0, e2.dot(ev);
  return m;
}

Eigen::Matrix2d uv_edge_matrix(const Vec2& a, const Vec2& b, const Vec2& c) {
  Eigen::Matrix2d m;
  m.col(0) = b - a;
  m.col(1) = c - a;
  return m;
}

// d lscm / d J for lscm(J) = (J01 + J10)^2 + (J11 - J00)^2 (thesis §4.2.2).
Eigen::Matrix2d lscm_gradient(const Eigen::Matrix2d& J) {
  const double d1 = J(0, 1) + J(1, 0), d2 = J(1, 1) - J(0, 0);
  Eigen::Matrix2d g;
  g << -2 * d2, 2 * d1, 2 * d1, 2 * d2;
  return g;
}

// Source triangles in the orientation of the map, their rest frames and areas, and each vertex's
// incident corners.
struct SourceRest {
  std::vector<Tri> tris;
  std::vector<Eigen::Matrix2d> M_inv, F_inv;
  std::vector<double> det_F, area;
  std::vector<double> vertex_area;
  std::vector<int> inc_start, inc;  // vertex v's corners (3 t + k) are inc[inc_start[v] .. inc_start[v + 1])
};

SourceRest source_rest(const TriMesh& source, const std::vector<Vec2>& source_uv, bool reflected) {
  const int n = source.num_vertices();
  SourceRest s;
  // Source triangles in the orientation of the map (reversed for a reflected start), with the
  // uv used as rest positions mirrored accordingly, so det J_phi > 0 for a feasible map.
  s.tris = source.triangles;
  std::vector<Vec2> f = source_uv;
  if (reflected) {
    for (Tri& t : s.tris) std::swap(t[1], t[2]);
    for (Vec2& p : f) p.y() = -p.y();
  }
  const std::vector<Tri>& tris = s.tris;
  const int nt = static_cast<int>(tris.size());
  s.M_inv.resize(nt);
  s.F_inv.resize(nt);
  s.det_F.resize(nt);
  s.area.resize(nt);
  s.vertex_area.assign(n, 0.0);
  for (int t = 0; t < nt; ++t) {
    const Tri& tr = tris[t];
    const Vec3 &a = source.positions[tr[0]], &b = source.positions[tr[1]], &c = source.positions[tr[2]];
    s.area[t] = 0.5 * (b - a).cross(c - a).norm();
    s.M_inv[t] = local_edge_matrix(a, b, c).inverse();
    const Eigen::Matrix2d F = uv_edge_matrix(f[tr[0]], f[tr[1]], f[tr[2]]);
    s.det_F[t] = F.determinant();
    s.F_inv[t] = F.inverse();
    for (int k = 0; k < 3; ++k) s.vertex_area[tr[k]] += s.area[t] / 3.0;
  }
  // Vertex -> incident (triangle, corner), ascending triangle: a fixed gather order.
  s.inc_start.assign(n + 1, 0);
  for (const Tri& tr : tris)
    for (int k = 0; k < 3; ++k) ++s.inc_start[tr[k] + 1];
  for (int v = 0; v < n; ++v) s.inc_start[v + 1] += s.inc_start[v];
  s.inc.resize(s.inc_start[n]);
  {
    std::vector<int> fill(s.inc_start.begin(), s.inc_start.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) s.inc[fill[tris[t][k]]++] = 3 * t + k;
  }
  return s;
}

struct TargetFrames {
  std::vector<Eigen::Matrix2d> Jg_inv;
  std::vector<std::array<Vec2, 3>> bary_grad;
  std::vector<std::vector<int>> neighbours;
  double mean_edge = 0;
};

// Target: J_g^-1 = N G^-1 per triangle (constant per target triangle: the thesis'
// discontinuity), barycentric gradients in g(T), vertex neighbours, mean uv edge length.
TargetFrames target_frames(const TriMesh& target, const std::vector<Vec2>& target_uv) {
  const int m = target.num_vertices();
  const int mt = target.num_triangles();
  TargetFrames g;
  g.Jg_inv.resize(mt);
  g.bary_grad.resize(mt);
  g.neighbours.resize(m);
  double edge_sum = 0;
  for (int t = 0; t < mt; ++t) {
    const Tri& tr = target.triangles[t];
    const Vec2 &a = target_uv[tr[0]], &b = target_uv[tr[1]], &c = target_uv[tr[2]];
    const Eigen::Matrix2d G = uv_edge_matrix(a, b, c);
    g.Jg_inv[t] = local_edge_matrix(target.positions[tr[0]], target.positions[tr[1]], target.positions[tr[2]]) * G.inverse();
    const double two_area = G.determinant();
    auto perp = [](const Vec2& e) { return Vec2(-e.y(), e.x()); };
    g.bary_grad[t] = {perp(c - b) / two_area, perp(a - c) / two_area, perp(b - a) / two_area};
    for (int k = 0; k < 3; ++k) {
      g.neighbours[tr[k]].push_back(tr[(k + 1) % 3]);
      edge_sum += (target_uv[tr[(k + 1) % 3]] - target_uv[tr[k]]).norm();
    }
  }
  g.mean_edge = edge_sum / (3.0 * mt);  // interior edges counted twice, as often as they occur
  return g;
}

double det_P(const std::vector<Tri>& tris, const Eigen::VectorXd& y, int t) {
  const Tri& tr = tris[t];
  const Vec2 e1 = y.segment<2>(2 * tr[1]) - y.segment<2>(2 * tr[0]);
  const Vec2 e2 = y.segment<2>(2 * tr[2]) - y.segment<2>(2 * tr[0]);
  return e1.x() * e2.y() - e1.y() * e2.x();
}

// The descent's fixed inputs and its per-iteration buffers.
struct Descent {
  const TriMesh& target;
  const std::vector<Vec2>& target_uv;
  const Eigen::VectorXd& source_descriptor;
  const Eigen::VectorXd& target_descriptor;
  const ThesisDescentOptions& options;
  const SourceRest& rest;
  const TargetFrames& frames;
  const TriangleLocator2D& locator;
  double max_update, vertex_eps;
  Eigen::VectorXd x, trial;
  std::vector<int> located;
  std::vector<Vec2> grad_vertex;
  std::vector<std::array<Vec2, 3>> grad_corner;
};

// Descriptor term (eq. 4.8, 4.9) and each vertex's target triangle.
void descriptor_gradients(Descent& s, int n) {
  const Eigen::VectorXd& x = s.x;
  for_each_block(n, kBlock, [&](int begin, int end, int) {
    for (int v = begin; v < end; ++v) {
      const PointLocation loc = s.locator.locate(x.segment<2>(2 * v));
      s.located[v] = loc.triangle;
      s.grad_vertex[v].setZero();
      if (loc.triangle < 0) continue;  // outside the overlap: no descriptor term
      const Tri& tr = s.target.triangles[loc.triangle];
      double d[3];
      for (int k = 0; k < 3; ++k) d[k] = std::abs(s.source_descriptor[v] - s.target_descriptor[tr[k]]);
      // Vertex case (§4.3.2): resting on a target vertex that is a local minimum of d(v, .).
      int nearest = 0;
      for (int k = 1; k < 3; ++k)
        if (loc.barycentric[k] > loc.barycentric[nearest]) nearest = k;
      const int w = tr[nearest];
      if ((x.segment<2>(2 * v) - s.target_uv[w]).norm() < s.vertex_eps) {
        bool minimum = true;
        for (int u : s.frames.neighbours[w])
          minimum = minimum && std::abs(s.source_descriptor[v] - s.target_descriptor[u]) >= d[nearest];
        if (minimum) continue;
      }
      Vec2 g = Vec2::Zero();
      for (int k = 0; k < 3; ++k) g += d[k] * s.frames.bary_grad[loc.triangle][k];
      s.grad_vertex[v] = s.options.alpha_descriptor * s.rest.vertex_area[v] * g;
    }
  });
}

// LSCM (eq. 4.10) per corner and the flip barrier (eq. 4.12) per triangle.
void corner_gradients(Descent& s, int nt) {
  const Eigen::VectorXd& x = s.x;
  const SourceRest& r = s.rest;
  const ThesisDescentOptions& options = s.options;
  for_each_block(nt, kBlock, [&](int begin, int end, int) {
    for (int t = begin; t < end; ++t) {
      const Tri& tr = r.tris[t];
      const Vec2 a = x.segment<2>(2 * tr[0]);
      Eigen::Matrix2d P;
      P.col(0) = x.segment<2>(2 * tr[1]) - a;
      P.col(1) = x.segment<2>(2 * tr[2]) - a;
      Eigen::Matrix2d D = Eigen::Matrix2d::Zero();  // d obj / d P
      for (int k = 0; k < 3; ++k) {
        const int lt = s.located[tr[k]];
        if (lt >= 0) {
          const Eigen::Matrix2d J = s.frames.Jg_inv[lt] * P * r.M_inv[t];
          D += s.frames.Jg_inv[lt].transpose() * lscm_gradient(J) * r.M_inv[t].transpose();
        } else {
          const Eigen::Matrix2d J = P * r.F_inv[t];
          D += lscm_gradient(J) * r.F_inv[t].transpose();
        }
      }
      D *= options.alpha_lscm * r.area[t] / 3.0;
      const double dp = P.determinant();
      if (dp / r.det_F[t] < options.barrier_start)  // -log(det P / det F / s_f): gradient -P^-T
        D -= options.alpha_flip * r.area[t] * P.inverse().transpose();
      s.grad_corner[t] = {Vec2(-(D.col(0) + D.col(1))), Vec2(D.col(0)), Vec2(D.col(1))};
    }
  });
}

// Gather, then the fixed step (halved until no triangle inverts). Returns whether a step was taken.
bool gather_and_step(Descent& s, int n, int nt) {
  const SourceRest& r = s.rest;
  double longest = 0;
  for (int v = 0; v < n; ++v) {
    Vec2 g = s.grad_vertex[v];
    for (int i = r.inc_start[v]; i < r.inc_start[v + 1]; ++i) g += s.grad_corner[r.inc[i] / 3][r.inc[i] % 3];
    s.grad_vertex[v] = g;
    longest = std::max(longest, g.norm());
  }
  double lambda = longest > s.max_update ? s.max_update / longest : 1.0;
  bool feasible = false;
  for (int b = 0; b <= s.options.max_backoffs && !feasible; ++b, lambda *= 0.5) {
    for (int v = 0; v < n; ++v) s.trial.segment<2>(2 * v) = s.x.segment<2>(2 * v) - lambda * s.grad_vertex[v];
    std::atomic<bool> inverted{false};
    for_each_block(nt, 1024, [&](int begin, int end, int) {
      for (int t = begin; t < end && !inverted.load(std::memory_order_relaxed); ++t)
        if (det_P(r.tris, s.trial, t) <= 0) inverted = true;
    });
    feasible = !inverted;
  }
  if (feasible) s.x.swap(s.trial);
  return feasible;
}

}  // namespace

ThesisDescentResult thesis_gradient_descent(const TriMesh& source, const std::vector<Vec2>& source_uv,
                                            const Eigen::VectorXd& source_descriptor, const TriMesh& target,
                                            const std::vector<Vec2>& target_uv,
                                            const Eigen::VectorXd& target_descriptor, const std::vector<Vec2>& start,
                                            bool reflected, const ThesisDescentOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = source.num_vertices(), m = target.num_vertices();
  require(static_cast<int>(source_uv.size()) == n && source_descriptor.size() == n &&
              static_cast<int>(start.size()) == n && static_cast<int>(target_uv.size()) == m &&
              target_descriptor.size() == m && n > 0 && m > 0,
          MCON_ERROR_INVALID_ARGUMENT, "thesis descent: inconsistent sizes");
  require(options.iterations >= 0 && options.step_scale > 0 && options.barrier_start > 0, MCON_ERROR_INVALID_ARGUMENT,
          "thesis descent: invalid options");

  const SourceRest rest = source_rest(source, source_uv, reflected);
  const int nt = static_cast<int>(rest.tris.size());
  const TargetFrames frames = target_frames(target, target_uv);
  const TriangleLocator2D locator(target_uv, target.triangles);
  Descent s{target, target_uv, source_descriptor, target_descriptor, options, rest, frames, locator,
            options.step_scale * frames.mean_edge, options.vertex_case_epsilon * frames.mean_edge,
            Eigen::VectorXd(2 * n), Eigen::VectorXd(2 * n), std::vector<int>(n), std::vector<Vec2>(n),
            std::vector<std::array<Vec2, 3>>(nt)};

  for (int v = 0; v < n; ++v) s.x.segment<2>(2 * v) = start[v];
  for (int t = 0; t < nt; ++t)
    require(det_P(rest.tris, s.x, t) > 0, MCON_ERROR_NUMERICAL, "thesis descent: the start has inverted triangles");

  ThesisDescentResult out;
  for (int iter = 0; iter < options.iterations; ++iter) {
    descriptor_gradients(s, n);
    corner_gradients(s, nt);
    if (!gather_and_step(s, n, nt)) ++out.rejected_steps;
    out.iterations = iter + 1;
  }
  out.phi.resize(n);
  for (int v = 0; v < n; ++v) out.phi[v] = s.x.segment<2>(2 * v);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace mcon::tools
