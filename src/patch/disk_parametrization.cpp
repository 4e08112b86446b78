#include "patch/disk_parametrization.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <string>
#include <limits>

#include "base/error.h"
#include "mesh/mesh_topology.h"

namespace mcon {
namespace {

// The loop must be one of the mesh's boundary loops, complete, in the mesh's winding, starting
// anywhere; and the mesh must be a single topological disk (one loop, connected, chi = 1),
// otherwise the Tutte map would silently overlap itself.
void check_boundary_loop(const TriMesh& mesh, const MeshTopology& topo, const std::vector<int>& loop) {
  const int nv = mesh.num_vertices();
  require(loop.size() >= 3, MCON_ERROR_INVALID_ARGUMENT,
          "boundary loop has " + std::to_string(loop.size()) + " vertices; a disk boundary needs at least 3");
  for (std::size_t k = 0; k < loop.size(); ++k)
    require(loop[k] >= 0 && loop[k] < nv, MCON_ERROR_INVALID_ARGUMENT,
            "boundary loop entry " + std::to_string(k) + " is vertex " + std::to_string(loop[k]) +
                " but the mesh has " + std::to_string(nv) + " vertices");

  const std::vector<int>* found = nullptr;
  std::size_t offset = 0;
  for (const auto& candidate : topo.boundary_loops) {
    auto it = std::find(candidate.begin(), candidate.end(), loop[0]);
    if (it != candidate.end()) {
      found = &candidate;
      offset = static_cast<std::size_t>(it - candidate.begin());
      break;
    }
  }
  require(found != nullptr, MCON_ERROR_INVALID_ARGUMENT,
          "boundary loop starts at vertex " + std::to_string(loop[0]) + ", which is not on the mesh boundary");
  const std::vector<int>& real = *found;
  const std::size_t n = real.size();
  require(loop.size() == n, MCON_ERROR_INVALID_ARGUMENT,
          "boundary loop has " + std::to_string(loop.size()) + " vertices but the mesh boundary loop through vertex " +
              std::to_string(loop[0]) + " has " + std::to_string(n));
  bool forward = true, backward = true;
  for (std::size_t k = 0; k < n && (forward || backward); ++k) {
    forward = forward && loop[k] == real[(offset + k) % n];
    backward = backward && loop[k] == real[(offset + n - k) % n];
  }
  require(forward, MCON_ERROR_INVALID_ARGUMENT,
          backward ? std::string("boundary loop runs clockwise (against the triangles' winding); the mesh must lie on "
                                 "its left")
                   : std::string("boundary loop is not the mesh's boundary loop (vertices out of order or not on "
                                 "the boundary)"));

  require(topo.boundary_loops.size() == 1, MCON_ERROR_NOT_A_DISK,
          "mesh has " + std::to_string(topo.boundary_loops.size()) + " boundary loops; a disk has exactly one");
  std::vector<int> component_of;
  const int components = triangle_components(mesh, topo, component_of);
  require(components == 1, MCON_ERROR_NOT_A_DISK,
          "mesh has " + std::to_string(components) + " connected components; a disk has one");
  const int chi = euler_characteristic(mesh, topo);
  require(chi == 1, MCON_ERROR_NOT_A_DISK,
          "mesh has Euler characteristic " + std::to_string(chi) + " (a disk has 1): it has handles");
}

// tan(a/2) for the angle a between u and v, as sin a / (1 + cos a): no trig, stable up to a -> pi.
double tan_half_angle(const Vec3& u, const Vec3& v) {
  const double lengths = u.norm() * v.norm();
  const double denom = lengths + u.dot(v);
  return denom > 0 ? u.cross(v).norm() / denom : 0.0;
}

using RowMajorSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

void check_options(const DiskParametrizationOptions& options) {
  require(options.stretch_iterations >= 0 && options.stretch_exponent > 0 && options.stretch_exponent <= 1 &&
              options.stretch_threshold >= 0 && std::isfinite(options.stretch_threshold) &&
              options.stretch_min_decrease >= 0 && options.stretch_min_decrease < 1,
          MCON_ERROR_INVALID_ARGUMENT,
          "disk parametrization: stretch_iterations must be >= 0, stretch_exponent in (0, 1], "
          "stretch_threshold finite and >= 0, and stretch_min_decrease in [0, 1)");
}

// Boundary: unit circle by cumulative arc length, CCW, boundary_loop[0] at angle 0.
void boundary_on_circle(const TriMesh& mesh, const std::vector<int>& boundary_loop, std::vector<Vec2>& uv) {
  const int nb = static_cast<int>(boundary_loop.size());
  std::vector<double> cumulative(nb + 1, 0.0);
  for (int k = 0; k < nb; ++k)
    cumulative[k + 1] =
        cumulative[k] + (mesh.positions[boundary_loop[(k + 1) % nb]] - mesh.positions[boundary_loop[k]]).norm();
  const double perimeter = cumulative[nb];
  require(perimeter > 0 && std::isfinite(perimeter), MCON_ERROR_NUMERICAL, "boundary loop has zero length");
  const double two_pi = 2.0 * std::acos(-1.0);
  for (int k = 0; k < nb; ++k) {
    const double angle = two_pi * cumulative[k] / perimeter;
    uv[boundary_loop[k]] = Vec2(std::cos(angle), std::sin(angle));
  }
}

// Interior unknowns: per vertex its unknown's index, -1 on the boundary.
std::vector<int> interior_unknowns(int nv, const std::vector<int>& boundary_loop, int& ni) {
  std::vector<int> unknown(nv, -1);
  std::vector<char> on_boundary(nv, 0);
  for (int v : boundary_loop) on_boundary[v] = 1;
  ni = 0;
  for (int v = 0; v < nv; ++v)
    if (!on_boundary[v]) unknown[v] = ni++;
  return unknown;
}

// Floater's mean-value weights (eq. of Floater 2003): corner angle a at i in triangle (i, j, k)
// adds tan(a/2) / |x_j - x_i| to w_ij and tan(a/2) / |x_k - x_i| to w_ik, so an interior edge
// collects the two angles at i beside it.
RowMajorSparse mean_value_weights(const TriMesh& mesh, const std::vector<int>& unknown, int ni) {
  std::vector<Eigen::Triplet<double>> weights;
  weights.reserve(static_cast<std::size_t>(mesh.num_triangles()) * 6);
  for (const Tri& tri : mesh.triangles) {
    for (int c = 0; c < 3; ++c) {
      const int i = tri[c], j = tri[(c + 1) % 3], k = tri[(c + 2) % 3];
      if (unknown[i] < 0) continue;  // on the boundary
      const Vec3 u = mesh.positions[j] - mesh.positions[i];
      const Vec3 v = mesh.positions[k] - mesh.positions[i];
      const double t = tan_half_angle(u, v);
      const double lu = u.norm(), lv = v.norm();
      require(lu > 0 && lv > 0, MCON_ERROR_NUMERICAL,
              "vertex " + std::to_string(i) + " coincides with a neighbour; mean-value weights are undefined");
      weights.emplace_back(unknown[i], j, t / lu);
      weights.emplace_back(unknown[i], k, t / lv);
    }
  }
  RowMajorSparse w(ni, mesh.num_vertices());
  w.setFromTriplets(weights.begin(), weights.end());
  return w;
}

// Row-normalized system: u_i - sum_j lambda_ij u_j = 0, boundary terms moved to the right.
void convex_combination_system(const RowMajorSparse& wm, const std::vector<int>& unknown, int ni,
                               const std::vector<Vec2>& uv, Eigen::SparseMatrix<double>& a, Eigen::MatrixXd& rhs) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(wm.nonZeros()) + ni);
  rhs = Eigen::MatrixXd::Zero(ni, 2);
  for (int r = 0; r < ni; ++r) {
    double sum = 0;
    for (RowMajorSparse::InnerIterator it(wm, r); it; ++it) sum += it.value();
    require(sum > 0 && std::isfinite(sum), MCON_ERROR_NUMERICAL,
            "an interior vertex has no positive mean-value weight (degenerate neighbourhood)");
    triplets.emplace_back(r, r, 1.0);
    for (RowMajorSparse::InnerIterator it(wm, r); it; ++it) {
      const int j = static_cast<int>(it.col());
      const double lambda = it.value() / sum;
      if (unknown[j] >= 0)
        triplets.emplace_back(r, unknown[j], -lambda);
      else
        rhs.row(r) += lambda * uv[j].transpose();
    }
  }
  a.resize(ni, ni);
  a.setFromTriplets(triplets.begin(), triplets.end());
  a.makeCompressed();
}

