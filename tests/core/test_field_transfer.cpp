// Per-vertex field transfer on synthetic flat disks with a known phi: exact properties only.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "transfer/field_transfer.h"
#include "known_maps.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

constexpr double kPi = 3.141592653589793;

Eigen::MatrixXd sample(const std::vector<Vec2>& uv, int dim) {
  Eigen::MatrixXd f(static_cast<Eigen::Index>(uv.size()), dim);
  for (std::size_t v = 0; v < uv.size(); ++v) f.row(static_cast<Eigen::Index>(v)) = synthetic::field(uv[v], dim).transpose();
  return f;
}

}  // namespace

TEST(FieldTransfer, IdentityMapTransfersEveryKindExactly) {
  const TriMesh disk = synthetic::make_jittered_disk(7, 0.3);
  const known::KnownMap m = known::make(disk, disk, [](const Vec2& p) { return p; });
  const MapView view = m.view();
  const int n = disk.num_vertices();

  for (std::uint8_t o : outside_mask(view)) EXPECT_EQ(o, 0);

  const Eigen::MatrixXd f = sample(m.source_uv, 3);
  const Eigen::MatrixXd g = transfer_interpolated(view, f);
  ASSERT_EQ(g.rows(), n);
  EXPECT_LE((g - f).cwiseAbs().maxCoeff(), 1e-12);

  std::vector<std::int32_t> labels(2 * n);
  for (int v = 0; v < 2 * n; ++v) labels[v] = (v * 7919) % 23 - 11;
  EXPECT_EQ(transfer_labels(view, 2, labels, -99), labels);

  std::vector<Vec3> t(n);
  for (int v = 0; v < n; ++v) t[v] = Vec3(std::cos(0.3 * v), std::sin(0.3 * v), 0) * (1 + 0.1 * (v % 5));
  const std::vector<Vec3> u = transfer_tangent_vectors(view, t);
  for (int v = 0; v < n; ++v) EXPECT_LE((u[v] - t[v]).norm(), 1e-9) << v;
}

TEST(FieldTransfer, InterpolationIsExactForAffineFieldsUnderASimilarity) {
  // phi = 0.2 + 0.8 R(0.7): every target vertex inside the image has the preimage
  // phi^-1(w), and an affine field of the flat source reproduces exactly.
  const auto psi = known::similarity(0.7, 0.8, Vec2(0.1, -0.05));
  const known::KnownMap m = known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(9, 0.35), psi);
  const MapView view = m.view();
  Eigen::MatrixXd f(m.source.num_vertices(), 2);
  for (int v = 0; v < m.source.num_vertices(); ++v)
    f.row(v) << 2 * m.source_uv[v].x() - m.source_uv[v].y() + 0.5, 3 * m.source_uv[v].y();
  const Eigen::MatrixXd g = transfer_interpolated(view, f);
  const std::vector<std::uint8_t> mask = outside_mask(view);
  const double c = std::cos(0.7), s = std::sin(0.7);
  int inside = 0;
  for (int w = 0; w < m.target.num_vertices(); ++w) {
    if (mask[w]) {
      EXPECT_EQ(g.row(w).cwiseAbs().maxCoeff(), 0.0);
      continue;
    }
    ++inside;
    const Vec2 q = (m.target_uv[w] - Vec2(0.1, -0.05)) / 0.8;
    const Vec2 p(c * q.x() + s * q.y(), -s * q.x() + c * q.y());  // R^-1 q
    EXPECT_NEAR(g(w, 0), 2 * p.x() - p.y() + 0.5, 1e-10);
    EXPECT_NEAR(g(w, 1), 3 * p.y(), 1e-10);
  }
  EXPECT_GT(inside, m.target.num_vertices() / 3);
}

