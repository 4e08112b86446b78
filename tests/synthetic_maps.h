// Synthetic re-embedding problems with a known answer, for the map tests and bench/map_bench:
// two differently tessellated flat unit disks (uv = xy), a smooth asymmetric descriptor field F
// on the target's plane, and a ground-truth map psi (rotation, optional mirror, translation and
// a mild non-rigid warp). The source's descriptor is F o psi, so the exact answer is phi = psi.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "descriptors/descriptor_pyramid.h"
#include "mesh/mesh.h"
#include "test_meshes.h"

namespace mcon::synthetic {

// make_disk with interior vertices moved by up to `jitter` times the ring spacing (deterministic).
inline TriMesh make_jittered_disk(int rings, double jitter, unsigned seed = 7u) {
  TriMesh m = test_meshes::make_disk(rings);
  unsigned state = seed;
  auto rnd = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5;
  };
  const double h = 1.0 / rings;
  for (Vec3& p : m.positions) {
    const double dx = rnd(), dy = rnd();
    if (p.head<2>().norm() < 1 - 0.5 * h) p += Vec3(jitter * h * dx, jitter * h * dy, 0);
  }
  return m;
}

inline std::vector<Vec2> planar_uv(const TriMesh& m) {
  std::vector<Vec2> uv;
  for (const Vec3& p : m.positions) uv.emplace_back(p.x(), p.y());
  return uv;
}

struct GroundTruth {
  double angle = 0;                 // radians
  Vec2 translation = Vec2::Zero();
  bool reflected = false;
  double warp = 0;                  // amplitude of the non-rigid part (0.05: mild)

  Vec2 apply(const Vec2& p) const {
    Vec2 q = reflected ? Vec2(p.x(), -p.y()) : p;
    q += warp * Vec2(std::sin(2.0 * q.y()), std::sin(2.0 * q.x()));
    const double c = std::cos(angle), s = std::sin(angle);
    return Vec2(c * q.x() - s * q.y(), s * q.x() + c * q.y()) + translation;
  }
};

// An asymmetric smooth field (no rotation or mirror symmetry), `dim` = 1..3 components.
inline Eigen::VectorXd field(const Vec2& p, int dim) {
  auto bump = [&p](double cx, double cy, double s) { return std::exp(-((p - Vec2(cx, cy)).squaredNorm()) / (2 * s * s)); };
  Eigen::VectorXd f(dim);
  f[0] = bump(0.35, 0.2, 0.25) - 0.7 * bump(-0.3, 0.35, 0.3) + 0.8 * bump(0.05, -0.45, 0.2) +
         0.5 * bump(-0.45, -0.25, 0.22) + 0.3 * p.x();
  if (dim > 1) f[1] = 0.6 * std::sin(2.2 * p.x() + 0.7) * std::cos(1.7 * p.y() - 0.4) + 0.6 * bump(0.5, -0.4, 0.3);
  if (dim > 2) f[2] = 0.5 * bump(-0.1, 0.1, 0.4) - 0.4 * bump(0.6, 0.6, 0.3) + 0.2 * p.y();
  return f;
}

// A smooth field unrelated to `field`, used to make the source's descriptor differ from the
// target's (as two real patches' curvatures do).
inline Eigen::VectorXd nuisance(const Vec2& p, int dim) {
  Eigen::VectorXd f(dim);
  for (int k = 0; k < dim; ++k)
    f[k] = std::sin(3.1 * p.x() + 1.3 * k) * std::cos(2.3 * p.y() - 0.5 * k) + 0.5 * std::cos(4.0 * p.x() * p.y() + k);
  return f;
}

struct Problem {
  TriMesh source, target;
  std::vector<Vec2> source_uv, target_uv;
  std::vector<Eigen::MatrixXd> source_levels, target_levels;
  GroundTruth truth;
};

// mismatch > 0 makes the source's descriptor (1 + mismatch) * F o psi + mismatch * nuisance o psi
// instead of F o psi: a magnitude difference plus a geometric difference.
inline Problem make_problem(int source_rings, int target_rings, const GroundTruth& truth, int dim = 2,
                            const std::vector<double>& sigmas = {0.2, 0.1, 0.0}, double mismatch = 0.0) {
  Problem pr;
  pr.truth = truth;
  pr.source = test_meshes::make_disk(source_rings);
  pr.target = make_jittered_disk(target_rings, 0.35);
  pr.source_uv = planar_uv(pr.source);
  pr.target_uv = planar_uv(pr.target);
  Eigen::MatrixXd fs(pr.source.num_vertices(), dim), ft(pr.target.num_vertices(), dim);
  for (int v = 0; v < pr.source.num_vertices(); ++v) {
    const Vec2 q = truth.apply(pr.source_uv[v]);
    fs.row(v) = ((1 + mismatch) * field(q, dim) + mismatch * nuisance(q, dim)).transpose();
  }
  for (int v = 0; v < pr.target.num_vertices(); ++v) ft.row(v) = field(pr.target_uv[v], dim).transpose();
  pr.source_levels = descriptor_pyramid(pr.source, fs, sigmas);
  pr.target_levels = descriptor_pyramid(pr.target, ft, sigmas);
  return pr;
}

// Mean |phi(v) - psi(v)| over source vertices whose true image lies inside radius `inner`.
inline double mean_error(const Problem& pr, const std::vector<Vec2>& phi, double inner = 0.95) {
  double sum = 0;
  int count = 0;
  for (std::size_t v = 0; v < phi.size(); ++v) {
    const Vec2 truth = pr.truth.apply(pr.source_uv[v]);
    if (truth.norm() >= inner) continue;
    sum += (phi[v] - truth).norm();
    ++count;
  }
  return count ? sum / count : 0.0;
}

}  // namespace mcon::synthetic
