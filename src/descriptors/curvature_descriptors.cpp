#include "descriptors/curvature_descriptors.h"

#include <array>
#include <cmath>
#include <string>

#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "operators/heat_smoothing.h"
#include "mesh/mesh_topology.h"

namespace mcon {
namespace {

// Thesis §3.1 / docs/design.md §1: CURV9 scales, for patches of geodesic radius 1.
constexpr std::array<double, 3> kCurv9Sigmas = {0.025, 0.05, 0.1};
constexpr double kMeanCurvatureSigma = 0.1;

// Column layout of the per-vertex field that gets smoothed: the 6 independent entries of the
// symmetric 3x3 normal-cycle tensor density, then the coverage density.
enum Column { kXX, kXY, kXZ, kYY, kYZ, kZZ, kCoverage, kColumns };

struct CurvatureField {
  Eigen::MatrixXd density;    // n x kColumns
  std::vector<Vec3> normals;  // area-weighted unit vertex normals
  SparseMatrix laplacian;
  Eigen::VectorXd mass;
};

// Cohen-Steiner & Morvan (2003): an interior edge e carries the curvature measure
// beta_e |e| e_hat e_hat^T, beta_e the signed angle between its two face normals (positive where
// convex w.r.t. the CCW outward normals). Half goes to each endpoint; dividing by the vertex area
// gives a density.
//
// Open boundaries: a boundary edge has no dihedral angle. Every edge also carries the area it
// stands for, (A(t0) + A(t1)) / 3, split the same way ("coverage"; summed over a vertex's edges it
// is exactly the vertex area). The tensor and the coverage are smoothed alike and divided
// (normalized convolution), so the estimate is the kernel-weighted average over the area whose
// folds are known:
// - kCutThroughTriangles: a boundary edge lies inside a flat host triangle, its fold is known to
//   be 0, so it covers its triangle's share A(t0) / 3: coverage is the plain area.
// - kAlongHostEdges: a boundary edge's fold is unknown, so it covers nothing; the missing folds are
//   taken to have the average density of the known ones around them.
// Off the boundary both rules give coverage 1 and change nothing.
CurvatureField curvature_field(const TriMesh& mesh, PatchBoundary boundary) {
  const int nv = mesh.num_vertices();
  const MeshTopology topo = build_topology(mesh);
  CurvatureField field;
  field.laplacian = cotan_laplacian(mesh);
  field.mass = vertex_areas(mesh);
  field.density = Eigen::MatrixXd::Zero(nv, kColumns);

  const int nt = mesh.num_triangles();
  std::vector<Vec3> face_normal(nt);
  std::vector<double> face_area(nt);
  field.normals.assign(nv, Vec3::Zero());
  for (int t = 0; t < nt; ++t) {
    const Tri& tri = mesh.triangles[t];
    const Vec3 n =
        (mesh.positions[tri[1]] - mesh.positions[tri[0]]).cross(mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    face_area[t] = 0.5 * n.norm();
    face_normal[t] = face_area[t] > 0 ? Vec3(n / n.norm()) : Vec3::Zero();
    for (int v : tri) field.normals[v] += n;  // |n| = 2 * area: area weighting
  }
  for (Vec3& n : field.normals) {
    const double len = n.norm();
    if (len > 0) n /= len;
  }

  for (int e = 0; e < topo.num_edges(); ++e) {
    if (topo.is_boundary_edge(e)) {
      if (boundary == PatchBoundary::kCutThroughTriangles) {
        const double coverage = 0.5 * face_area[topo.edge_triangles[e][0]] / 3.0;
        for (int v : topo.edges[e]) field.density(v, kCoverage) += coverage;
      }
      continue;
    }
    const int t0 = topo.edge_triangles[e][0], t1 = topo.edge_triangles[e][1];
    // Orient the edge as it runs in t0 (a -> b in t0's winding): then (n0 x n1) . e_hat > 0
    // exactly when the fold is convex.
    int a = topo.edges[e][0], b = topo.edges[e][1];
    const Tri& tri = mesh.triangles[t0];
    for (int i = 0; i < 3; ++i)
      if (tri[i] == b && tri[(i + 1) % 3] == a) std::swap(a, b);
    const Vec3 d = mesh.positions[b] - mesh.positions[a];
    const double length = d.norm();
    if (!(length > 0)) continue;
    const Vec3 e_hat = d / length;
    const Vec3& n0 = face_normal[t0];
    const Vec3& n1 = face_normal[t1];
    const double beta = std::atan2(n0.cross(n1).dot(e_hat), n0.dot(n1));
    const double w = 0.5 * beta * length;  // half to each endpoint
    const double coverage = 0.5 * (face_area[t0] + face_area[t1]) / 3.0;
    const double entries[kColumns] = {w * e_hat.x() * e_hat.x(),
                                      w * e_hat.x() * e_hat.y(),
                                      w * e_hat.x() * e_hat.z(),
                                      w * e_hat.y() * e_hat.y(),
                                      w * e_hat.y() * e_hat.z(),
                                      w * e_hat.z() * e_hat.z(),
                                      coverage};
    for (int v : {a, b})
      for (int c = 0; c < kColumns; ++c) field.density(v, c) += entries[c];
  }
  for (int v = 0; v < nv; ++v) {
    if (field.mass[v] > 0)
      field.density.row(v) /= field.mass[v];
    else
      field.density.row(v).setZero();
  }
  return field;
}

// Principal curvatures from a smoothed tensor field: tangential part at each vertex normal. The
// normal-cycle tensor has the principal directions swapped, but its eigenvalues are k_min, k_max.
// Tensors from tangent planes tilted by up to ~sigma * k are averaged in ambient space, which
// shrinks the result by about (sigma * k)^2 (1% on a unit sphere at sigma = 0.1; measured).
PrincipalCurvatures principal_curvatures(const Eigen::MatrixXd& smoothed, const std::vector<Vec3>& normals) {
  const Eigen::Index nv = smoothed.rows();
  PrincipalCurvatures out;
  out.k1 = Eigen::VectorXd::Zero(nv);
  out.k2 = Eigen::VectorXd::Zero(nv);
  for (Eigen::Index v = 0; v < nv; ++v) {
    const double coverage = smoothed(v, kCoverage);
    if (!(coverage > 1e-9)) continue;  // no measured edge within reach: report flat
    Eigen::Matrix3d tensor;
    tensor << smoothed(v, kXX), smoothed(v, kXY), smoothed(v, kXZ), smoothed(v, kXY), smoothed(v, kYY),
        smoothed(v, kYZ), smoothed(v, kXZ), smoothed(v, kYZ), smoothed(v, kZZ);
    tensor /= coverage;
    const Vec3& n = normals[v];
    // Any orthonormal tangent basis: the eigenvalues do not depend on the choice.
    Eigen::Index axis;
    n.cwiseAbs().minCoeff(&axis);
    const Vec3 u = n.cross(Vec3::Unit(axis)).normalized();
    const Vec3 w = n.cross(u);
    const double s11 = u.dot(tensor * u), s12 = u.dot(tensor * w), s22 = w.dot(tensor * w);
    const double mean = 0.5 * (s11 + s22);
    const double radius = std::hypot(0.5 * (s11 - s22), s12);
    out.k1[v] = mean + radius;
    out.k2[v] = mean - radius;
  }
  return out;
}

void require_valid_sigma(double sigma) {
  require(std::isfinite(sigma) && sigma >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "curvature smoothing width sigma must be finite and >= 0, got " + std::to_string(sigma));
}

// Heat time for a Gaussian of width sigma: the planar heat kernel at time t has variance 2t.
double heat_time(double sigma) { return 0.5 * sigma * sigma; }

}  // namespace

PrincipalCurvatures smoothed_principal_curvatures(const TriMesh& mesh, double sigma, PatchBoundary boundary) {
  require_valid_sigma(sigma);
  const CurvatureField field = curvature_field(mesh, boundary);
  const HeatSmoother smoother(field.laplacian, field.mass, heat_time(sigma));
  return principal_curvatures(smoother.smooth(field.density), field.normals);
}

Eigen::MatrixXd curv9_descriptor(const TriMesh& mesh, PatchBoundary boundary) {
  const CurvatureField field = curvature_field(mesh, boundary);
  Eigen::MatrixXd out(mesh.num_vertices(), 3 * static_cast<Eigen::Index>(kCurv9Sigmas.size()));
  HeatSmoother smoother(field.laplacian, field.mass, heat_time(kCurv9Sigmas[0]));
  for (std::size_t s = 0; s < kCurv9Sigmas.size(); ++s) {
    if (s > 0) smoother.set_time(heat_time(kCurv9Sigmas[s]));
    const PrincipalCurvatures k = principal_curvatures(smoother.smooth(field.density), field.normals);
    out.col(3 * s + 0) = k.gaussian();
    out.col(3 * s + 1) = k.mean();
    out.col(3 * s + 2) = k.abs_max();
  }
  return out;
}

Eigen::VectorXd mean_curvature_descriptor(const TriMesh& mesh, PatchBoundary boundary) {
  return smoothed_principal_curvatures(mesh, kMeanCurvatureSigma, boundary).mean();
}

}  // namespace mcon
