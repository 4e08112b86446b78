// Curvature descriptors against exact curvatures. Every test prints what it measured
// ("[measured] ..."); the bounds sit about 1.5x-3x above those numbers, so they hold across
// compilers but catch a sign, factor-2, scale or smoothing-time regression.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "operators/cotan_laplacian.h"
#include "descriptors/curvature_descriptors.h"
#include "base/error.h"
#include "patch/geodesic_disk_patch.h"
#include "io/mesh_io.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

const double kSigmas[3] = {0.025, 0.05, 0.1};

struct ErrorStats {
  double mean = 0;  // mean absolute error
  double max = 0;   // largest absolute error
  int count = 0;
};

// |value - expected| over the vertices where use(v) holds, divided by `scale`.
ErrorStats errors(
    const Eigen::VectorXd& value, const std::function<double(int)>& expected, double scale = 1.0,
    const std::function<bool(int)>& use = [](int) { return true; }) {
  ErrorStats s;
  for (int v = 0; v < value.size(); ++v) {
    if (!use(v)) continue;
    const double err = std::abs(value[v] - expected(v)) / scale;
    s.mean += err;
    s.max = std::max(s.max, err);
    ++s.count;
  }
  if (s.count) s.mean /= s.count;
  return s;
}

ErrorStats errors_to(
    const Eigen::VectorXd& value, double expected, double scale = 1.0,
    const std::function<bool(int)>& use = [](int) { return true; }) {
  return errors(
      value, [expected](int) { return expected; }, scale, use);
}

ErrorStats report(const std::string& what, const ErrorStats& s) {
  std::printf("[measured] %-52s mean %.2e  max %.2e  (n = %d)\n", what.c_str(), s.mean, s.max, s.count);
  return s;
}

std::string label(const char* format, double a, double b = 0, double c = 0) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

// All three CURV9 scales from one call (one edge-tensor build, one ordering): kSigmas[s] is column
// block s, as Curv9LayoutAndMeanCurvatureDescriptor checks.
struct Scales {
  Eigen::MatrixXd curv9;
  Eigen::VectorXd gaussian(int s) const { return curv9.col(3 * s); }
  Eigen::VectorXd mean(int s) const { return curv9.col(3 * s + 1); }
  Eigen::VectorXd abs_max(int s) const { return curv9.col(3 * s + 2); }
};

Scales at_all_scales(const TriMesh& m, PatchBoundary boundary = PatchBoundary::kCutThroughTriangles) {
  return {curv9_descriptor(m, boundary)};
}