// A sparse LU that keeps its symbolic analysis (ordering, elimination tree) from its first
// system for the later ones: the stretch rounds below solve systems of one sparsity pattern, and
// the analysis is about two thirds of a fresh LU's cost. Every system it solves must share that
// pattern.
struct PatternLu {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  bool analyzed = false;
};

// Sparse LU, and BiCGSTAB if that fails; NUMERICAL if neither gives a small residual.
Eigen::MatrixXd solve_system(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& rhs, PatternLu& solver) {
  const int ni = static_cast<int>(a.rows());
  auto acceptable = [&](const Eigen::MatrixXd& x) {
    if (!x.allFinite()) return false;
    const double residual = (a * x - rhs).norm();
    return residual <= 1e-8 * (1.0 + rhs.norm());
  };
  Eigen::MatrixXd x;
  bool solved = false;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>& lu = solver.lu;
  if (!solver.analyzed) {
    lu.analyzePattern(a);
    solver.analyzed = true;
  }
  lu.factorize(a);
  if (lu.info() == Eigen::Success) {
    x = lu.solve(rhs);
    solved = lu.info() == Eigen::Success && acceptable(x);
  }
  if (!solved) {
    // Fallback only: the matrix is an M-matrix (diagonally dominant), so BiCGSTAB converges.
    Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, Eigen::IncompleteLUT<double>> iterative;
    iterative.setTolerance(1e-12);
    iterative.setMaxIterations(std::max(1000, 4 * ni));
    iterative.compute(a);
    if (iterative.info() == Eigen::Success) {
      x = iterative.solve(rhs);
      solved = iterative.info() == Eigen::Success && acceptable(x);
    }
  }
  require(solved, MCON_ERROR_NUMERICAL, "disk parametrization: the mean-value Laplace system could not be solved");
  return x;
}

