#include "operators/cotan_laplacian.h"

#include <vector>

namespace mcon {

SparseMatrix cotan_laplacian(const TriMesh& mesh) {
  const int n = mesh.num_vertices();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(mesh.num_triangles()) * 12);
  for (const Tri& tri : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      // Corner i is opposite edge (j, k): its cotangent weights that edge.
      const int vi = tri[i], vj = tri[(i + 1) % 3], vk = tri[(i + 2) % 3];
      const Vec3 u = mesh.positions[vj] - mesh.positions[vi];
      const Vec3 v = mesh.positions[vk] - mesh.positions[vi];
      const double cross = u.cross(v).norm();
      const double w = cross > 0 ? 0.5 * u.dot(v) / cross : 0.0;
      triplets.emplace_back(vj, vk, -w);
      triplets.emplace_back(vk, vj, -w);
      triplets.emplace_back(vj, vj, w);
      triplets.emplace_back(vk, vk, w);
    }
  }
  SparseMatrix L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

Eigen::VectorXd vertex_areas(const TriMesh& mesh) {
  Eigen::VectorXd areas = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const double a = triangle_area(mesh, t) / 3.0;
    for (int v : mesh.triangles[t]) areas[v] += a;
  }
  return areas;
}

}  // namespace mcon
