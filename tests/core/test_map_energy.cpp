#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "base/counter_rng.h"
#include "map/descriptor_field_2d.h"
#include "base/error.h"
#include "map/injective_step.h"
#include "map/map_energy.h"
#include "map/matching_score.h"
#include "synthetic_maps.h"

using namespace mcon;

namespace {

using ElementEnergy = std::function<double(const Eigen::Matrix2d&, Eigen::Vector4d*, Eigen::Matrix4d*)>;

Eigen::Matrix2d from_vec(const Eigen::Vector4d& v) {
  Eigen::Matrix2d J;
  J << v[0], v[1], v[2], v[3];
  return J;
}

// Central differences of value -> gradient and gradient -> Hessian at J.
void check_element_derivatives(const ElementEnergy& f, const Eigen::Matrix2d& J) {
  Eigen::Vector4d g;
  Eigen::Matrix4d h;
  f(J, &g, &h);
  const Eigen::Vector4d j(J(0, 0), J(0, 1), J(1, 0), J(1, 1));
  const double eps = 1e-6;
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector4d jp = j, jm = j;
    jp[i] += eps;
    jm[i] -= eps;
    const double fd = (f(from_vec(jp), nullptr, nullptr) - f(from_vec(jm), nullptr, nullptr)) / (2 * eps);
    EXPECT_NEAR(g[i], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "gradient " << i;
    Eigen::Vector4d gp, gm;
    f(from_vec(jp), &gp, nullptr);
    f(from_vec(jm), &gm, nullptr);
    const Eigen::Vector4d hd = (gp - gm) / (2 * eps);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(h(k, i), hd[k], 1e-5 * std::max(1.0, std::abs(hd[k]))) << "hessian " << k << "," << i;
  }
}

Eigen::Matrix2d rotation(double a) {
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return R;
}

}  // namespace

TEST(MapEnergy, ElementEnergiesVanishWhereTheyShouldAndBlockInversion) {
  const Eigen::Matrix2d similarity = 1.7 * rotation(0.4);
  EXPECT_NEAR(conformal_distortion(similarity, nullptr, nullptr), 0.0, 1e-14);
  EXPECT_NEAR(area_distortion(rotation(1.1), nullptr, nullptr), 0.0, 1e-14);
  EXPECT_GT(area_distortion(similarity, nullptr, nullptr), 0.1);
  EXPECT_EQ(injectivity_barrier(similarity, 0.5, nullptr, nullptr), 0.0);
  Eigen::Matrix2d shear;
  shear << 1, 0.5, 0, 1;
  EXPECT_GT(conformal_distortion(shear, nullptr, nullptr), 0.1);
  EXPECT_GT(injectivity_barrier(0.5 * Eigen::Matrix2d::Identity(), 0.5, nullptr, nullptr), 0.0);
  Eigen::Matrix2d mirror;
  mirror << 1, 0, 0, -1;
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(conformal_distortion(mirror, nullptr, nullptr), inf);
  EXPECT_EQ(area_distortion(mirror, nullptr, nullptr), inf);
  EXPECT_EQ(injectivity_barrier(Eigen::Matrix2d::Zero(), 0.5, nullptr, nullptr), inf);
  // The barrier is C1 where it starts (det = s_f): value and gradient tend to 0 from below.
  Eigen::Vector4d g;
  const double below = injectivity_barrier(std::sqrt(0.5 * (1 - 1e-6)) * Eigen::Matrix2d::Identity(), 0.5, &g, nullptr);
  EXPECT_LT(below, 1e-11);
  EXPECT_LT(g.norm(), 1e-5);
}

