#include "map/similarity_icp.h"

#include <cmath>

#include <Eigen/SVD>

#include "base/error.h"
#include "base/parallel_blocks.h"
#include "mesh/closest_point_3d.h"

namespace mcon {

namespace {

// One third of each incident triangle's area per vertex: the weights of the ICP sums, so a
// finely tessellated region does not pull the alignment more than a coarse one of the same area.
std::vector<double> vertex_areas(const TriMesh& mesh) {
  std::vector<double> a(mesh.positions.size(), 0.0);
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (const int v : mesh.triangles[t]) a[v] += triangle_area(mesh, t) / 3.0;
  return a;
}

Vec3 area_centroid(const TriMesh& mesh, double& area) {
  Vec3 c = Vec3::Zero();
  area = 0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tri = mesh.triangles[t];
    const double a = triangle_area(mesh, t);
    c += a * (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0;
    area += a;
  }
  return area > 0 ? Vec3(c / area) : c;
}

// Closest target point of every transformed source vertex (in parallel, one slot each).
void closest_points(const TriMesh& source, const SimilarityTransform3D& T, const TriangleTree3D& tree,
                    std::vector<ClosestSurfacePoint>& out) {
  out.resize(source.positions.size());
  for_each_block(source.num_vertices(), 256, [&](int begin, int end, int) {
    for (int v = begin; v < end; ++v) out[v] = tree.closest(T.apply(source.positions[v]));
  });
}

double weighted_rms(const std::vector<ClosestSurfacePoint>& c, const std::vector<double>& w, double total) {
  double sum = 0;
  for (std::size_t v = 0; v < c.size(); ++v) sum += w[v] * c[v].squared_distance;
  return std::sqrt(sum / total);
}

}  // namespace

SimilarityTransform3D weighted_similarity(const std::vector<Vec3>& x, const std::vector<Vec3>& y,
                                          const std::vector<double>& w) {
  require(x.size() == y.size() && x.size() == w.size() && !x.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "weighted_similarity: point lists of different sizes");
  double total = 0;
  Vec3 mx = Vec3::Zero(), my = Vec3::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    total += w[i];
    mx += w[i] * x[i];
    my += w[i] * y[i];
  }
  require(total > 0, MCON_ERROR_INVALID_ARGUMENT, "weighted_similarity: the weights sum to zero");
  mx /= total;
  my /= total;
  double var_x = 0;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    var_x += w[i] * (x[i] - mx).squaredNorm();
    cov += w[i] * (y[i] - my) * (x[i] - mx).transpose();
  }
  var_x /= total;
  cov /= total;
  require(var_x > 0, MCON_ERROR_INVALID_ARGUMENT, "weighted_similarity: the source points coincide");
  // Umeyama eq. 39-42: S = diag(1, 1, -1) when det(U) det(V) < 0 keeps R a proper rotation.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Vec3 d = Vec3::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) d[2] = -1;
  SimilarityTransform3D T;
  T.rotation = svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
  T.scale = svd.singularValues().dot(d) / var_x;
  T.translation = my - T.scale * (T.rotation * mx);
  return T;
}

SimilarityIcpResult similarity_icp(const TriMesh& source, const TriMesh& target, const SimilarityIcpOptions& options) {
  require(options.max_iterations >= 0 && options.relative_tolerance >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "similarity_icp: max_iterations and relative_tolerance must be >= 0");
  require(source.num_triangles() > 0 && target.num_triangles() > 0, MCON_ERROR_INVALID_ARGUMENT,
          "similarity_icp: empty mesh");
  double source_area = 0, target_area = 0;
  const Vec3 cs = area_centroid(source, source_area);
  const Vec3 ct = area_centroid(target, target_area);
  require(source_area > 0 && target_area > 0, MCON_ERROR_INVALID_ARGUMENT, "similarity_icp: zero-area mesh");
  SimilarityIcpResult out;
  out.transform.scale = std::sqrt(target_area / source_area);
  out.transform.translation = ct - out.transform.scale * cs;
  const std::vector<double> w = vertex_areas(source);
  const TriangleTree3D tree(target);
  std::vector<ClosestSurfacePoint> c;
  closest_points(source, out.transform, tree, c);
  double rms = weighted_rms(c, w, source_area);
  std::vector<Vec3> y(source.positions.size());
  for (int it = 0; it < options.max_iterations; ++it) {
    for (std::size_t v = 0; v < c.size(); ++v) y[v] = c[v].position;
    const SimilarityTransform3D next = weighted_similarity(source.positions, y, w);
    std::vector<ClosestSurfacePoint> c_next;
    closest_points(source, next, tree, c_next);
    const double rms_next = weighted_rms(c_next, w, source_area);
    out.transform = next;
    c.swap(c_next);
    ++out.iterations;
    const bool converged = std::abs(rms - rms_next) <= options.relative_tolerance * rms;
    rms = rms_next;
    if (converged) break;
  }
  out.rms_distance = rms;
  out.closest.resize(c.size());
  for (std::size_t v = 0; v < c.size(); ++v) out.closest[v] = c[v].point;
  return out;
}

TriMesh host_mesh(const Patch& patch) {
  TriMesh m = patch.mesh;
  for (Vec3& p : m.positions) p = patch.center_position + patch.radius * p;
  return m;
}

}  // namespace mcon