TEST(FieldTransfer, LabelsAreNeverBlended) {
  const known::KnownMap m =
      known::make(test_meshes::make_disk(5), synthetic::make_jittered_disk(9, 0.35), known::similarity(0.3, 0.9, Vec2(0.15, 0)));
  const MapView view = m.view();
  const int n = m.source.num_vertices();
  std::vector<std::int32_t> labels(3 * n);
  for (int v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) labels[3 * v + c] = 1000 * c + v;  // unique per vertex: a blend would show
  const std::vector<std::int32_t> out = transfer_labels(view, 3, labels, -1);
  int inside = 0, outside = 0;
  for (int w = 0; w < m.target.num_vertices(); ++w) {
    const SurfacePoint& p = m.c.target_to_source[w];
    if (p.triangle < 0) {
      ++outside;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(out[3 * w + c], -1);
      continue;
    }
    ++inside;
    const Tri& t = m.source.triangles[p.triangle];
    int best = 0;
    for (int k = 1; k < 3; ++k)
      if (p.barycentric[k] > p.barycentric[best]) best = k;
    const int v = out[3 * w];
    EXPECT_EQ(v, t[best]);  // the dominant corner's label, one of the triangle's own
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out[3 * w + c], 1000 * c + v);
  }
  EXPECT_GT(inside, 0);
  EXPECT_GT(outside, 0);  // the shifted, shrunk image leaves the target's left rim uncovered
}

TEST(FieldTransfer, RotatedMapRotatesTangentVectorsAndKeepsTheirLength) {
  const double angle = 0.9;
  const known::KnownMap m = known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(8, 0.3),
                                        known::similarity(angle, 0.6, Vec2::Zero()));
  const int n = m.source.num_vertices();
  std::vector<Vec3> t(n);
  for (int v = 0; v < n; ++v) t[v] = Vec3(0.5 + 0.1 * m.source_uv[v].y(), -0.2, 0.0);  // varies, but affine
  const std::vector<Vec3> u = transfer_tangent_vectors(m.view(), t);
  const double c = std::cos(angle), s = std::sin(angle);
  int checked = 0;
  for (int w = 0; w < m.target.num_vertices(); ++w) {
    const SurfacePoint& p = m.c.target_to_source[w];
    if (p.triangle < 0) {
      EXPECT_EQ(u[w].norm(), 0.0);
      continue;
    }
    const Vec2 q = m.target_uv[w] / 0.6;
    const Vec2 pre(c * q.x() + s * q.y(), -s * q.x() + c * q.y());
    const Vec3 src(0.5 + 0.1 * pre.y(), -0.2, 0.0);
    const Vec3 expected(c * src.x() - s * src.y(), s * src.x() + c * src.y(), 0.0);
    EXPECT_LE((u[w] - expected).norm(), 1e-9) << w;
    ++checked;
  }
  EXPECT_GT(checked, m.target.num_vertices() / 4);
}

TEST(FieldTransfer, MirroredMapMirrorsTangentVectors) {
  const known::KnownMap m = known::make(test_meshes::make_disk(5), synthetic::make_jittered_disk(7, 0.3),
                                        known::similarity(0.0, 0.9, Vec2::Zero(), true));
  EXPECT_EQ(count_phi_flips(m.source, m.phi, true), 0);
  EXPECT_EQ(count_phi_flips(m.source, m.phi, false), m.source.num_triangles());
  const std::vector<Vec3> t(m.source.positions.size(), Vec3(0.3, 0.4, 0));
  const std::vector<Vec3> u = transfer_tangent_vectors(m.view(), t);
  for (int w = 0; w < m.target.num_vertices(); ++w)
    if (m.c.target_to_source[w].triangle >= 0) {
      EXPECT_LE((u[w] - Vec3(0.3, -0.4, 0)).norm(), 1e-9) << w;
    }
}