TEST(MapEnergy, ElementDerivativesMatchFiniteDifferences) {
  CounterRng rng(11, 0);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix2d J = Eigen::Matrix2d::Identity();
    for (int i = 0; i < 4; ++i) J(i / 2, i % 2) += 0.6 * (rng.uniform() - 0.5);
    if (J.determinant() < 0.2) continue;
    check_element_derivatives(conformal_distortion, J);
    check_element_derivatives(area_distortion, J);
    // Scale into the barrier's support (det below s_f = 0.5).
    check_element_derivatives([](const Eigen::Matrix2d& A, Eigen::Vector4d* gg, Eigen::Matrix4d* hh) {
      return injectivity_barrier(A, 0.5, gg, hh);
    }, J * std::sqrt(0.3 / J.determinant()));
  }
}

TEST(MapEnergy, TheSvdRotationsReconstructJ) {
  CounterRng rng(5, 0);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix2d J;
    for (int i = 0; i < 4; ++i) J(i / 2, i % 2) = 4 * (rng.uniform() - 0.5);
    Eigen::Matrix2d U, Vt;
    rotations_of_svd(J, U, Vt);
    const Eigen::Matrix2d S = U.transpose() * J * Vt.transpose();
    EXPECT_NEAR(S(0, 1), 0, 1e-12) << J;
    EXPECT_NEAR(S(1, 0), 0, 1e-12) << J;
    EXPECT_GE(S(0, 0), std::abs(S(1, 1)) - 1e-12) << J;
    EXPECT_NEAR(U.determinant(), 1, 1e-12);
    EXPECT_NEAR(Vt.determinant(), 1, 1e-12);
  }
}

TEST(MapEnergy, TwoByTwoProjectionMatchesTheEigendecomposition) {
  CounterRng rng(9, 0);
  int cases[3] = {0, 0, 0};  // kept as is, one eigenvalue clamped, both clamped
  for (int trial = 0; trial < 600; ++trial) {
    Eigen::Matrix2d h;
    h(0, 0) = 4 * (rng.uniform() - 0.5);
    h(1, 1) = 4 * (rng.uniform() - 0.5);
    h(0, 1) = h(1, 0) = 2 * (rng.uniform() - 0.5);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(h);
    const Eigen::Vector2d ev = es.eigenvalues();
    const Eigen::Matrix2d expected = es.eigenvectors() * ev.cwiseMax(0.0).asDiagonal() * es.eigenvectors().transpose();
    const Eigen::Matrix2d p = project_psd(h);
    EXPECT_LE((p - expected).cwiseAbs().maxCoeff(), 1e-12) << h;
    ++cases[(ev[0] < 0) + (ev[1] < 0)];
    if (ev.minCoeff() >= 0) {
      EXPECT_EQ(p, h);  // untouched, bit for bit
    }
  }
  for (int n : cases) EXPECT_GT(n, 50);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(project_psd(Eigen::Matrix2d(Eigen::Matrix2d::Constant(nan))).array().isNaN().all());
}

// The closed-form projection of the weighted element Hessian (every term isotropic) equals the
// eigendecomposition's, on Jacobians near and far from the identity, near-conformal ones
// (s1 = s2) and ones inside the barrier; a Hessian that is not isotropic is refused unchanged.
TEST(MapEnergy, IsotropicProjectionMatchesTheEigendecomposition) {
  CounterRng rng(7, 0);
  int indefinite = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Eigen::Matrix2d J = rotation(6 * rng.uniform()) * Eigen::Vector2d(0.2 + 2 * rng.uniform(), 0.2 + 2 * rng.uniform()).asDiagonal() *
                        rotation(6 * rng.uniform());
    if (trial % 4 == 0) J = (0.3 + rng.uniform()) * rotation(6 * rng.uniform());  // conformal: s1 = s2
    Eigen::Vector4d g;
    Eigen::Matrix4d h1, h2, h3;
    conformal_distortion(J, &g, &h1);
    area_distortion(J, &g, &h2);
    injectivity_barrier(J, 2.0, &g, &h3);
    const Eigen::Matrix4d h = h1 + 0.5 * h2 + 0.01 * h3;
    Eigen::Matrix4d p = h;
    ASSERT_TRUE(project_psd_isotropic(J, p)) << J;
    const Eigen::Matrix4d expected = project_psd(h);
    EXPECT_LE((p - expected).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, h.cwiseAbs().maxCoeff())) << J;
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(p).eigenvalues().minCoeff(), -1e-9 * h.norm());
    EXPECT_LE((project_psd_element(h, J) - expected).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, h.cwiseAbs().maxCoeff()));
    indefinite += Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(h).eigenvalues().minCoeff() < 0;
  }
  EXPECT_GT(indefinite, 50);  // the comparison covered projections that clamp
  Eigen::Matrix4d a;
  for (int i = 0; i < 16; ++i) a(i / 4, i % 4) = rng.uniform() - 0.5;
  const Eigen::Matrix4d not_isotropic = a + a.transpose();
  Eigen::Matrix4d p = not_isotropic;
  EXPECT_FALSE(project_psd_isotropic(rotation(0.3) * Eigen::Vector2d(1.5, 0.7).asDiagonal(), p));
  EXPECT_EQ(p, not_isotropic);
  EXPECT_LE((project_psd_element(not_isotropic, Eigen::Matrix2d::Identity()) - project_psd(not_isotropic)).norm(), 0);
}

