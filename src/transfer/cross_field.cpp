#include "transfer/cross_field.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <string>
#include <unordered_map>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "base/error.h"
#include "mesh/edge_key.h"
#include "mesh/mesh_topology.h"

namespace mcon {
namespace {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex>;
using ComplexVector = Eigen::VectorXcd;

// Orthonormal tangent frame per face: e1 along the first edge, e2 = n x e1. Angles of tangent
// directions are measured in this frame.
struct FaceFrame {
  Vec3 e1, e2, n;
};

std::vector<FaceFrame> face_frames(const TriMesh& mesh) {
  std::vector<FaceFrame> frames(mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tri = mesh.triangles[t];
    FaceFrame& fr = frames[t];
    fr.n = triangle_normal(mesh, t);
    fr.e1 = (mesh.positions[tri[1]] - mesh.positions[tri[0]]).normalized();
    fr.e2 = fr.n.cross(fr.e1);
  }
  return frames;
}

double angle_in_frame(const FaceFrame& fr, const Vec3& v) { return std::atan2(v.dot(fr.e2), v.dot(fr.e1)); }

// The 4-RoSy representative of a direction at angle a: all four directions of a cross map to the
// same complex number e^{4ia}.
Complex cross_value(double angle) { return std::polar(1.0, 4.0 * angle); }

Vec3 centroid(const TriMesh& mesh, int t) {
  const Tri& tri = mesh.triangles[t];
  return (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0;
}

// Smoothness term w |z_f - r z_g|^2 of one interior edge. r is the discrete Levi-Civita transport
// from g to f: unfolding g onto f about the shared edge keeps a direction's angle to that edge, so a
// direction at angle a in g's frame is at a - theta_g + theta_f in f's (theta_* = the edge's
// angle in each frame), and its cross value is multiplied by e^{4i(theta_f - theta_g)}.
// w = |edge| / |centroid_f - centroid_g|: the two-point flux weight of the Dirichlet energy of a
// per-face field, dimensionless so the result does not depend on the mesh scale.
struct Coupling {
  int f, g;
  double w;
  Complex r;
};

std::vector<Coupling> edge_couplings(const TriMesh& mesh, const MeshTopology& topo,
                                     const std::vector<FaceFrame>& frames) {
  std::vector<Coupling> couplings;
  couplings.reserve(topo.num_edges());
  for (int e = 0; e < topo.num_edges(); ++e) {
    if (topo.is_boundary_edge(e)) continue;
    const int f = topo.edge_triangles[e][0], g = topo.edge_triangles[e][1];
    const Vec3 d = mesh.positions[topo.edges[e][1]] - mesh.positions[topo.edges[e][0]];
    const double len = d.norm();
    const double w = len / (centroid(mesh, f) - centroid(mesh, g)).norm();
    const double delta = angle_in_frame(frames[f], d) - angle_in_frame(frames[g], d);
    couplings.push_back({f, g, w, cross_value(delta)});
  }
  return couplings;
}

// Per face: sum of lambda * w_c and of lambda * w_c * c over its constraints (the constraint
// energy of a face, lambda sum w_c |z - c_c|^2, only needs these two sums).
struct FaceTargets {
  std::vector<double> weight;
  std::vector<Complex> value;
};

void add_target(FaceTargets& targets, const FaceFrame& frame, int face, const Vec3& direction, double weight) {
  if (weight <= 0) return;
  targets.weight[face] += weight;
  targets.value[face] += weight * cross_value(angle_in_frame(frame, direction));
}

FaceTargets collect_targets(const TriMesh& mesh, const MeshTopology& topo, const std::vector<FaceFrame>& frames,
                            const std::vector<DirectionConstraint>& constraints, const CrossFieldOptions& options) {
  const int nt = mesh.num_triangles();
  FaceTargets targets;
  targets.weight.assign(nt, 0.0);
  targets.value.assign(nt, Complex(0, 0));
  bool any_positive = false;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const DirectionConstraint& c = constraints[i];
    const std::string which = "constraint " + std::to_string(i);
    require(c.face >= 0 && c.face < nt, MCON_ERROR_INVALID_ARGUMENT,
            which + ": face " + std::to_string(c.face) + " is out of range (mesh has " + std::to_string(nt) +
                " triangles)");
    require(c.direction.allFinite(), MCON_ERROR_INVALID_ARGUMENT, which + ": direction is not finite");
    require(std::isfinite(c.weight) && c.weight >= 0, MCON_ERROR_INVALID_ARGUMENT,
            which + ": weight must be finite and >= 0");
    const Vec3& n = frames[c.face].n;
    const double length = c.direction.norm();
    const Vec3 in_plane = c.direction - c.direction.dot(n) * n;
    require(length > 0 && in_plane.norm() > 1e-6 * length, MCON_ERROR_INVALID_ARGUMENT,
            which + (length > 0 ? ": direction is normal to face " + std::to_string(c.face) : ": direction is zero"));
    any_positive = any_positive || c.weight > 0;
    add_target(targets, frames[c.face], c.face, in_plane, options.alignment_weight * c.weight);
  }
  require(constraints.empty() || any_positive, MCON_ERROR_INVALID_ARGUMENT,
          "all " + std::to_string(constraints.size()) + " constraint weights are zero");
  if (options.align_to_boundary) {
    for (int e = 0; e < topo.num_edges(); ++e) {
      if (!topo.is_boundary_edge(e)) continue;
      const int f = topo.edge_triangles[e][0];
      const Vec3 d = mesh.positions[topo.edges[e][1]] - mesh.positions[topo.edges[e][0]];
      add_target(targets, frames[f], f, d, options.alignment_weight * options.boundary_weight);
    }
  }
  return targets;
}

// One connected component's Hermitian matrix, in local indices 0..faces.size()-1: the smoothness
// terms, plus on the diagonal the constraint weights and `shift` * mass (the eigen solve's shift).
// Solved in complex arithmetic: the same SPD system as the real 2n x 2n one (Re, Im of each z),
// with half the unknowns in the ordering and about half the factorization work.
ComplexSparse build_matrix(const std::vector<int>& faces, const std::vector<int>& local,
                           const std::vector<Coupling>& couplings, const std::vector<int>& coupling_ids,
                           const FaceTargets& targets, double shift, const Eigen::VectorXd& mass) {
  const int n = static_cast<int>(faces.size());
  std::vector<Eigen::Triplet<Complex>> triplets;
  triplets.reserve(2 * coupling_ids.size() + faces.size());
  std::vector<double> diag(n, 0.0);
  for (int id : coupling_ids) {
    const Coupling& c = couplings[id];
    const int i = local[c.f], j = local[c.g];
    diag[i] += c.w;
    diag[j] += c.w;
    triplets.emplace_back(i, j, -c.w * c.r);
    triplets.emplace_back(j, i, -c.w * std::conj(c.r));
  }
  for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, diag[i] + targets.weight[faces[i]] + shift * mass[i]);
  ComplexSparse matrix(n, n);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  return matrix;
}

// Counter-based start vector for the inverse iteration: deterministic and, unlike a constant,
// never orthogonal to the wanted eigenvector by symmetry.
double hashed_angle(int face) {
  std::uint64_t x = static_cast<std::uint64_t>(face) + 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return 2.0 * 3.14159265358979323846 * static_cast<double>(x >> 11) / static_cast<double>(1ull << 53);
}

// Smallest eigenvector of H z = mu M z (M = face areas / mean area) by inverse iteration on the
// slightly shifted, hence positive definite, H + sigma M. Stops when the eigenvalue estimate
// settles: on symmetric shapes (a sphere) the smallest eigenvalue can be (nearly) multiple, and
// any vector of that eigenspace is an equally smooth field.
ComplexVector smoothest_field(const std::vector<int>& faces, const std::vector<int>& local,
                              const std::vector<Coupling>& couplings, const std::vector<int>& coupling_ids,
                              const FaceTargets& targets, const Eigen::VectorXd& mass) {
  const int n = static_cast<int>(faces.size());
  // sigma relative to the smoothness scale: small against the spectral gap, large enough for a
  // well-conditioned factorization when the smallest eigenvalue is 0 (trivial holonomy).
  double scale = 0;
  for (int id : coupling_ids) scale += 2.0 * couplings[id].w;
  scale = std::max(scale / n, 1.0);
  const double sigma = 1e-8 * scale;
  Eigen::SimplicialLDLT<ComplexSparse> solver(build_matrix(faces, local, couplings, coupling_ids, targets, sigma, mass));
  require(solver.info() == Eigen::Success, MCON_ERROR_NUMERICAL, "cross field: factorization failed");

  auto m_normalize = [&](ComplexVector& x) { x /= std::sqrt((mass.array() * x.array().abs2()).sum()); };
  ComplexVector x(n);
  for (int i = 0; i < n; ++i) x[i] = std::polar(1.0, hashed_angle(faces[i]));
  m_normalize(x);
  double estimate = 0;  // x^* M (H + sigma M)^{-1} M x -> 1 / (mu_min + sigma)
  for (int it = 0; it < 100; ++it) {
    const ComplexVector mx = mass.cast<Complex>().cwiseProduct(x);
    ComplexVector y = solver.solve(mx);
    require(solver.info() == Eigen::Success && y.allFinite(), MCON_ERROR_NUMERICAL, "cross field: solve failed");
    const double next = mx.dot(y).real();
    x = std::move(y);
    m_normalize(x);
    // The estimate converges like the square of the vector, and it is the field's smoothness
    // energy: once it moves by less than 1e-6, the field is as smooth as the eigenvector to that
    // precision, even where (near-)multiple eigenvalues keep the vector itself drifting slowly.
    const bool settled = std::abs(next - estimate) <= 1e-6 * std::abs(next);
    estimate = next;
    if (settled) break;
  }
  return x;
}

}  // namespace