TriMesh flipped(TriMesh m) {
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// Graph z = f(x, y) over [-1, 1]^2 and its exact curvatures.
struct Graph {
  std::function<double(double, double)> f;
  std::function<Eigen::Vector2d(double, double)> grad;
  std::function<Eigen::Matrix2d(double, double)> hess;

  double mean(const Vec3& p) const {
    const Eigen::Vector2d g = grad(p.x(), p.y());
    const Eigen::Matrix2d h = hess(p.x(), p.y());
    const double w = 1 + g.squaredNorm();
    // Our sign: convex w.r.t. the upward (CCW) normal is positive, so a bowl z = x^2 + y^2 (which
    // curves towards its normal, like a sphere seen from inside) has H < 0.
    return -((1 + g.y() * g.y()) * h(0, 0) - 2 * g.x() * g.y() * h(0, 1) + (1 + g.x() * g.x()) * h(1, 1)) /
           (2 * std::pow(w, 1.5));
  }
  double gaussian(const Vec3& p) const {
    const Eigen::Vector2d g = grad(p.x(), p.y());
    const double w = 1 + g.squaredNorm();
    return hess(p.x(), p.y()).determinant() / (w * w);
  }
  TriMesh mesh(int n, double jitter) const {
    TriMesh m = test_meshes::make_grid(n, 2.0, jitter);
    for (Vec3& p : m.positions) {
      p.x() -= 1;
      p.y() -= 1;
      p.z() = f(p.x(), p.y());
    }
    return m;
  }
};

// Saddle 0.5 * (u^2 - w^2) in axes rotated by 30 degrees (not aligned with the grid).
Graph saddle() {
  const double c = std::cos(0.5236), s = std::sin(0.5236);
  Eigen::Matrix2d r;
  r << c, s, -s, c;
  const Eigen::Matrix2d h = r.transpose() * Eigen::Vector2d(1.0, -1.0).asDiagonal() * r;
  return {[h](double x, double y) { return 0.5 * Eigen::Vector2d(x, y).dot(h * Eigen::Vector2d(x, y)); },
          [h](double x, double y) { return Eigen::Vector2d(h * Eigen::Vector2d(x, y)); },
          [h](double, double) { return h; }};
}

// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 (a scaled icosphere) and its exact curvatures.
struct Ellipsoid {
  double a, b, c;
  TriMesh mesh(int subdivisions) const {
    TriMesh m = test_meshes::make_icosphere(subdivisions);
    for (Vec3& p : m.positions) p = Vec3(a * p.x(), b * p.y(), c * p.z());
    return m;
  }
  double h(const Vec3& p) const {
    return std::sqrt(p.x() * p.x() / std::pow(a, 4) + p.y() * p.y() / std::pow(b, 4) + p.z() * p.z() / std::pow(c, 4));
  }
  double gaussian(const Vec3& p) const { return 1 / (a * a * b * b * c * c * std::pow(h(p), 4)); }
  double mean(const Vec3& p) const {
    return (a * a + b * b + c * c - p.squaredNorm()) / (2 * a * a * b * b * c * c * std::pow(h(p), 3));
  }
};

// The part where f <= 0, cut exactly along the iso-line f = 0 as extract_geodesic_disk does;
// crossings within 20% of an edge end snap onto that vertex (no slivers).
TriMesh cut_exactly(const TriMesh& m, const std::function<double(const Vec3&)>& f) {
  const double snap = 0.2;
  std::vector<double> value(m.positions.size());
  for (std::size_t v = 0; v < value.size(); ++v) value[v] = f(m.positions[v]);
  for (const Tri& tri : m.triangles)
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      if (value[a] == 0 || value[b] == 0 || (value[a] < 0) == (value[b] < 0)) continue;
      const double t = value[a] / (value[a] - value[b]);
      if (t < snap)
        value[a] = 0;
      else if (t > 1 - snap)
        value[b] = 0;
    }
  TriMesh out;
  out.positions = m.positions;
  std::map<std::pair<int, int>, int> crossing_of;
  auto crossing = [&](int a, int b) {
    if (value[a] == 0) return a;
    if (value[b] == 0) return b;
    const auto key = std::minmax(a, b);
    auto it = crossing_of.find(key);
    if (it != crossing_of.end()) return it->second;
    const double t = value[a] / (value[a] - value[b]);
    out.positions.push_back((1 - t) * m.positions[a] + t * m.positions[b]);
    const int id = static_cast<int>(out.positions.size()) - 1;
    crossing_of.emplace(key, id);
    return id;
  };
  auto add = [&](int a, int b, int c) {
    if (a != b && b != c && a != c) out.triangles.push_back({a, b, c});
  };
  for (const Tri& tri : m.triangles) {
    int inside = 0;
    for (int v : tri) inside += value[v] <= 0;
    if (inside == 3) out.triangles.push_back(tri);
    if (inside == 0 || inside == 3) continue;
    for (int r = 0; r < 3; ++r) {
      const int a = tri[r], b = tri[(r + 1) % 3], c = tri[(r + 2) % 3];
      if (inside == 1 && value[a] <= 0) {
        add(a, crossing(a, b), crossing(a, c));
        break;
      }
      if (inside == 2 && value[a] > 0) {
        const int ab = crossing(a, b), ac = crossing(a, c);
        add(ab, b, c);
        add(ab, c, ac);
        break;
      }
    }
  }
  remove_unreferenced_vertices(out);
  validate_mesh(out);
  return out;
}

std::vector<char> boundary_vertices(const TriMesh& m) {
  std::vector<char> on(m.positions.size(), 0);
  for (const auto& loop : build_topology(m).boundary_loops)
    for (int v : loop) on[v] = 1;
  return on;
}

const Ellipsoid kEllipsoid{1.0, 0.8, 0.6};

// The ellipsoid at 4 and 5 subdivisions and its descriptors, computed once for two tests.
const Scales& ellipsoid_scales(int subdivisions) {
  static const Scales coarse = at_all_scales(kEllipsoid.mesh(4));
  static const Scales fine = at_all_scales(kEllipsoid.mesh(5));
  return subdivisions == 4 ? coarse : fine;
}

}  // namespace