TEST(MapEnergy, JacobianMapIsTheDerivativeOfJ) {
  Eigen::Matrix2d rest;
  rest << 1.0, 0.2, 0.1, 0.9;
  const Eigen::Matrix2d D = rest.inverse();
  const Eigen::Matrix<double, 4, 6> B = jacobian_map(D);
  Vector6d q;
  q << 0.1, 0.2, 1.3, 0.1, 0.3, 1.1;
  auto J = [&](const Vector6d& y) {
    Eigen::Matrix2d X;
    X << y[2] - y[0], y[4] - y[0], y[3] - y[1], y[5] - y[1];
    const Eigen::Matrix2d M = X * D;
    return Eigen::Vector4d(M(0, 0), M(0, 1), M(1, 0), M(1, 1));
  };
  // J is linear in q: J(q) = B q exactly.
  EXPECT_LT((J(q) - B * q).norm(), 1e-12);
}

TEST(MapEnergy, TotalGradientMatchesFiniteDifferencesAndHessiansArePsd) {
  synthetic::GroundTruth truth;
  truth.angle = 0.3;
  truth.warp = 0.05;
  const synthetic::Problem pr = synthetic::make_problem(6, 5, truth, 2, {0.0});
  const TriangleLocator2D locator(pr.target_uv, pr.target.triangles);
  const DescriptorField2D field(locator, pr.target_levels[0]);
  for (bool reflected : {false, true}) {
    for (OutsideRule rule : {OutsideRule::zero, OutsideRule::nearest_rim}) {
      const SourceDisk disk = make_source_disk(pr.source, pr.source_uv, reflected);
      ScoreSettings score;
      score.sigma = 0.3;
      score.band = 0.2;
      score.outside = rule;
      MapEnergyWeights w;
      w.barrier_start = 0.9;  // make the barrier active somewhere
      const MapEnergy energy(disk, field, pr.source_levels[0], score, w);
      // A smooth deformation of the (mirrored) rest positions, reaching beyond the rim.
      const std::vector<Vec2> rest = rest_positions(pr.source_uv, reflected);
      Eigen::VectorXd x(2 * rest.size());
      for (std::size_t v = 0; v < rest.size(); ++v) {
        const Vec2 p = rest[v];
        x.segment<2>(2 * v) = 1.05 * rotation(0.3) * p + Vec2(0.05 * std::sin(3 * p.y()), 0.04 * p.x() * p.x()) + Vec2(0.02, 0.01);
      }
      ASSERT_EQ(count_inverted(disk.triangles, x), 0);
      MapEnergy::Derivatives der;
      energy.derivatives(x, der);
      EXPECT_DOUBLE_EQ(der.terms.total, energy.evaluate(x).total);
      const double eps = 1e-7;
      int checked = 0;
      for (int i = 0; i < x.size(); i += 3) {
        Eigen::VectorXd xp = x, xm = x;
        xp[i] += eps;
        xm[i] -= eps;
        const double fd = (energy.evaluate(xp).total - energy.evaluate(xm).total) / (2 * eps);
        // Kinks of the piecewise-linear field (target edges) can sit within eps; allow a few.
        if (std::abs(der.gradient[i] - fd) > 1e-5 * std::max(1.0, std::abs(fd))) continue;
        ++checked;
      }
      EXPECT_GT(checked, 0.95 * (x.size() / 3)) << "reflected " << reflected;
      for (const Matrix6d& h : der.triangle_hessians)
        EXPECT_GE(Eigen::SelfAdjointEigenSolver<Matrix6d>(h).eigenvalues().minCoeff(), -1e-12);
      for (const Eigen::Matrix2d& h : der.vertex_hessians)
        EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(h).eigenvalues().minCoeff(), -1e-12);
    }
  }
}

