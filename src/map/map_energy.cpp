#include "map/map_energy.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "base/error.h"
#include "base/parallel_blocks.h"

namespace mcon {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kVertexBlock = 256;
constexpr int kTriangleBlock = 512;

Eigen::Vector4d vec(const Eigen::Matrix2d& J) { return Eigen::Vector4d(J(0, 0), J(0, 1), J(1, 0), J(1, 1)); }

// d det / d vec(J) and its (constant) Hessian.
Eigen::Vector4d det_gradient(const Eigen::Matrix2d& J) { return Eigen::Vector4d(J(1, 1), -J(1, 0), -J(0, 1), J(0, 0)); }
Eigen::Matrix4d det_hessian() {
  Eigen::Matrix4d h = Eigen::Matrix4d::Zero();
  h(0, 3) = h(3, 0) = 1;
  h(1, 2) = h(2, 1) = -1;
  return h;
}

Eigen::Matrix2d jacobian_at(const Eigen::VectorXd& x, const Tri& tri, const Eigen::Matrix2d& rest_inverse) {
  const int a = 2 * tri[0], b = 2 * tri[1], c = 2 * tri[2];
  Eigen::Matrix2d X;
  X << x[b] - x[a], x[c] - x[a], x[b + 1] - x[a + 1], x[c + 1] - x[a + 1];
  return X * rest_inverse;
}

// values[index[j]] += the block sums of triangle term j (sums: one row of index.size() per
// block), in block order.
void add_block_sums(const std::vector<double>& sums, const std::vector<int>& index, std::vector<double>& values) {
  const std::size_t k = index.size();
  for (std::size_t b = 0; k > 0 && b < sums.size() / k; ++b)
    for (std::size_t j = 0; j < k; ++j) values[index[j]] += sums[b * k + j];
}

}  // namespace

const std::vector<MapEnergyTerm>& map_energy_terms() {
  static const std::vector<MapEnergyTerm> terms = {
      {"descriptor", &MapEnergyWeights::descriptor, MapTermDomain::descriptor, nullptr},
      {"distortion", &MapEnergyWeights::distortion, MapTermDomain::triangle,
       [](const Eigen::Matrix2d& J, const MapEnergyWeights&, Eigen::Vector4d* g, Eigen::Matrix4d* h) {
         return conformal_distortion(J, g, h);
       }},
      {"area", &MapEnergyWeights::area, MapTermDomain::triangle,
       [](const Eigen::Matrix2d& J, const MapEnergyWeights&, Eigen::Vector4d* g, Eigen::Matrix4d* h) {
         return area_distortion(J, g, h);
       }},
      {"injectivity", &MapEnergyWeights::injectivity, MapTermDomain::triangle,
       [](const Eigen::Matrix2d& J, const MapEnergyWeights& w, Eigen::Vector4d* g, Eigen::Matrix4d* h) {
         return injectivity_barrier(J, w.barrier_start, g, h);
       }},
      {"anchor", &MapEnergyWeights::anchor, MapTermDomain::anchor, nullptr},
  };
  return terms;
}

int map_energy_term_index(const char* name) {
  const std::vector<MapEnergyTerm>& terms = map_energy_terms();
  for (std::size_t i = 0; i < terms.size(); ++i)
    if (std::strcmp(terms[i].name, name) == 0) return static_cast<int>(i);
  return -1;
}

double MapEnergyTerms::value(const char* name) const {
  const int i = map_energy_term_index(name);
  require(i >= 0 && static_cast<std::size_t>(i) < values.size(), MCON_ERROR_INVALID_ARGUMENT,
          std::string("map energy: no term named '") + name + "'");
  return values[static_cast<std::size_t>(i)];
}

std::vector<Vec2> rest_positions(const std::vector<Vec2>& uv, bool reflected) {
  std::vector<Vec2> rest(uv);
  if (reflected)
    for (Vec2& p : rest) p.y() = -p.y();
  return rest;
}