TEST(CurvatureDescriptors, SphereHasMeanCurvatureOneOverRAndGaussianOneOverRSquared) {
  // Bounds per sigma (relative errors). The mean error at sigma = 0.1 is the known bias of
  // averaging tensors of rotating tangent planes in ambient space: about (sigma / R)^2.
  const double mean_h[3] = {0.006, 0.008, 0.015}, max_h[3] = {0.25, 0.2, 0.12};
  for (int subdivisions : {4, 5}) {
    for (double radius : {1.0, 2.5}) {
      const Scales c = at_all_scales(test_meshes::make_icosphere(subdivisions, radius));
      for (int s = 0; s < 3; ++s) {
        const ErrorStats h =
            report(label("sphere ico%.0f R=%.1f sigma=%.3f H (relative)", subdivisions, radius, kSigmas[s]),
                   errors_to(c.mean(s), 1 / radius, 1 / radius));
        const ErrorStats g =
            report(label("sphere ico%.0f R=%.1f sigma=%.3f K (relative)", subdivisions, radius, kSigmas[s]),
                   errors_to(c.gaussian(s), 1 / (radius * radius), 1 / (radius * radius)));
        const ErrorStats m =
            report(label("sphere ico%.0f R=%.1f sigma=%.3f |k|max (relative)", subdivisions, radius, kSigmas[s]),
                   errors_to(c.abs_max(s), 1 / radius, 1 / radius));
        EXPECT_LT(h.mean, mean_h[s]);
        EXPECT_LT(h.max, max_h[s]);
        EXPECT_LT(g.mean, 2 * mean_h[s]);
        EXPECT_LT(g.max, 2.2 * max_h[s]);
        EXPECT_LT(m.mean, 2 * mean_h[s]);
        EXPECT_LT(m.max, 1.5 * max_h[s]);
      }
    }
  }
}

TEST(CurvatureDescriptors, InvertedSphereHasNegativeMeanCurvature) {
  const TriMesh sphere = flipped(test_meshes::make_icosphere(4, 2.0));
  const PrincipalCurvatures k = smoothed_principal_curvatures(sphere, 0.05);
  EXPECT_LT(errors_to(k.mean(), -0.5, 0.5).max, 0.2);
  EXPECT_LT(errors_to(k.gaussian(), 0.25, 0.25).mean, 0.02);
  EXPECT_LT(k.k1.maxCoeff(), 0.0);
  EXPECT_LT(k.mean().mean(), -0.49);
}

TEST(CurvatureDescriptors, CylinderHasHalfCurvatureMeanAndZeroGaussianAwayFromTheEnds) {
  const double r = 0.5;
  const TriMesh cylinder = test_meshes::make_cylinder(r, 2.0, 96, 72);  // near-equilateral, 6912 vertices
  auto middle = [&](int v) { return std::abs(cylinder.positions[v].z() - 1.0) < 0.5; };
  const Scales c = at_all_scales(cylinder);
  for (int s = 0; s < 3; ++s) {
    const ErrorStats h = report(label("cylinder R=0.5 sigma=%.3f H (middle, relative)", kSigmas[s]),
                                errors_to(c.mean(s), 1 / (2 * r), 1 / (2 * r), middle));
    const ErrorStats g = report(label("cylinder R=0.5 sigma=%.3f K (middle, per 1/R^2)", kSigmas[s]),
                                errors_to(c.gaussian(s), 0.0, 1 / (r * r), middle));
    const ErrorStats m = report(label("cylinder R=0.5 sigma=%.3f |k|max (middle, relative)", kSigmas[s]),
                                errors_to(c.abs_max(s), 1 / r, 1 / r, middle));
    EXPECT_LT(h.max, 2e-3);
    EXPECT_LT(g.max, 2e-3);
    EXPECT_LT(m.max, 1e-3);
  }
}

TEST(CurvatureDescriptors, PlaneIsFlat) {
  TriMesh plane = test_meshes::make_grid(30, 2.0, 0.5);  // jitter 0.5 folds no triangle
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : plane.positions) p = rotation * p + Vec3(3, -1, 2);
  const Eigen::MatrixXd curv9 = curv9_descriptor(plane);
  EXPECT_LT(curv9.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(smoothed_principal_curvatures(plane, 0.0).abs_max().maxCoeff(), 1e-9);
}