TEST(MapEnergy, MatchScoreGradientAndRules) {
  const TriMesh m = synthetic::make_jittered_disk(8, 0.3);
  const std::vector<Vec2> uv = synthetic::planar_uv(m);
  Eigen::MatrixXd values(m.num_vertices(), 2);
  for (int v = 0; v < m.num_vertices(); ++v) values.row(v) = synthetic::field(uv[v], 2).transpose();
  const TriangleLocator2D locator(uv, m.triangles);
  const DescriptorField2D field(locator, values);
  const double source[2] = {0.3, -0.1};
  double scratch[6];
  ScoreSettings s;
  s.sigma = 0.4;
  s.band = 0.1;
  // zero rule: 0 beyond the circle; nearest_rim: equal to the rim value radially outward.
  EXPECT_EQ(match_score(field, source, Vec2(1.2, 0.3), s, false, scratch).score, 0.0);
  s.outside = OutsideRule::nearest_rim;
  const double far = match_score(field, source, Vec2(1.2, 0.3) * 1.5, s, false, scratch).score;
  EXPECT_NEAR(far, match_score(field, source, Vec2(1.2, 0.3), s, false, scratch).score, 1e-12);
  EXPECT_GT(far, 0.0);
  for (OutsideRule rule : {OutsideRule::zero, OutsideRule::nearest_rim}) {
    s.outside = rule;
    for (const Vec2& x : {Vec2(0.2, 0.31), Vec2(-0.5, 0.7), Vec2(0.93, 0.05), Vec2(1.3, -0.4)}) {
      const ScoreSample a = match_score(field, source, x, s, true, scratch);
      const double eps = 1e-7;
      for (int i = 0; i < 2; ++i) {
        Vec2 xp = x, xm = x;
        xp[i] += eps;
        xm[i] -= eps;
        const double fd = (match_score(field, source, xp, s, false, scratch).score -
                           match_score(field, source, xm, s, false, scratch).score) / (2 * eps);
        EXPECT_NEAR(a.gradient[i], fd, 1e-5) << x.transpose();
      }
    }
  }
}

TEST(InjectiveStep, FirstInversionIsFound) {
  EXPECT_EQ(smallest_positive_root(0, 1, 1), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(smallest_positive_root(0, -2, 1), 0.5, 1e-15);
  EXPECT_NEAR(smallest_positive_root(1, -3, 2), 1.0, 1e-15);   // roots 1, 2
  EXPECT_NEAR(smallest_positive_root(-1, 0, 4), 2.0, 1e-15);   // roots -2, 2
  EXPECT_EQ(smallest_positive_root(1, 1, 1), std::numeric_limits<double>::infinity());
  const TriMesh m = test_meshes::make_disk(5);
  Eigen::VectorXd x(2 * m.num_vertices()), d(2 * m.num_vertices());
  CounterRng rng(2, 0);
  for (int v = 0; v < m.num_vertices(); ++v) {
    x.segment<2>(2 * v) = m.positions[v].head<2>();
    d.segment<2>(2 * v) = Vec2(rng.uniform() - 0.5, rng.uniform() - 0.5);
  }
  const double t = max_injective_step(m.triangles, x, d);
  ASSERT_TRUE(std::isfinite(t));
  EXPECT_EQ(count_inverted(m.triangles, x + 0.999 * t * d), 0);
  EXPECT_GT(count_inverted(m.triangles, x + 1.001 * t * d), 0);
}

TEST(MapEnergy, SourceDiskRejectsBadInput) {
  const TriMesh m = test_meshes::make_disk(3);
  std::vector<Vec2> uv = synthetic::planar_uv(m);
  EXPECT_NO_THROW(make_source_disk(m, uv, false));
  std::vector<Vec2> flipped = uv;
  for (Vec2& p : flipped) p.y() = -p.y();
  try {
    make_source_disk(m, flipped, false);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_INVALID_ARGUMENT);
  }
  uv.pop_back();
  EXPECT_THROW(make_source_disk(m, uv, false), Error);
}

