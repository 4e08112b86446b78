#include "transfer/field_transfer.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace mcon {

namespace {

void require_finite(const double* values, std::size_t n, const char* what) {
  for (std::size_t i = 0; i < n; ++i)
    require(std::isfinite(values[i]), MCON_ERROR_NON_FINITE,
            std::string(what) + ": value " + std::to_string(i) + " is not finite");
}

// Interior angle of triangle t at its corner k.
double corner_angle(const TriMesh& mesh, const Tri& t, int k) {
  const Vec3& p = mesh.positions[t[k]];
  const Vec3 a = mesh.positions[t[(k + 1) % 3]] - p, b = mesh.positions[t[(k + 2) % 3]] - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Coefficients (alpha, beta) of a vector x = alpha e1 + beta e2 in the plane of (e1, e2), least
// squares (x is projected first). Returns false for a degenerate frame.
bool plane_coefficients(const Vec3& e1, const Vec3& e2, const Vec3& x, double& alpha, double& beta) {
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2);
  const double det = a * c - b * b;
  if (!(det > 1e-300)) return false;
  const double r1 = e1.dot(x), r2 = e2.dot(x);
  alpha = (c * r1 - b * r2) / det;
  beta = (a * r2 - b * r1) / det;
  return true;
}

bool plane_coefficients_2d(const Vec2& e1, const Vec2& e2, const Vec2& x, double& alpha, double& beta) {
  const double det = e1.x() * e2.y() - e1.y() * e2.x();
  if (!(std::abs(det) > 1e-300)) return false;
  alpha = (x.x() * e2.y() - x.y() * e2.x()) / det;
  beta = (e1.x() * x.y() - e1.y() * x.x()) / det;
  return true;
}

}  // namespace

std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  std::vector<Vec3> n(mesh.positions.size(), Vec3::Zero());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tri = mesh.triangles[t];
    const Vec3 nt = triangle_normal(mesh, t);
    for (int k = 0; k < 3; ++k) n[tri[k]] += corner_angle(mesh, tri, k) * nt;
  }
  for (Vec3& x : n) {
    const double len = x.norm();
    x = len > 1e-300 ? Vec3(x / len) : Vec3::Zero();
  }
  return n;
}

std::vector<std::uint8_t> outside_mask(const MapView& map) {
  check_map_view(map);
  std::vector<std::uint8_t> mask(map.target_to_source.size());
  for (std::size_t w = 0; w < mask.size(); ++w) mask[w] = map.target_to_source[w].triangle < 0 ? 1 : 0;
  return mask;
}

Eigen::MatrixXd transfer_interpolated(const MapView& map, const Eigen::MatrixXd& source_values) {
  check_map_view(map);
  require(source_values.rows() == map.source.num_vertices(), MCON_ERROR_INVALID_ARGUMENT,
          "transfer: the field has " + std::to_string(source_values.rows()) + " rows for " +
              std::to_string(map.source.num_vertices()) + " source vertices");
  require_finite(source_values.data(), static_cast<std::size_t>(source_values.size()), "transfer");
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(map.target.num_vertices(), source_values.cols());
  for (int w = 0; w < map.target.num_vertices(); ++w) {
    const SurfacePoint& p = map.target_to_source[w];
    if (p.triangle < 0) continue;
    const Tri& t = map.source.triangles[p.triangle];
    // The map is piecewise linear (thesis Fig. 4.3): a point keeps its barycentric coordinates.
    out.row(w) = p.barycentric[0] * source_values.row(t[0]) + p.barycentric[1] * source_values.row(t[1]) +
                 p.barycentric[2] * source_values.row(t[2]);
  }
  return out;
}