CrossField compute_cross_field(const TriMesh& mesh, const std::vector<DirectionConstraint>& constraints,
                               const CrossFieldOptions& options) {
  const int nt = mesh.num_triangles();
  require(nt > 0, MCON_ERROR_EMPTY_MESH, "cross field: mesh has no triangles");
  require(std::isfinite(options.alignment_weight) && options.alignment_weight > 0, MCON_ERROR_INVALID_ARGUMENT,
          "cross field: alignment_weight must be finite and > 0");
  require(std::isfinite(options.boundary_weight) && options.boundary_weight >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "cross field: boundary_weight must be finite and >= 0");

  const MeshTopology topo = build_topology(mesh);
  const std::vector<FaceFrame> frames = face_frames(mesh);
  const FaceTargets targets = collect_targets(mesh, topo, frames, constraints, options);
  const std::vector<Coupling> couplings = edge_couplings(mesh, topo, frames);

  // Components are solved separately: one without constraints would make the constrained
  // system singular, and gets the smoothest field instead.
  std::vector<int> component_of;
  const int nc = triangle_components(mesh, topo, component_of);
  std::vector<std::vector<int>> component_faces(nc), component_couplings(nc);
  for (int t = 0; t < nt; ++t) component_faces[component_of[t]].push_back(t);
  for (int id = 0; id < static_cast<int>(couplings.size()); ++id)
    component_couplings[component_of[couplings[id].f]].push_back(id);

  std::vector<double> areas(nt);
  double mean_area = 0;
  for (int t = 0; t < nt; ++t) mean_area += (areas[t] = triangle_area(mesh, t));
  mean_area /= nt;

  CrossField field;
  field.directions.resize(nt);
  field.confidence.assign(nt, 0.0);
  std::vector<int> local(nt, -1);
  for (int c = 0; c < nc; ++c) {
    const std::vector<int>& faces = component_faces[c];
    const int n = static_cast<int>(faces.size());
    bool constrained = false;
    Eigen::VectorXd mass(n);
    for (int i = 0; i < n; ++i) {
      local[faces[i]] = i;
      mass[i] = areas[faces[i]] / mean_area;
      constrained = constrained || targets.weight[faces[i]] > 0;
    }
    ComplexVector z;
    if (constrained) {
      ComplexVector rhs(n);
      for (int i = 0; i < n; ++i) rhs[i] = targets.value[faces[i]];
      Eigen::SimplicialLDLT<ComplexSparse> solver(
          build_matrix(faces, local, couplings, component_couplings[c], targets, 0.0, mass));
      require(solver.info() == Eigen::Success, MCON_ERROR_NUMERICAL, "cross field: factorization failed");
      z = solver.solve(rhs);
      require(solver.info() == Eigen::Success && z.allFinite(), MCON_ERROR_NUMERICAL, "cross field: solve failed");
    } else {
      z = smoothest_field(faces, local, couplings, component_couplings[c], targets, mass);
    }
    for (int i = 0; i < n; ++i) {
      const int t = faces[i];
      const Complex zi = z[i];
      const double magnitude = std::abs(zi);
      const double angle = magnitude > 1e-12 ? std::arg(zi) / 4.0 : 0.0;
      field.directions[t] = (std::cos(angle) * frames[t].e1 + std::sin(angle) * frames[t].e2).normalized();
      field.confidence[t] = constrained ? std::min(magnitude, 1.0) : 0.0;
    }
  }
  return field;
}