SourceDisk make_source_disk(const TriMesh& mesh, const std::vector<Vec2>& uv, bool reflected) {
  require(uv.size() == mesh.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
          "source disk: uv must have one entry per vertex");
  for (const Vec2& p : uv)
    require(std::isfinite(p.x()) && std::isfinite(p.y()), MCON_ERROR_NON_FINITE, "source disk: non-finite uv");
  SourceDisk s;
  s.num_vertices = mesh.num_vertices();
  s.reflected = reflected;
  const std::vector<Vec2> rest = rest_positions(uv, reflected);
  const int nt = mesh.num_triangles();
  s.triangles.resize(nt);
  s.rest_inverse.resize(nt);
  s.triangle_weight.resize(nt);
  s.vertex_weight.assign(s.num_vertices, 0.0);
  double total = 0;
  for (int t = 0; t < nt; ++t) total += triangle_area(mesh, t);
  require(total > 0 && std::isfinite(total), MCON_ERROR_DEGENERATE_TRIANGLE, "source disk: zero total area");
  for (int t = 0; t < nt; ++t) {
    Tri tri = mesh.triangles[t];
    if (reflected) std::swap(tri[1], tri[2]);
    Eigen::Matrix2d E;
    E << rest[tri[1]] - rest[tri[0]], rest[tri[2]] - rest[tri[0]];
    const double det = E.determinant();
    require(det > 0, MCON_ERROR_INVALID_ARGUMENT,
            "source disk: uv triangle " + std::to_string(t) + " is inverted or degenerate");
    s.triangles[t] = tri;
    s.rest_inverse[t] = E.inverse();
    s.triangle_weight[t] = triangle_area(mesh, t) / total;
    for (int v : tri) s.vertex_weight[v] += s.triangle_weight[t] / 3.0;
  }
  return s;
}

double conformal_distortion(const Eigen::Matrix2d& J, Eigen::Vector4d* gradient, Eigen::Matrix4d* hessian) {
  const double det = J.determinant();
  if (!(det > 0)) return kInf;
  const Eigen::Vector4d j = vec(J);
  const double F = j.squaredNorm();
  const double value = F / (2 * det) - 1;
  if (gradient || hessian) {
    const Eigen::Vector4d gd = det_gradient(J);
    if (gradient) *gradient = j / det - F / (2 * det * det) * gd;
    if (hessian) {
      *hessian = Eigen::Matrix4d::Identity() / det - (j * gd.transpose() + gd * j.transpose()) / (det * det) +
                 F / (det * det * det) * gd * gd.transpose() - F / (2 * det * det) * det_hessian();
    }
  }
  return value;
}

double area_distortion(const Eigen::Matrix2d& J, Eigen::Vector4d* gradient, Eigen::Matrix4d* hessian) {
  const double det = J.determinant();
  if (!(det > 0)) return kInf;
  const double value = 0.5 * (det + 1 / det) - 1;
  if (gradient || hessian) {
    const double a1 = 0.5 * (1 - 1 / (det * det));
    const double a2 = 1 / (det * det * det);
    const Eigen::Vector4d gd = det_gradient(J);
    if (gradient) *gradient = a1 * gd;
    if (hessian) *hessian = a2 * gd * gd.transpose() + a1 * det_hessian();
  }
  return value;
}

double injectivity_barrier(const Eigen::Matrix2d& J, double s, Eigen::Vector4d* gradient, Eigen::Matrix4d* hessian) {
  const double det = J.determinant();
  if (!(det > 0)) return kInf;
  const double q = det / s;
  if (q >= 1) {
    if (gradient) gradient->setZero();
    if (hessian) hessian->setZero();
    return 0;
  }
  const double lq = std::log(q), qm = q - 1;
  const double value = -qm * qm * lq;
  if (gradient || hessian) {
    const double b1 = -2 * qm * lq - qm * qm / q;                              // db/dq
    const double b2 = -2 * lq - 4 * qm / q + qm * qm / (q * q);               // d2b/dq2
    const Eigen::Vector4d gd = det_gradient(J);
    if (gradient) *gradient = (b1 / s) * gd;
    if (hessian) *hessian = (b2 / (s * s)) * gd * gd.transpose() + (b1 / s) * det_hessian();
  }
  return value;
}