TEST(FieldTransfer, TangentVectorsLandInTheCurvedTargetsTangentPlanes) {
  const known::KnownMap m =
      known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(8, 0.3), known::similarity(0.4, 0.8, Vec2::Zero()),
                  [](double x, double y) { return 0.4 * x * x - 0.3 * y * y + 0.2 * x * y; });
  const int n = m.source.num_vertices();
  std::vector<Vec3> t(n);
  for (int v = 0; v < n; ++v) t[v] = Vec3(std::cos(2.0 * m.source_uv[v].x()), 1.0, 0.0);
  const std::vector<Vec3> u = transfer_tangent_vectors(m.view(), t);
  const std::vector<Vec3> normals = vertex_normals(m.target);
  int checked = 0;
  for (int w = 0; w < m.target.num_vertices(); ++w) {
    const SurfacePoint& p = m.c.target_to_source[w];
    if (p.triangle < 0) continue;
    const Tri& s = m.source.triangles[p.triangle];
    const Vec3 v = p.barycentric[0] * t[s[0]] + p.barycentric[1] * t[s[1]] + p.barycentric[2] * t[s[2]];
    EXPECT_NEAR(u[w].norm(), v.norm(), 1e-9) << w;        // length kept
    EXPECT_LE(std::abs(u[w].dot(normals[w])), 1e-9) << w;  // tangent to the target
    // On a gentle height field the lifted direction projects back to the rotated planar one.
    const double c = std::cos(0.4), sn = std::sin(0.4);
    const Vec2 planar(c * v.x() - sn * v.y(), sn * v.x() + c * v.y());
    EXPECT_GT(u[w].head<2>().normalized().dot(planar.normalized()), 0.9) << w;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(FieldTransfer, TargetVerticesWithoutPreimageAreMaskedAndZero) {
  const Vec2 shift(0.55, 0.0);
  const known::KnownMap m = known::make(test_meshes::make_disk(6), synthetic::make_jittered_disk(8, 0.3),
                                        known::similarity(0.0, 1.0, shift));
  const std::vector<std::uint8_t> mask = outside_mask(m.view());
  const Eigen::MatrixXd f = Eigen::MatrixXd::Constant(m.source.num_vertices(), 1, 5.0);
  const Eigen::MatrixXd g = transfer_interpolated(m.view(), f);
  int outside = 0;
  for (int w = 0; w < m.target.num_vertices(); ++w) {
    const double d = (m.target_uv[w] - shift).norm();
    if (d > 1.0 + 1e-6) {
      EXPECT_EQ(mask[w], 1) << w;
    }
    if (d < 0.97) {
      EXPECT_EQ(mask[w], 0) << w;
    }
    EXPECT_EQ(mask[w], m.c.target_to_source[w].triangle < 0 ? 1 : 0);
    EXPECT_DOUBLE_EQ(g(w, 0), mask[w] ? 0.0 : 5.0);
    outside += mask[w];
  }
  EXPECT_GT(outside, 10);
}

TEST(FieldTransfer, BadInputIsRejected) {
  const known::KnownMap m = known::make(test_meshes::make_disk(3), test_meshes::make_disk(3), [](const Vec2& p) { return p; });
  const MapView view = m.view();
  const int n = m.source.num_vertices();
  EXPECT_EQ(status_of([&] { transfer_interpolated(view, Eigen::MatrixXd::Zero(n + 1, 1)); }), MCON_ERROR_INVALID_ARGUMENT);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Zero(n, 2);
  nan(3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(status_of([&] { transfer_interpolated(view, nan); }), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(status_of([&] { transfer_labels(view, 0, {}, 0); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { transfer_labels(view, 2, std::vector<std::int32_t>(n), 0); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { transfer_tangent_vectors(view, std::vector<Vec3>(n - 1, Vec3::Zero())); }),
            MCON_ERROR_INVALID_ARGUMENT);
  std::vector<Vec3> t(n, Vec3::Zero());
  t[0].x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(status_of([&] { transfer_tangent_vectors(view, t); }), MCON_ERROR_NON_FINITE);
  const std::vector<Vec2> short_phi(2, Vec2::Zero());
  const MapView broken{m.source, m.source_uv, m.target, m.target_uv, short_phi, m.c.source_to_target, m.c.target_to_source};
  EXPECT_EQ(status_of([&] { outside_mask(broken); }), MCON_ERROR_INVALID_ARGUMENT);
}