std::vector<DirectionConstraint> constraints_from_polylines(const TriMesh& mesh,
                                                            const std::vector<std::vector<SurfacePoint>>& polylines,
                                                            double weight) {
  const int nt = mesh.num_triangles();
  require(std::isfinite(weight) && weight >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "polyline constraints: weight must be finite and >= 0");
  for (std::size_t l = 0; l < polylines.size(); ++l)
    for (std::size_t k = 0; k < polylines[l].size(); ++k) {
      const SurfacePoint& p = polylines[l][k];
      const std::string which = "polyline " + std::to_string(l) + " point " + std::to_string(k);
      require(p.triangle >= 0 && p.triangle < nt, MCON_ERROR_INVALID_ARGUMENT,
              which + ": face " + std::to_string(p.triangle) + " is out of range (mesh has " + std::to_string(nt) +
                  " triangles)");
      const Vec3& b = p.barycentric;
      require(b.allFinite() && b.minCoeff() >= -1e-9 && std::abs(b.sum() - 1.0) < 1e-6, MCON_ERROR_INVALID_ARGUMENT,
              which + ": barycentric coordinates must be finite, >= 0 and sum to 1");
    }
  if (nt == 0) return {};

  auto position = [&](const SurfacePoint& p) {
    const Tri& tri = mesh.triangles[p.triangle];
    const Vec3 b = p.barycentric / p.barycentric.sum();
    return Vec3(b[0] * mesh.positions[tri[0]] + b[1] * mesh.positions[tri[1]] + b[2] * mesh.positions[tri[2]]);
  };
  const double h = mean_edge_length(mesh);
  std::vector<DirectionConstraint> out;
  auto assign = [&](int face, const Vec3& d, double len, double w) {
    // Only where the segment runs along the face: across a sharp fold its chord can be nearly
    // normal to one side, and would give that face an arbitrary direction.
    const Vec3 n = triangle_normal(mesh, face);
    if ((d - d.dot(n) * n).norm() < 0.1 * len) return;
    out.push_back({face, d / len, w});
  };
  for (const auto& polyline : polylines)
    for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
      const SurfacePoint& a = polyline[k];
      const SurfacePoint& b = polyline[k + 1];
      const Vec3 d = position(b) - position(a);
      const double len = d.norm();
      if (!(len > 1e-12 * h)) continue;
      const double w = weight * len / h;
      assign(a.triangle, d, len, w);
      if (b.triangle != a.triangle) assign(b.triangle, d, len, w);
    }
  return out;
}

