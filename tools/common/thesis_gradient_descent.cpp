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

  // Source triangles in the orientation of the map (reversed for a reflected start), with the
  // uv used as rest positions mirrored accordingly, so det J_phi > 0 for a feasible map.
  std::vector<Tri> tris = source.triangles;
  std::vector<Vec2> f = source_uv;
  if (reflected) {
    for (Tri& t : tris) std::swap(t[1], t[2]);
    for (Vec2& p : f) p.y() = -p.y();
  }
  const int nt = static_cast<int>(tris.size());
  std::vector<Eigen::Matrix2d> M_inv(nt), F_inv(nt);
  std::vector<double> det_F(nt), area(nt);
  std::vector<double> vertex_area(n, 0.0);
  for (int t = 0; t < nt; ++t) {
    const Tri& tr = tris[t];
    const Vec3 &a = source.positions[tr[0]], &b = source.positions[tr[1]], &c = source.positions[tr[2]];
    area[t] = 0.5 * (b - a).cross(c - a).norm();
    M_inv[t] = local_edge_matrix(a, b, c).inverse();
    const Eigen::Matrix2d F = uv_edge_matrix(f[tr[0]], f[tr[1]], f[tr[2]]);
    det_F[t] = F.determinant();
    F_inv[t] = F.inverse();
    for (int k = 0; k < 3; ++k) vertex_area[tr[k]] += area[t] / 3.0;
  }
  // Vertex -> incident (triangle, corner), ascending triangle: a fixed gather order.
  std::vector<int> inc_start(n + 1, 0), inc;
  for (const Tri& tr : tris)
    for (int k = 0; k < 3; ++k) ++inc_start[tr[k] + 1];
  for (int v = 0; v < n; ++v) inc_start[v + 1] += inc_start[v];
  inc.resize(inc_start[n]);
  {
    std::vector<int> fill(inc_start.begin(), inc_start.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) inc[fill[tris[t][k]]++] = 3 * t + k;
  }

  // Target: J_g^-1 = N G^-1 per triangle (constant per target triangle: the thesis'
  // discontinuity), barycentric gradients in g(T), vertex neighbours, mean uv edge length.
  const int mt = target.num_triangles();
  std::vector<Eigen::Matrix2d> Jg_inv(mt);
  std::vector<std::array<Vec2, 3>> bary_grad(mt);
  std::vector<std::vector<int>> neighbours(m);
  double edge_sum = 0;
  for (int t = 0; t < mt; ++t) {
    const Tri& tr = target.triangles[t];
    const Vec2 &a = target_uv[tr[0]], &b = target_uv[tr[1]], &c = target_uv[tr[2]];
    const Eigen::Matrix2d G = uv_edge_matrix(a, b, c);
    Jg_inv[t] = local_edge_matrix(target.positions[tr[0]], target.positions[tr[1]], target.positions[tr[2]]) * G.inverse();
    const double two_area = G.determinant();
    auto perp = [](const Vec2& e) { return Vec2(-e.y(), e.x()); };
    bary_grad[t] = {perp(c - b) / two_area, perp(a - c) / two_area, perp(b - a) / two_area};
    for (int k = 0; k < 3; ++k) {
      neighbours[tr[k]].push_back(tr[(k + 1) % 3]);
      edge_sum += (target_uv[tr[(k + 1) % 3]] - target_uv[tr[k]]).norm();
    }
  }
  const double mean_edge = edge_sum / (3.0 * mt);  // interior edges counted twice, as often as they occur
  const double max_update = options.step_scale * mean_edge;
  const double vertex_eps = options.vertex_case_epsilon * mean_edge;
  const TriangleLocator2D locator(target_uv, target.triangles);

  Eigen::VectorXd x(2 * n);
  for (int v = 0; v < n; ++v) x.segment<2>(2 * v) = start[v];
  auto det_P = [&](const Eigen::VectorXd& y, int t) {
    const Tri& tr = tris[t];
    const Vec2 e1 = y.segment<2>(2 * tr[1]) - y.segment<2>(2 * tr[0]);
    const Vec2 e2 = y.segment<2>(2 * tr[2]) - y.segment<2>(2 * tr[0]);
    return e1.x() * e2.y() - e1.y() * e2.x();
  };
  for (int t = 0; t < nt; ++t)
    require(det_P(x, t) > 0, MCON_ERROR_NUMERICAL, "thesis descent: the start has inverted triangles");

  std::vector<int> located(n);
  std::vector<Vec2> grad_vertex(n);
  std::vector<std::array<Vec2, 3>> grad_corner(nt);
  Eigen::VectorXd trial(2 * n);
  ThesisDescentResult out;
  for (int iter = 0; iter < options.iterations; ++iter) {
    // Descriptor term (eq. 4.8, 4.9) and each vertex's target triangle.
    for_each_block(n, kBlock, [&](int begin, int end, int) {
      for (int v = begin; v < end; ++v) {
        const PointLocation loc = locator.locate(x.segment<2>(2 * v));
        located[v] = loc.triangle;
        grad_vertex[v].setZero();
        if (loc.triangle < 0) continue;  // outside the overlap: no descriptor term
        const Tri& tr = target.triangles[loc.triangle];
        double d[3];
        for (int k = 0; k < 3; ++k) d[k] = std::abs(source_descriptor[v] - target_descriptor[tr[k]]);
        // Vertex case (§4.3.2): resting on a target vertex that is a local minimum of d(v, .).
        int nearest = 0;
        for (int k = 1; k < 3; ++k)
          if (loc.barycentric[k] > loc.barycentric[nearest]) nearest = k;
        const int w = tr[nearest];
        if ((x.segment<2>(2 * v) - target_uv[w]).norm() < vertex_eps) {
          bool minimum = true;
          for (int u : neighbours[w])
            minimum = minimum && std::abs(source_descriptor[v] - target_descriptor[u]) >= d[nearest];
          if (minimum) continue;
        }
        Vec2 g = Vec2::Zero();
        for (int k = 0; k < 3; ++k) g += d[k] * bary_grad[loc.triangle][k];
        grad_vertex[v] = options.alpha_descriptor * vertex_area[v] * g;
      }
    });
    // LSCM (eq. 4.10) per corner and the flip barrier (eq. 4.12) per triangle.
    for_each_block(nt, kBlock, [&](int begin, int end, int) {
      for (int t = begin; t < end; ++t) {
        const Tri& tr = tris[t];
        const Vec2 a = x.segment<2>(2 * tr[0]);
        Eigen::Matrix2d P;
        P.col(0) = x.segment<2>(2 * tr[1]) - a;
        P.col(1) = x.segment<2>(2 * tr[2]) - a;
        Eigen::Matrix2d D = Eigen::Matrix2d::Zero();  // d obj / d P
        for (int k = 0; k < 3; ++k) {
          const int lt = located[tr[k]];
          if (lt >= 0) {
            const Eigen::Matrix2d J = Jg_inv[lt] * P * M_inv[t];
            D += Jg_inv[lt].transpose() * lscm_gradient(J) * M_inv[t].transpose();
          } else {
            const Eigen::Matrix2d J = P * F_inv[t];
            D += lscm_gradient(J) * F_inv[t].transpose();
          }
        }
        D *= options.alpha_lscm * area[t] / 3.0;
        const double dp = P.determinant();
        if (dp / det_F[t] < options.barrier_start)  // -log(det P / det F / s_f): gradient -P^-T
          D -= options.alpha_flip * area[t] * P.inverse().transpose();
        grad_corner[t] = {Vec2(-(D.col(0) + D.col(1))), Vec2(D.col(0)), Vec2(D.col(1))};
      }
    });
    // Gather, then the fixed step.
    double longest = 0;
    for (int v = 0; v < n; ++v) {
      Vec2 g = grad_vertex[v];
      for (int i = inc_start[v]; i < inc_start[v + 1]; ++i) g += grad_corner[inc[i] / 3][inc[i] % 3];
      grad_vertex[v] = g;
      longest = std::max(longest, g.norm());
    }
    double lambda = longest > max_update ? max_update / longest : 1.0;
    bool feasible = false;
    for (int b = 0; b <= options.max_backoffs && !feasible; ++b, lambda *= 0.5) {
      for (int v = 0; v < n; ++v) trial.segment<2>(2 * v) = x.segment<2>(2 * v) - lambda * grad_vertex[v];
      std::atomic<bool> inverted{false};
      for_each_block(nt, 1024, [&](int begin, int end, int) {
        for (int t = begin; t < end && !inverted.load(std::memory_order_relaxed); ++t)
          if (det_P(trial, t) <= 0) inverted = true;
      });
      feasible = !inverted;
    }
    if (feasible)
      x.swap(trial);
    else
      ++out.rejected_steps;
    out.iterations = iter + 1;
  }
  out.phi.resize(n);
  for (int v = 0; v < n; ++v) out.phi[v] = x.segment<2>(2 * v);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace mcon::tools