// Solves the row-normalized convex-combination system for the weights `wm` into uv. Calls that
// share `solver` must share the sparsity of `wm`.
void solve_interior(const RowMajorSparse& wm, const std::vector<int>& unknown, int ni, std::vector<Vec2>& uv,
                    PatternLu& solver) {
  Eigen::SparseMatrix<double> a;
  Eigen::MatrixXd rhs;
  convex_combination_system(wm, unknown, ni, uv, a, rhs);
  const Eigen::MatrixXd x = solve_system(a, rhs, solver);
  for (int v = 0; v < static_cast<int>(uv.size()); ++v)
    if (unknown[v] >= 0) uv[v] = x.row(unknown[v]).transpose();
}

// The 3D triangle areas the stretch is weighted by, and their sum.
struct AreaWeights {
  std::vector<double> a3;
  double area3 = 0;
};

AreaWeights triangle_areas(const TriMesh& mesh) {
  const int nt = mesh.num_triangles();
  AreaWeights w;
  w.a3.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const Tri& tr = mesh.triangles[t];
    w.a3[t] = 0.5 * (mesh.positions[tr[1]] - mesh.positions[tr[0]]).cross(mesh.positions[tr[2]] - mesh.positions[tr[0]]).norm();
    w.area3 += w.a3[t];
  }
  return w;
}