Eigen::Matrix<double, 4, 6> jacobian_map(const Eigen::Matrix2d& D) {
  Eigen::Matrix<double, 4, 6> B = Eigen::Matrix<double, 4, 6>::Zero();
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      B(2 * r + c, 0 + r) = -(D(0, c) + D(1, c));
      B(2 * r + c, 2 + r) = D(0, c);
      B(2 * r + c, 4 + r) = D(1, c);
    }
  return B;
}

Eigen::Matrix4d project_psd(const Eigen::Matrix4d& h) {
  // Most element Hessians are already positive definite: a 4x4 Cholesky says so at a fraction of
  // the eigendecomposition's cost (bench: derivatives 1.79 -> 1.33 s over the four cases).
  if (Eigen::LLT<Eigen::Matrix4d>(h).info() == Eigen::Success) return h;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> es(h);
  const Eigen::Vector4d ev = es.eigenvalues();
  if (ev.minCoeff() >= 0) return h;
  return es.eigenvectors() * ev.cwiseMax(0.0).asDiagonal() * es.eigenvectors().transpose();
}

// J = U diag(s1, s2) V^T with U, V rotations (s2 < 0 when det J < 0): the closed form of the 2x2
// SVD through the rotation and reflection parts of J (Blinn, "Consider the lowly 2x2 matrix").
void rotations_of_svd(const Eigen::Matrix2d& J, Eigen::Matrix2d& U, Eigen::Matrix2d& Vt) {
  const double e = 0.5 * (J(0, 0) + J(1, 1)), f = 0.5 * (J(0, 0) - J(1, 1));
  const double g = 0.5 * (J(1, 0) + J(0, 1)), h = 0.5 * (J(1, 0) - J(0, 1));
  const double a1 = std::atan2(g, f), a2 = std::atan2(h, e);
  const double phi = 0.5 * (a2 + a1), theta = 0.5 * (a2 - a1);
  U << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
  Vt << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
}

bool project_psd_isotropic(const Eigen::Matrix2d& J, Eigen::Matrix4d& h) {
  // Smith, de Goes, Kim 2019, "Analytic eigensystems for isotropic distortion energies" (2D): the
  // Hessian of an energy of the singular values of J has the eigenvectors U M V^T for M the twist
  // [0 -1; 1 0] / sqrt 2 and the flip [0 1; 1 0] / sqrt 2, and two in the span of the scalings
  // diag(1, 0), diag(0, 1). Rotated into that basis it is diagonal, diagonal, and a 2x2 block.
  Eigen::Matrix2d U, Vt;
  rotations_of_svd(J, U, Vt);
  const double r = std::sqrt(0.5);
  const Eigen::Matrix2d modes[4] = {(Eigen::Matrix2d() << 0, -r, r, 0).finished(),
                                    (Eigen::Matrix2d() << 0, r, r, 0).finished(),
                                    (Eigen::Matrix2d() << 1, 0, 0, 0).finished(),
                                    (Eigen::Matrix2d() << 0, 0, 0, 1).finished()};
  Eigen::Matrix4d Q;
  for (int k = 0; k < 4; ++k) Q.col(k) = vec(U * modes[k] * Vt);
  const Eigen::Matrix4d d = Q.transpose() * h * Q;
  const double off = std::max({std::abs(d(0, 1)), std::abs(d(0, 2)), std::abs(d(0, 3)), std::abs(d(1, 2)),
                               std::abs(d(1, 3))});
  if (!(off <= 1e-9 * d.cwiseAbs().maxCoeff())) return false;  // not isotropic (or not finite)
  Eigen::Matrix4d clamped = Eigen::Matrix4d::Zero();
  clamped(0, 0) = std::max(d(0, 0), 0.0);
  clamped(1, 1) = std::max(d(1, 1), 0.0);
  clamped.block<2, 2>(2, 2) = project_psd(Eigen::Matrix2d(0.5 * (d.block<2, 2>(2, 2) + d.block<2, 2>(2, 2).transpose())));
  h = Q * clamped * Q.transpose();
  return true;
}