std::vector<std::int32_t> transfer_labels(const MapView& map, int dimension, const std::vector<std::int32_t>& labels,
                                          std::int32_t outside_label) {
  check_map_view(map);
  require(dimension >= 1, MCON_ERROR_INVALID_ARGUMENT, "transfer_labels: dimension must be >= 1");
  require(labels.size() == static_cast<std::size_t>(dimension) * map.source.positions.size(),
          MCON_ERROR_INVALID_ARGUMENT,
          "transfer_labels: " + std::to_string(labels.size()) + " labels for " +
              std::to_string(map.source.positions.size()) + " source vertices x dimension " + std::to_string(dimension));
  const std::size_t d = static_cast<std::size_t>(dimension);
  std::vector<std::int32_t> out(d * map.target.positions.size(), outside_label);
  for (std::size_t w = 0; w < map.target.positions.size(); ++w) {
    const SurfacePoint& p = map.target_to_source[w];
    if (p.triangle < 0) continue;
    int best = 0;  // the dominant corner; strict '>' so ties keep the lowest slot (deterministic)
    for (int k = 1; k < 3; ++k)
      if (p.barycentric[k] > p.barycentric[best]) best = k;
    const std::size_t v = static_cast<std::size_t>(map.source.triangles[p.triangle][best]);
    for (std::size_t c = 0; c < d; ++c) out[d * w + c] = labels[d * v + c];
  }
  return out;
}

std::vector<Vec3> transfer_tangent_vectors(const MapView& map, const std::vector<Vec3>& source_vectors) {
  check_map_view(map);
  require(source_vectors.size() == map.source.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
          "transfer_tangent_vectors: " + std::to_string(source_vectors.size()) + " vectors for " +
              std::to_string(map.source.positions.size()) + " source vertices");
  for (std::size_t v = 0; v < source_vectors.size(); ++v)
    require(source_vectors[v].allFinite(), MCON_ERROR_NON_FINITE,
            "transfer_tangent_vectors: vector " + std::to_string(v) + " is not finite");

  const TriMesh& S = map.source;
  const TriMesh& T = map.target;
  // Target triangles around each vertex with the vertex's corner angle, and vertex normals.
  std::vector<std::vector<std::pair<int, double>>> around(T.positions.size());
  for (int t = 0; t < T.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) around[T.triangles[t][k]].push_back({t, corner_angle(T, T.triangles[t], k)});
  const std::vector<Vec3> normals = vertex_normals(T);

  std::vector<Vec3> out(T.positions.size(), Vec3::Zero());
  for (std::size_t w = 0; w < T.positions.size(); ++w) {
    const SurfacePoint& p = map.target_to_source[w];
    if (p.triangle < 0) continue;
    const Tri& s = S.triangles[p.triangle];
    Vec3 v = p.barycentric[0] * source_vectors[s[0]] + p.barycentric[1] * source_vectors[s[1]] +
             p.barycentric[2] * source_vectors[s[2]];
    const Vec3 ns = triangle_normal(S, p.triangle);
    v -= v.dot(ns) * ns;
    const double length = v.norm();
    if (!(length > 1e-300)) continue;
    // J_phi · J_f: the 3D edge frame of s onto the edges of phi(s).
    double alpha = 0, beta = 0;
    if (!plane_coefficients(S.positions[s[1]] - S.positions[s[0]], S.positions[s[2]] - S.positions[s[0]], v, alpha,
                            beta))
      continue;
    const Vec2 d = alpha * (map.phi[s[1]] - map.phi[s[0]]) + beta * (map.phi[s[2]] - map.phi[s[0]]);
    // J_g^-1 on each target triangle around w, blended by corner angle.
    Vec3 u = Vec3::Zero();
    for (const auto& [t, angle] : around[w]) {
      const Tri& tt = T.triangles[t];
      double a2 = 0, b2 = 0;
      if (!plane_coefficients_2d(map.target_uv[tt[1]] - map.target_uv[tt[0]],
                                 map.target_uv[tt[2]] - map.target_uv[tt[0]], d, a2, b2))
        continue;
      Vec3 lifted = a2 * (T.positions[tt[1]] - T.positions[tt[0]]) + b2 * (T.positions[tt[2]] - T.positions[tt[0]]);
      const double len = lifted.norm();
      if (len > 1e-300) u += angle * lifted / len;
    }
    u -= u.dot(normals[w]) * normals[w];
    const double ulen = u.norm();
    if (!(ulen > 1e-12)) continue;
    out[w] = (length / ulen) * u;
  }
  return out;
}

}  // namespace mcon