TEST(CurvatureDescriptors, SaddleHasNegativeGaussianCurvatureAndExactMeanCurvature) {
  const Graph g = saddle();
  const TriMesh m = g.mesh(61, 0.3);  // edge ~0.033, jittered
  auto inner = [&](int v) { return m.positions[v].head<2>().cwiseAbs().maxCoeff() < 0.6; };
  auto exact_h = [&](int v) { return g.mean(m.positions[v]); };
  auto exact_k = [&](int v) { return g.gaussian(m.positions[v]); };
  // sigma 0.025 is below the edge length: the per-vertex estimate of a jittered grid.
  const double mean_h[3] = {0.03, 0.005, 0.006}, mean_k[3] = {0.2, 0.02, 0.05}, max_k[3] = {0.5, 0.08, 0.12};
  const Scales up = at_all_scales(m);
  for (int s = 0; s < 3; ++s) {
    const ErrorStats h =
        report(label("saddle sigma=%.3f H (inner, per kappa)", kSigmas[s]), errors(up.mean(s), exact_h, 1.0, inner));
    const ErrorStats gk = report(label("saddle sigma=%.3f K (inner, per kappa^2)", kSigmas[s]),
                                 errors(up.gaussian(s), exact_k, 1.0, inner));
    EXPECT_LT(h.mean, mean_h[s]);
    EXPECT_LT(gk.mean, mean_k[s]);
    EXPECT_LT(gk.max, max_k[s]);
    if (s == 0) continue;
    for (int v = 0; v < m.num_vertices(); ++v) {
      if (inner(v)) {
        ASSERT_LT(up.gaussian(s)[v], 0.0) << v;
      }
    }
  }
  // Turning the surface over flips H but not K.
  const Scales down = at_all_scales(flipped(m));
  for (int s = 0; s < 3; ++s) {
    EXPECT_LT((up.mean(s) + down.mean(s)).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((up.gaussian(s) - down.gaussian(s)).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(CurvatureDescriptors, EllipsoidMatchesExactCurvatures) {
  // Curvature varies here, so the larger sigmas add a true smoothing bias (H from ~0.8 to ~2.2).
  const double mean_h[3] = {0.012, 0.02, 0.06}, mean_k[3] = {0.035, 0.06, 0.2};
  for (int subdivisions : {4, 5}) {
    const TriMesh m = kEllipsoid.mesh(subdivisions);
    const Scales& c = ellipsoid_scales(subdivisions);
    for (int s = 0; s < 3; ++s) {
      const ErrorStats h = report(label("ellipsoid ico%.0f sigma=%.3f H", subdivisions, kSigmas[s]),
                                  errors(c.mean(s), [&](int v) { return kEllipsoid.mean(m.positions[v]); }));
      const ErrorStats g = report(label("ellipsoid ico%.0f sigma=%.3f K", subdivisions, kSigmas[s]),
                                  errors(c.gaussian(s), [&](int v) { return kEllipsoid.gaussian(m.positions[v]); }));
      EXPECT_LT(h.mean, mean_h[s]);
      EXPECT_LT(g.mean, mean_k[s]);
    }
  }
}

TEST(CurvatureDescriptors, UniformRefinementChangesLittle) {
  // One subdivision step more keeps the coarse vertices first: compare H there.
  const Scales& coarse = ellipsoid_scales(4);
  const Scales& fine = ellipsoid_scales(5);
  const double mean_bound[3] = {0.006, 0.006, 0.004}, max_bound[3] = {0.2, 0.1, 0.02};
  for (int s = 0; s < 3; ++s) {
    const Eigen::VectorXd hc = coarse.mean(s);
    const Eigen::VectorXd hf = fine.mean(s).head(hc.size());
    const ErrorStats d =
        report(label("ellipsoid ico4 vs ico5 sigma=%.3f H", kSigmas[s]), errors(hc, [&](int v) { return hf[v]; }));
    EXPECT_LT(d.mean, mean_bound[s]);
    EXPECT_LT(d.max, max_bound[s]);
  }
}

TEST(CurvatureDescriptors, InvariantToRigidMotionAndCovariantWithScale) {
  const TriMesh patch = test_meshes::make_bumpy_grid(35);
  const Eigen::MatrixXd reference = curv9_descriptor(patch);
  const double magnitude = reference.cwiseAbs().maxCoeff();
  ASSERT_GT(magnitude, 1.0);

  TriMesh moved = patch;
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(2.1, Vec3(-1, 0.5, 0.3).normalized()).toRotationMatrix();
  for (Vec3& p : moved.positions) p = rotation * p + Vec3(10, -4, 7);
  EXPECT_LT((curv9_descriptor(moved) - reference).cwiseAbs().maxCoeff(), 1e-9 * magnitude);

  // Scaling by s with sigma scaled alike divides curvatures by s (the heat system is scale-free).
  const double scale = 3.0;
  TriMesh scaled = patch;
  for (Vec3& p : scaled.positions) p *= scale;
  const PrincipalCurvatures a = smoothed_principal_curvatures(patch, 0.05);
  const PrincipalCurvatures b = smoothed_principal_curvatures(scaled, 0.05 * scale);
  EXPECT_LT((scale * b.k1 - a.k1).cwiseAbs().maxCoeff(), 1e-9 * magnitude);
  EXPECT_LT((scale * b.k2 - a.k2).cwiseAbs().maxCoeff(), 1e-9 * magnitude);
}

TEST(CurvatureDescriptors, ExactlyCutBoundaryNeedsNoCorrection) {
  // A spherical cap and a cylinder piece cut exactly along tilted planes, as extract_geodesic_disk
  // cuts: boundary edges lie inside flat host triangles. The default rule keeps the rim close.
  const TriMesh cap =
      cut_exactly(test_meshes::make_icosphere(5), [](const Vec3& p) { return 0.3 - p.z() - 0.3 * p.x(); });
  const TriMesh tube = cut_exactly(test_meshes::make_cylinder(0.5, 2.0, 96, 72),
                                   [](const Vec3& p) { return p.z() + 1.2 * p.x() + 0.3 * p.y() - 1.0; });
  const std::vector<char> cap_rim = boundary_vertices(cap), tube_rim = boundary_vertices(tube);
  const Scales cap_scales = at_all_scales(cap), tube_scales = at_all_scales(tube);
  const double cap_bound[3] = {0.15, 0.06, 0.04}, tube_bound[3] = {0.25, 0.1, 0.05};
  for (int s = 0; s < 3; ++s) {
    const ErrorStats c = report(label("exact-cut cap sigma=%.3f H (rim, relative)", kSigmas[s]),
                                errors_to(cap_scales.mean(s), 1.0, 1.0, [&](int v) { return cap_rim[v] != 0; }));
    const ErrorStats t = report(label("exact-cut cylinder sigma=%.3f H (rim, relative)", kSigmas[s]),
                                errors_to(tube_scales.mean(s), 1.0, 1.0, [&](int v) { return tube_rim[v] != 0; }));
    EXPECT_LT(c.mean, cap_bound[s]);
    EXPECT_LT(t.mean, tube_bound[s]);
  }
}

TEST(CurvatureDescriptors, FaceSelectedBoundaryIsRestoredByNormalizedConvolution) {
  // A cap made of whole icosphere faces: its boundary edges' folds are lost. Without a correction
  // the rim reads ~25% flatter; kAlongHostEdges restores it.
  const TriMesh cap = test_meshes::select_faces(test_meshes::make_icosphere(5),
                                                [](const Vec3& p) { return p.z() + 0.3 * p.x() > 0.3; });
  const std::vector<char> rim = boundary_vertices(cap);
  auto on_rim = [&](int v) { return rim[v] != 0; };
  const Scales plain_scales = at_all_scales(cap);
  const Scales restored_scales = at_all_scales(cap, PatchBoundary::kAlongHostEdges);
  const double bound[3] = {0.06, 0.03, 0.03};
  for (int s = 0; s < 3; ++s) {
    const ErrorStats plain = report(label("face-selected cap sigma=%.3f H (rim, default rule)", kSigmas[s]),
                                    errors_to(plain_scales.mean(s), 1.0, 1.0, on_rim));
    const ErrorStats restored = report(label("face-selected cap sigma=%.3f H (rim, kAlongHostEdges)", kSigmas[s]),
                                       errors_to(restored_scales.mean(s), 1.0, 1.0, on_rim));
    EXPECT_LT(restored.mean, bound[s]);
    EXPECT_LT(restored.mean, 0.5 * plain.mean);
  }
  // On a closed mesh the two rules are the same computation.
  const TriMesh sphere = test_meshes::make_icosphere(3);
  EXPECT_EQ(curv9_descriptor(sphere), curv9_descriptor(sphere, PatchBoundary::kAlongHostEdges));
}

TEST(CurvatureDescriptors, Curv9LayoutAndMeanCurvatureDescriptor) {
  const TriMesh patch = test_meshes::make_bumpy_grid(25);
  const Eigen::MatrixXd curv9 = curv9_descriptor(patch);
  ASSERT_EQ(curv9.rows(), patch.num_vertices());
  ASSERT_EQ(curv9.cols(), 9);
  for (int s = 0; s < 3; ++s) {
    const PrincipalCurvatures k = smoothed_principal_curvatures(patch, kSigmas[s]);
    EXPECT_LT((curv9.col(3 * s + 0) - k.gaussian()).cwiseAbs().maxCoeff(), 1e-9) << s;
    EXPECT_LT((curv9.col(3 * s + 1) - k.mean()).cwiseAbs().maxCoeff(), 1e-9) << s;
    EXPECT_LT((curv9.col(3 * s + 2) - k.abs_max()).cwiseAbs().maxCoeff(), 1e-9) << s;
    EXPECT_GE((k.k1 - k.k2).minCoeff(), 0.0);
  }
  // Larger sigma smooths: the spread of H shrinks from column to column.
  auto spread = [&](int c) { return curv9.col(c).maxCoeff() - curv9.col(c).minCoeff(); };
  EXPECT_GT(spread(1), spread(4));
  EXPECT_GT(spread(4), spread(7));
  const Eigen::VectorXd h = mean_curvature_descriptor(patch);
  EXPECT_LT((h - curv9.col(7)).cwiseAbs().maxCoeff(), 1e-9);
  // Deterministic: bit-identical on a second run.
  EXPECT_EQ(curv9_descriptor(patch), curv9);
}

TEST(CurvatureDescriptors, RealPatchesAreFiniteMirrorSymmetricAndSigned) {
  // MakeHuman body (mirror-symmetric): the left and right ear patches, cut by extract_geodesic_disk,
  // must give the same area-weighted CURV9 means; the nose is convex (H > 0), and the eye patch,
  // which grows over the socket lining, is concave on average (H < 0).
  io::MeshFileOptions file;
  file.face_end = 13378;  // the body group (shared/bench/README.md)
  const io::LoadedMesh body = io::read_mesh(std::string(MACROCON_SHARED_DIR) + "/meshes/makehuman/base.obj.gz", file);
  auto area_weighted_curv9 = [&](int center_file_vertex, double radius) {
    PatchOptions options;
    options.center.vertex = body.file_to_mesh.at(center_file_vertex);
    options.radius = radius;
    const Patch patch = extract_geodesic_disk(body.mesh, options);
    const Eigen::MatrixXd curv9 = curv9_descriptor(patch.mesh);
    EXPECT_TRUE(curv9.allFinite());
    const Eigen::VectorXd area = vertex_areas(patch.mesh);
    return Eigen::RowVectorXd(area.transpose() * curv9 / area.sum());
  };
  const Eigen::RowVectorXd ear_l = area_weighted_curv9(12222, 0.5), ear_r = area_weighted_curv9(5625, 0.5);
  std::printf("[measured] ear_l CURV9 area-weighted mean H(sigma=0.1) %.4f, |k|max %.4f; ear_r - ear_l max %.2e\n",
              ear_l[7], ear_l[8], (ear_r - ear_l).cwiseAbs().maxCoeff());
  EXPECT_LT((ear_r - ear_l).cwiseAbs().maxCoeff(), 1e-3 * ear_l.cwiseAbs().maxCoeff());
  EXPECT_GT(area_weighted_curv9(297, 0.5)[7], 0.3);    // nose
  EXPECT_LT(area_weighted_curv9(1329, 0.6)[7], -0.5);  // eye_r
}

TEST(CurvatureDescriptors, RejectsBadSigma) {
  const TriMesh sphere = test_meshes::make_icosphere(1);
  for (double sigma : {-0.1, std::nan(""), HUGE_VAL}) {
    try {
      smoothed_principal_curvatures(sphere, sigma);
      FAIL() << "sigma " << sigma << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), MCON_ERROR_INVALID_ARGUMENT);
    }
  }
  EXPECT_NO_THROW(smoothed_principal_curvatures(sphere, 0.0));
}