Eigen::Matrix4d project_psd_element(const Eigen::Matrix4d& h, const Eigen::Matrix2d& J) {
  if (Eigen::LLT<Eigen::Matrix4d>(h).info() == Eigen::Success) return h;  // the common case, as in project_psd
  Eigen::Matrix4d p = h;
  if (project_psd_isotropic(J, p)) return p;
  return project_psd(h);
}

Eigen::Matrix2d project_psd(const Eigen::Matrix2d& h) {
  // Closed form of the symmetric [a b; b c] (its lower triangle, as an eigensolver reads it): the
  // eigenvalues are m +- r, m = (a + c) / 2, r = sqrt(((a - c) / 2)^2 + b^2). With exactly one
  // negative one, the projection keeps hi v v^T, and v v^T = (H - lo I) / (hi - lo) is the
  // spectral projector of hi, so no eigenvector is needed.
  const double a = h(0, 0), b = h(1, 0), c = h(1, 1);
  const double m = 0.5 * (a + c), half_gap = 0.5 * (a - c);
  const double r = std::sqrt(half_gap * half_gap + b * b);
  const double hi = m + r, lo = m - r;
  if (lo >= 0) return h;
  if (hi <= 0) return Eigen::Matrix2d::Zero();
  if (!std::isfinite(lo)) return h;  // NaN in, NaN out (the caller's finiteness checks see it)
  Eigen::Matrix2d p;
  p << a - lo, b, b, c - lo;
  return (hi / (hi - lo)) * p;
}

MapEnergy::MapEnergy(const SourceDisk& source, const DescriptorField2D& target_field,
                     const Eigen::MatrixXd& source_values, const ScoreSettings& score,
                     const MapEnergyWeights& weights, const MapAnchor* anchor)
    : source_(&source), field_(&target_field), score_(score), weights_(weights) {
  require(weights.anchor >= 0 && std::isfinite(weights.anchor), MCON_ERROR_INVALID_ARGUMENT,
          "map energy: the anchor weight must be finite and >= 0");
  if (weights.anchor > 0) {
    require(anchor != nullptr && anchor->position.size() == static_cast<std::size_t>(source.num_vertices) &&
                anchor->weight.size() == anchor->position.size(),
            MCON_ERROR_INVALID_ARGUMENT, "map energy: an anchor weight > 0 needs one anchor position and weight per source vertex");
    anchor_ = anchor;
  }
  require(source_values.rows() == source.num_vertices, MCON_ERROR_INVALID_ARGUMENT,
          "map energy: one source descriptor row per vertex expected");
  require(source_values.cols() == target_field.dimension(), MCON_ERROR_INVALID_ARGUMENT,
          "map energy: source and target descriptors differ in dimension");
  require(source_values.allFinite(), MCON_ERROR_NON_FINITE, "map energy: non-finite source descriptor");
  const int d = target_field.dimension();
  location_hint_.assign(source.num_vertices, -1);
  values_.resize(static_cast<std::size_t>(source.num_vertices) * d);
  for (int v = 0; v < source.num_vertices; ++v)
    for (int k = 0; k < d; ++k) values_[static_cast<std::size_t>(v) * d + k] = source_values(v, k);
}