// The total area-weighted L2 stretch (Sander et al. 2001) of the map p (1: equal-area), and each
// vertex's stretch in vertex_sigma.
double l2_stretch(const TriMesh& mesh, const AreaWeights& areas, const std::vector<Vec2>& p,
                  std::vector<double>& vertex_sigma) {
  const int nt = mesh.num_triangles(), nv = mesh.num_vertices();
  const std::vector<double>& a3 = areas.a3;
  const double area3 = areas.area3;
  double area2 = 0;
  std::vector<double> s2(nt, 0.0);
  for (int t = 0; t < nt; ++t) {
    const Tri& tr = mesh.triangles[t];
    const Vec2 &p1 = p[tr[0]], &p2 = p[tr[1]], &p3 = p[tr[2]];
    const double A = 0.5 * ((p2.x() - p1.x()) * (p3.y() - p1.y()) - (p3.x() - p1.x()) * (p2.y() - p1.y()));
    area2 += A;
    if (!(A > 0)) { s2[t] = std::numeric_limits<double>::infinity(); continue; }
    const Vec3 &q1 = mesh.positions[tr[0]], &q2 = mesh.positions[tr[1]], &q3 = mesh.positions[tr[2]];
    const Vec3 ss = (q1 * (p2.y() - p3.y()) + q2 * (p3.y() - p1.y()) + q3 * (p1.y() - p2.y())) / (2 * A);
    const Vec3 st = (q1 * (p3.x() - p2.x()) + q2 * (p1.x() - p3.x()) + q3 * (p2.x() - p1.x())) / (2 * A);
    s2[t] = 0.5 * (ss.squaredNorm() + st.squaredNorm());
  }
  const double norm2 = area2 / area3;  // sigma = 1: equal-area scaling
  std::vector<double> num(nv, 0.0), den(nv, 0.0);
  double total = 0;
  for (int t = 0; t < nt; ++t) {
    total += a3[t] * s2[t];
    for (int c = 0; c < 3; ++c) {
      num[mesh.triangles[t][c]] += a3[t] * s2[t];
      den[mesh.triangles[t][c]] += a3[t];
    }
  }
  vertex_sigma.assign(nv, 1.0);
  for (int v = 0; v < nv; ++v)
    if (den[v] > 0) vertex_sigma[v] = std::sqrt(num[v] / den[v] * norm2);
  return std::sqrt(total / area3 * norm2);
}

// w_ij <- w_ij / sigma_j^exponent.
void divide_by_stretch(RowMajorSparse& wk, const std::vector<double>& sigma, double exponent) {
  for (int r = 0; r < wk.outerSize(); ++r) {
    double sum = 0;
    for (RowMajorSparse::InnerIterator e(wk, r); e; ++e) {
      e.valueRef() /= std::pow(std::max(sigma[e.col()], 1e-12), exponent);
      sum += e.value();
    }
    // Rows sum to 1 again (the system is row-normalized anyway), so that repeated rounds
    // cannot underflow the weights.
    for (RowMajorSparse::InnerIterator e(wk, r); e; ++e) e.valueRef() /= sum;
  }
}