namespace {

TEST(MapEnergy, TermTableNamesEachTermOnceWithTheDescriptorFirst) {
  const std::vector<MapEnergyTerm>& terms = map_energy_terms();
  ASSERT_GE(terms.size(), 4u);
  EXPECT_STREQ(terms[0].name, "descriptor");
  EXPECT_EQ(terms[0].triangle_energy, nullptr);
  EXPECT_EQ(terms[0].domain, MapTermDomain::descriptor);
  for (std::size_t i = 0; i < terms.size(); ++i) {
    EXPECT_EQ(map_energy_term_index(terms[i].name), static_cast<int>(i));
    // Exactly the triangle terms have a triangle energy.
    EXPECT_EQ(terms[i].triangle_energy != nullptr, terms[i].domain == MapTermDomain::triangle) << terms[i].name;
  }
  for (const char* name : {"distortion", "area", "injectivity"}) EXPECT_GE(map_energy_term_index(name), 1) << name;
  // The anchor came after the first four: their indices (the C API's term order) stay.
  EXPECT_EQ(map_energy_term_index("anchor"), 4);
  EXPECT_EQ(map_energy_term_index("bogus"), -1);
}

TEST(MapEnergy, TotalIsTheWeightedSumOfTheTermValues) {
  synthetic::GroundTruth truth;
  truth.angle = 0.2;
  const synthetic::Problem pr = synthetic::make_problem(6, 5, truth, 2, {0.0});
  const TriangleLocator2D locator(pr.target_uv, pr.target.triangles);
  const DescriptorField2D field(locator, pr.target_levels[0]);
  const SourceDisk disk = make_source_disk(pr.source, pr.source_uv, false);
  ScoreSettings score;
  score.sigma = 0.3;
  MapEnergyWeights w;
  w.descriptor = 0.7;
  w.distortion = 0.2;
  w.area = 0.3;
  w.injectivity = 0.05;
  w.barrier_start = 0.9;
  const MapEnergy energy(disk, field, pr.source_levels[0], score, w);
  Eigen::VectorXd x(2 * pr.source_uv.size());
  for (std::size_t v = 0; v < pr.source_uv.size(); ++v) x.segment<2>(2 * v) = 0.8 * rotation(0.2) * pr.source_uv[v];
  const MapEnergyTerms t = energy.evaluate(x);
  ASSERT_EQ(t.values.size(), map_energy_terms().size());
  double expected = 0;
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    EXPECT_TRUE(std::isfinite(t.values[i])) << map_energy_terms()[i].name;
    expected += w.*map_energy_terms()[i].weight * t.values[i];
  }
  EXPECT_NEAR(t.total, expected, 1e-12 * std::max(1.0, std::abs(expected)));
  EXPECT_GT(t.value("area"), 0);  // the disk was shrunk to 0.8: the area term sees it
  EXPECT_EQ(t.value("descriptor"), t.values[0]);
  EXPECT_THROW(t.value("bogus"), Error);
}