MapEnergy::TriangleTermSet MapEnergy::triangle_terms() const {
  TriangleTermSet set;
  const std::vector<MapEnergyTerm>& terms = map_energy_terms();
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (terms[i].domain == MapTermDomain::descriptor) {
      set.descriptor = static_cast<int>(i);
    } else if (terms[i].domain == MapTermDomain::anchor) {
      set.anchor = static_cast<int>(i);
    } else {
      set.index.push_back(static_cast<int>(i));
      set.energy.push_back(terms[i].triangle_energy);
      set.weight.push_back(weights_.*terms[i].weight);
    }
  }
  return set;
}

// The weighted total, summed in table order (the order of the terms is the order of the sum).
double MapEnergy::weighted_total(const std::vector<double>& values) const {
  const std::vector<MapEnergyTerm>& terms = map_energy_terms();
  double total = weights_.*terms[0].weight * values[0];
  for (std::size_t i = 1; i < terms.size(); ++i) total += weights_.*terms[i].weight * values[i];
  return total;
}

MapEnergyTerms MapEnergy::evaluate(const Eigen::VectorXd& x) const {
  const SourceDisk& s = *source_;
  const int d = field_->dimension();
  const int nt = static_cast<int>(s.triangles.size());
  const TriangleTermSet tt = triangle_terms();
  const std::size_t k = tt.energy.size();
  MapEnergyTerms terms;
  terms.values.assign(map_energy_terms().size(), 0.0);
  // The triangle terms per block; an inverted triangle makes the distortion and barrier +infinity.
  std::vector<double> sums(static_cast<std::size_t>(block_count(nt, kTriangleBlock)) * k, 0.0);
  for_each_block(nt, kTriangleBlock, [&](int begin, int end, int b) {
    double* sum = &sums[static_cast<std::size_t>(b) * k];
    for (int t = begin; t < end; ++t) {
      const Eigen::Matrix2d J = jacobian_at(x, s.triangles[t], s.rest_inverse[t]);
      const double w = s.triangle_weight[t];
      for (std::size_t j = 0; j < k; ++j) sum[j] += w * tt.energy[j](J, weights_, nullptr, nullptr);
    }
  });
  add_block_sums(sums, tt.index, terms.values);
  terms.values[tt.descriptor] = deterministic_sum(s.num_vertices, kVertexBlock, [&](int v) {
    thread_local std::vector<double> scratch;
    scratch.resize(3 * static_cast<std::size_t>(d));
    const ScoreSample sample = vertex_score(v, x, false, scratch.data());
    return s.vertex_weight[v] * (1.0 - sample.score);
  });
  if (anchor_) terms.values[tt.anchor] = anchor_energy(x, nullptr, nullptr);
  terms.total = weighted_total(terms.values);
  if (!std::isfinite(terms.total)) terms.total = kInf;
  return terms;
}

ScoreSample MapEnergy::vertex_score(int v, const Eigen::VectorXd& x, bool derivatives, double* scratch) const {
  const ScoreSample sample = match_score(*field_, &values_[static_cast<std::size_t>(v) * field_->dimension()],
                                         Vec2(x[2 * v], x[2 * v + 1]), score_, derivatives, scratch, nullptr,
                                         location_hint_[v]);
  if (sample.location.triangle >= 0) location_hint_[v] = sample.location.triangle;
  return sample;
}

// E_p = sum_v A_v m_v |x_v - p_v|^2; gradient 2 alpha_p A_v m_v (x_v - p_v), Hessian 2 alpha_p A_v m_v I.
double MapEnergy::anchor_energy(const Eigen::VectorXd& x, std::vector<Vec2>* gradient,
                                std::vector<Eigen::Matrix2d>* hessians) const {
  const SourceDisk& s = *source_;
  return deterministic_sum(s.num_vertices, kVertexBlock, [&](int v) {
    const double w = s.vertex_weight[v] * anchor_->weight[v];
    const Vec2 d = Vec2(x[2 * v], x[2 * v + 1]) - anchor_->position[v];
    if (gradient) (*gradient)[v] += 2 * weights_.anchor * w * d;
    if (hessians) (*hessians)[v] += 2 * weights_.anchor * w * Eigen::Matrix2d::Identity();
    return w * d.squaredNorm();
  });
}