namespace {

// For each listed edge, its faces (-1 where there is none).
std::vector<std::array<int, 2>> faces_of_edges(const TriMesh& mesh, const std::vector<std::array<int, 2>>& edges) {
  std::unordered_map<std::uint64_t, std::array<int, 2>> faces;
  for (const auto& e : edges) faces.emplace(edge_key(e[0], e[1]), std::array<int, 2>{-1, -1});
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto it = faces.find(edge_key(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3]));
      if (it != faces.end()) it->second[it->second[0] < 0 ? 0 : 1] = t;
    }
  std::vector<std::array<int, 2>> out;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto& f = faces.at(edge_key(edges[i][0], edges[i][1]));
    require(f[0] >= 0 && edges[i][0] != edges[i][1], MCON_ERROR_INVALID_ARGUMENT,
            "edge " + std::to_string(i) + " (" + std::to_string(edges[i][0]) + ", " + std::to_string(edges[i][1]) +
                ") is not an edge of the mesh");
    out.push_back(f);
  }
  return out;
}

}  // namespace

std::vector<DirectionConstraint> constraints_from_edges(const TriMesh& mesh,
                                                        const std::vector<std::array<int, 2>>& edges, double weight) {
  require(std::isfinite(weight) && weight >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "edge constraints: weight must be finite and >= 0");
  const auto faces = faces_of_edges(mesh, edges);
  std::vector<DirectionConstraint> out;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Vec3 d = (mesh.positions[edges[i][1]] - mesh.positions[edges[i][0]]).normalized();
    for (int f : faces[i])
      if (f >= 0) out.push_back({f, d, weight});
  }
  return out;
}

void align_field_to_edges(const TriMesh& mesh, const std::vector<std::array<int, 2>>& edges, CrossField& field) {
  require(field.directions.size() == mesh.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
          "the field has " + std::to_string(field.directions.size()) + " faces for a mesh of " +
              std::to_string(mesh.triangles.size()));
  const auto faces = faces_of_edges(mesh, edges);
  std::vector<bool> done(mesh.triangles.size(), false);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Vec3 d = (mesh.positions[edges[i][1]] - mesh.positions[edges[i][0]]).normalized();
    for (int f : faces[i])
      if (f >= 0 && !done[f]) {
        field.directions[f] = d;  // an edge of the face lies in its plane
        done[f] = true;
      }
  }
}

}  // namespace mcon