TEST(MapEnergy, AnchorTermIsTheWeightedSquaredDistanceToItsPositions) {
  synthetic::GroundTruth truth;
  truth.angle = 0.2;
  const synthetic::Problem pr = synthetic::make_problem(6, 5, truth, 2, {0.0});
  const TriangleLocator2D locator(pr.target_uv, pr.target.triangles);
  const DescriptorField2D field(locator, pr.target_levels[0]);
  const SourceDisk disk = make_source_disk(pr.source, pr.source_uv, false);
  ScoreSettings score;
  score.sigma = 0.3;
  const int n = disk.num_vertices;
  MapAnchor anchor;
  for (int v = 0; v < n; ++v) {
    anchor.position.push_back(rotation(0.25) * pr.source_uv[v] + Vec2(0.03, -0.02));
    anchor.weight.push_back(v % 3 == 0 ? 0.0 : (v % 3 == 1 ? 1.0 : 0.5));
  }
  Eigen::VectorXd x(2 * n);
  for (int v = 0; v < n; ++v) x.segment<2>(2 * v) = 0.9 * rotation(0.2) * pr.source_uv[v];
  MapEnergyWeights off;
  MapEnergyWeights on = off;
  on.anchor = 2.5;
  // Weight 0 (the default): the term is 0 and the total is what it was without an anchor.
  const MapEnergyTerms t_off = MapEnergy(disk, field, pr.source_levels[0], score, off, &anchor).evaluate(x);
  const MapEnergyTerms t_none = MapEnergy(disk, field, pr.source_levels[0], score, off).evaluate(x);
  EXPECT_EQ(t_off.value("anchor"), 0.0);
  EXPECT_EQ(t_off.total, t_none.total);
  // E_p = sum_v A_v m_v |x_v - p_v|^2, added with its weight.
  const MapEnergy energy(disk, field, pr.source_levels[0], score, on, &anchor);
  const MapEnergyTerms t = energy.evaluate(x);
  double expected = 0;
  for (int v = 0; v < n; ++v)
    expected += disk.vertex_weight[v] * anchor.weight[v] * (x.segment<2>(2 * v) - anchor.position[v]).squaredNorm();
  EXPECT_NEAR(t.value("anchor"), expected, 1e-14);
  EXPECT_GT(expected, 0);
  EXPECT_NEAR(t.total, t_none.total + on.anchor * expected, 1e-12);
  // Its gradient and Hessian: the difference of the derivatives with and without it.
  MapEnergy::Derivatives d_on, d_off;
  energy.derivatives(x, d_on);
  MapEnergy(disk, field, pr.source_levels[0], score, off).derivatives(x, d_off);
  for (int v = 0; v < n; ++v) {
    const double w = 2 * on.anchor * disk.vertex_weight[v] * anchor.weight[v];
    const Vec2 g = d_on.gradient.segment<2>(2 * v) - d_off.gradient.segment<2>(2 * v);
    EXPECT_NEAR((g - w * (x.segment<2>(2 * v) - anchor.position[v])).norm(), 0, 1e-12) << v;
    EXPECT_NEAR((d_on.vertex_hessians[v] - d_off.vertex_hessians[v] - w * Eigen::Matrix2d::Identity()).norm(), 0,
                1e-12) << v;
  }
  // At its positions the term vanishes.
  Eigen::VectorXd at(2 * n);
  for (int v = 0; v < n; ++v) at.segment<2>(2 * v) = anchor.position[v];
  EXPECT_EQ(energy.evaluate(at).value("anchor"), 0.0);
  // A weight without positions, or with the wrong count, or a negative weight: INVALID_ARGUMENT.
  EXPECT_THROW(MapEnergy(disk, field, pr.source_levels[0], score, on), Error);
  MapAnchor short_anchor = anchor;
  short_anchor.position.pop_back();
  EXPECT_THROW(MapEnergy(disk, field, pr.source_levels[0], score, on, &short_anchor), Error);
  MapEnergyWeights negative = off;
  negative.anchor = -1;
  EXPECT_THROW(MapEnergy(disk, field, pr.source_levels[0], score, negative, &anchor), Error);
}

}  // namespace