// Stretch reduction (Yoshizawa, Belyaev, Seidel 2004): w_ij <- w_ij / sigma_j with sigma_j
// the area-weighted L2 stretch (Sander et al. 2001) around vertex j, repeated while the total
// stretch falls. The weights stay positive, so every iterate is still a Tutte embedding
// (Floater 2003: positive convex combinations with a convex boundary are injective).
// The exponent damps each round (1 is YBS's update). Measured (eval-mapping --classes hand,
// seed 1, 2 pairs): mean eps x 100 32.9 with the plain map; 12.4 with exponent 1 (10 rounds,
// overshoots and stops early); 2.0 with 0.5 and up to 30 rounds (18 used). The rounds stop
// early once one gains less than stretch_min_decrease (docs/design.md §17: the maps between
// patches matched better with that early stop than with the least-stretched iterate).
void reduce_stretch(const TriMesh& mesh, const RowMajorSparse& w, const std::vector<int>& unknown, int ni,
                    const DiskParametrizationOptions& options, PatternLu& solver, std::vector<Vec2>& uv) {
  const AreaWeights areas = triangle_areas(mesh);
  std::vector<double> sigma;
  double best = l2_stretch(mesh, areas, uv, sigma);
  if (!(best > options.stretch_threshold)) return;
  std::vector<Vec2> best_uv = uv;
  // Constructed, then assigned: Eigen's copy constructor leaks its outer index when an
  // allocation fails inside it (no destructor runs); a failed assignment is freed.
  RowMajorSparse wk;
  wk = w;
  for (int it = 0; it < options.stretch_iterations && std::isfinite(best); ++it) {
    divide_by_stretch(wk, sigma, options.stretch_exponent);
    try {
      solve_interior(wk, unknown, ni, uv, solver);
    } catch (const Error&) {
      break;  // a failed round keeps the best iterate so far (the plain map solved)
    }
    const double now = l2_stretch(mesh, areas, uv, sigma);
    if (!(now < best)) break;
    const bool small_gain = now > best * (1 - options.stretch_min_decrease);
    best = now;
    best_uv = uv;
    if (small_gain) break;
  }
  uv = best_uv;
}

}  // namespace

std::vector<Vec2> disk_parametrization(const TriMesh& mesh, const std::vector<int>& boundary_loop,
                                      const DiskParametrizationOptions& options) {
  check_options(options);
  const MeshTopology topo = build_topology(mesh);
  check_boundary_loop(mesh, topo, boundary_loop);
  const int nv = mesh.num_vertices();

  std::vector<Vec2> uv(nv, Vec2::Zero());
  boundary_on_circle(mesh, boundary_loop, uv);
  int ni = 0;
  const std::vector<int> unknown = interior_unknowns(nv, boundary_loop, ni);
  if (ni == 0) return uv;
  const RowMajorSparse w = mean_value_weights(mesh, unknown, ni);
  PatternLu solver;
  solve_interior(w, unknown, ni, uv, solver);
  if (options.stretch_iterations > 0) reduce_stretch(mesh, w, unknown, ni, options, solver, uv);
  return uv;
}

void mean_value_solve(const TriMesh& mesh, const std::vector<char>& movable, std::vector<Vec2>& uv) {
  const int nv = mesh.num_vertices();
  require(static_cast<int>(uv.size()) == nv && static_cast<int>(movable.size()) == nv, MCON_ERROR_INVALID_ARGUMENT,
          "mean_value_solve: uv and movable need one entry per vertex (" + std::to_string(nv) + ")");
  std::vector<int> unknown(nv, -1);
  int ni = 0;
  for (int v = 0; v < nv; ++v)
    if (movable[v]) unknown[v] = ni++;
  if (ni > 0) {
    PatternLu solver;
    solve_interior(mean_value_weights(mesh, unknown, ni), unknown, ni, uv, solver);
  }
}

int count_flipped_triangles(const TriMesh& mesh, const std::vector<Vec2>& uv) {
  require(uv.size() == mesh.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
          "uv has " + std::to_string(uv.size()) + " entries but the mesh has " + std::to_string(mesh.positions.size()) +
              " vertices");
  int flipped = 0;
  for (const Tri& tri : mesh.triangles) {
    const Vec2 e1 = uv[tri[1]] - uv[tri[0]], e2 = uv[tri[2]] - uv[tri[0]];
    const double signed_twice_area = e1.x() * e2.y() - e1.y() * e2.x();
    if (!(signed_twice_area > 0)) ++flipped;  // also counts NaN
  }
  return flipped;
}

}  // namespace mcon