void MapEnergy::derivatives(const Eigen::VectorXd& x, Derivatives& out) const {
  const SourceDisk& s = *source_;
  const int d = field_->dimension();
  const int nt = static_cast<int>(s.triangles.size());
  const int nv = s.num_vertices;
  const TriangleTermSet tt = triangle_terms();
  const std::size_t k = tt.energy.size();
  out.triangle_hessians.resize(nt);
  out.vertex_hessians.resize(nv);
  std::vector<Vector6d> tri_grad(static_cast<std::size_t>(nt));
  std::vector<Vec2> vert_grad(static_cast<std::size_t>(nv));
  std::vector<double> sums(static_cast<std::size_t>(block_count(nt, kTriangleBlock)) * k, 0.0);
  for_each_block(nt, kTriangleBlock, [&](int begin, int end, int b) {
    double* sum = &sums[static_cast<std::size_t>(b) * k];
    for (int t = begin; t < end; ++t) {
      const Eigen::Matrix2d J = jacobian_at(x, s.triangles[t], s.rest_inverse[t]);
      const double w = s.triangle_weight[t];
      // The weighted sum of the terms' derivatives, then one PSD projection of the element's
      // Hessian (projecting the sum keeps more curvature than summing projected terms).
      Eigen::Vector4d g_sum = Eigen::Vector4d::Zero();
      Eigen::Matrix4d h_sum = Eigen::Matrix4d::Zero();
      for (std::size_t j = 0; j < k; ++j) {
        Eigen::Vector4d g;
        Eigen::Matrix4d h;
        sum[j] += w * tt.energy[j](J, weights_, &g, &h);
        g_sum += tt.weight[j] * g;
        h_sum += tt.weight[j] * h;
      }
      const Eigen::Vector4d grad = w * g_sum;
      const Eigen::Matrix4d hess = project_psd_element(Eigen::Matrix4d(w * h_sum), J);
      const Eigen::Matrix<double, 4, 6> B = jacobian_map(s.rest_inverse[t]);
      tri_grad[t] = B.transpose() * grad;
      out.triangle_hessians[t] = B.transpose() * hess * B;
    }
  });
  MapEnergyTerms terms;
  terms.values.assign(map_energy_terms().size(), 0.0);
  add_block_sums(sums, tt.index, terms.values);
  const double descriptor_weight = weights_.*map_energy_terms()[tt.descriptor].weight;
  terms.values[tt.descriptor] = deterministic_sum(nv, kVertexBlock, [&](int v) {
    thread_local std::vector<double> scratch;
    scratch.resize(3 * static_cast<std::size_t>(d));
    const ScoreSample sample = vertex_score(v, x, true, scratch.data());
    const double w = descriptor_weight * s.vertex_weight[v];
    vert_grad[v] = -w * sample.gradient;
    out.vertex_hessians[v] = project_psd(Eigen::Matrix2d(-w * sample.hessian));
    return s.vertex_weight[v] * (1.0 - sample.score);
  });
  if (anchor_) terms.values[tt.anchor] = anchor_energy(x, &vert_grad, &out.vertex_hessians);
  terms.total = weighted_total(terms.values);
  out.terms = terms;
  // Gather in a fixed order (deterministic).
  out.gradient.setZero(2 * nv);
  for (int v = 0; v < nv; ++v) out.gradient.segment<2>(2 * v) += vert_grad[v];
  for (int t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c) out.gradient.segment<2>(2 * s.triangles[t][c]) += tri_grad[t].segment<2>(2 * c);
}

}  // namespace mcon
