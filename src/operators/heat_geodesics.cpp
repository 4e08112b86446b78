// Heat method (Crane, Weischedel, Wardetzky 2013, Algorithm 1):
//   I.   (M + tL) u = u0                 one backward-Euler heat step (eq. 6, Neumann boundary),
//   II.  X = -grad u / |grad u|          per triangle (eq. 1),
//   III. L phi = div X                   Poisson (eq. 2), then shift phi to 0 at the source.
// The heat operators (Neumann, and Dirichlet on meshes with a boundary) and the Laplacian are
// factored once in the constructor; a query is two or three back-substitutions plus O(n) work.
// Queries only read the factorizations, so they may run concurrently. By default everything runs
// on the intrinsic Delaunay triangulation of the mesh (src/intrinsic_delaunay.h): on meshes with
// obtuse or quad-split triangles the extrinsic cotan operators give negative heat and distances
// off by 9% on average (MakeHuman body), against 2.5% intrinsically.
#include "operators/heat_geodesics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "operators/intrinsic_delaunay.h"
#include "mesh/mesh_topology.h"

namespace mcon {
namespace {

// All matrices share the edge graph's pattern, so one fill-reducing ordering (AMD) serves them
// all: each is permuted once into its upper triangle, which the solver then uses without a copy.
using Solver = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>>;
using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

// Step I decays like exp(-r / sqrt(t)) away from the source, i.e. by e per mean edge length at
// t = h^2, so a plain unit heat underflows about 700 edges away and the far field loses its
// gradient. Scaling the right-hand side by a power of two (exact in floating point) so that the
// largest possible heat value is near 2^900 roughly doubles that reach (to ~1300 edges).
// Solution bound: u = (M + tL)^-1 b with M + tL >= M gives |u_v| <= sum(b) / min(M).
constexpr int kHeatExponent = 900;
constexpr int kLargestHeatExponent = 1000;  // keeps the right-hand side itself finite
// Heat below this (subnormal territory) has lost precision: no reliable gradient direction.
constexpr double kSmallestUsefulHeat = 0x1p-970;

// Per-triangle data of eq. 1 and eq. 2 in the triangle's own 2D frame. For corner i,
// g_i = A * grad(hat_i) = (N x e_i) / 2 with e_i the edge opposite corner i. Then
//   A * grad u = sum_i u_i g_i = (u1 - u0) g1 + (u2 - u0) g2     (g0 = -g1 - g2),
// and the integrated divergence of X at corner i is g_i . X (the weak form of eq. 2 that matches
// the positive semi-definite cotan L; it equals the paper's half-cotan sum with opposite sign).
// The area factor cancels in the normalization of step II, so only g1, g2 are stored.
struct TriangleGradient {
  double g1x, g1y, g2x, g2y;
};

// From the side lengths l01, l12, l20 (intrinsic: no positions needed).
TriangleGradient triangle_gradient(const std::array<double, 3>& l) {
  // Corners in the frame: q0 = (0, 0), q1 = (l01, 0), q2 = (a, b) with b > 0 (CCW).
  const double l01 = l[0], l12 = l[1], l20 = l[2];
  const double a = (l01 * l01 + l20 * l20 - l12 * l12) / (2 * l01);
  const double b = 2 * triangle_area_from_lengths(l01, l12, l20) / l01;
  // g_i = rot90(q_{i+2} - q_{i+1}) / 2 with rot90(x, y) = (-y, x).
  //   g1 = rot90(q0 - q2) / 2 = (b, -a) / 2,   g2 = rot90(q1 - q0) / 2 = (0, l01) / 2.
  return {0.5 * b, -0.5 * a, 0.0, 0.5 * l01};
}

std::string str(long v) { return std::to_string(v); }

void check_input(const TriMesh& mesh, const HeatGeodesicsOptions& options) {
  const int n = mesh.num_vertices(), nt = mesh.num_triangles();
  require(n > 0 && nt > 0, MCON_ERROR_EMPTY_MESH,
          "heat geodesics: mesh is empty (" + str(n) + " vertices, " + str(nt) + " triangles)");
  if (!(std::isfinite(options.time_factor) && options.time_factor > 0))
    fail(MCON_ERROR_INVALID_ARGUMENT,
         "heat geodesics: time_factor must be finite and > 0, got " + std::to_string(options.time_factor));
  // Cheap guards so a mesh that skipped validate_mesh fails cleanly instead of crashing;
  // manifoldness is checked by build_topology below.
  for (int v = 0; v < n; ++v)
    if (!mesh.positions[v].allFinite())
      fail(MCON_ERROR_NON_FINITE, "heat geodesics: vertex " + str(v) + " has a non-finite coordinate");
  for (int t = 0; t < nt; ++t)
    for (int v : mesh.triangles[t])
      if (v < 0 || v >= n)
        fail(MCON_ERROR_INDEX_OUT_OF_RANGE,
             "heat geodesics: triangle " + str(t) + " uses vertex " + str(v) + " of " + str(n));
}

// Dirichlet heat operator: u = 0 on boundary vertices, i.e. identity rows and columns there.
SparseMatrix dirichlet_operator(const SparseMatrix& heat, const std::vector<char>& on_boundary) {
  // Constructed, then assigned: Eigen's copy constructor leaks its outer index when an
  // allocation fails inside it (no destructor runs); a failed assignment is freed.
  SparseMatrix dirichlet;
  dirichlet = heat;
  dirichlet.prune([&](Eigen::Index i, Eigen::Index j, double) {
    return i == j || (!on_boundary[i] && !on_boundary[j]);
  });
  for (int v = 0; v < static_cast<int>(on_boundary.size()); ++v)
    if (on_boundary[v]) dirichlet.coeffRef(v, v) = 1.0;
  return dirichlet;
}

// III. L is singular (constants per component): fix the pinned vertex of each component to 0.
// This is exact, not a regularization: the right-hand side sums to 0 over every component.
SparseMatrix pinned_poisson(const SparseMatrix& L, const std::vector<int>& pinned, int n) {
  SparseMatrix poisson;  // constructed, then assigned (see dirichlet_operator)
  poisson = L;
  std::vector<char> is_pinned(n, 0);
  for (int v : pinned) is_pinned[v] = 1;
  poisson.prune([&](Eigen::Index i, Eigen::Index j, double) { return i == j || (!is_pinned[i] && !is_pinned[j]); });
  for (int v : pinned) poisson.coeffRef(v, v) = 1.0;
  return poisson;
}

}  // namespace

struct HeatGeodesics::Impl {
  int num_vertices = 0;
  double min_area = 0;                 // smallest lumped vertex area (for the heat scaling)
  std::vector<Vec3> positions;         // the mesh, for point sources
  std::vector<Tri> mesh_triangles;
  std::vector<Tri> triangles;          // the triangulation the operators live on
  std::vector<TriangleGradient> gradients;
  std::vector<int> component;          // per vertex
  std::vector<int> pinned;             // per component: the vertex fixed to 0 in the Poisson solve
  std::vector<char> on_boundary;       // per vertex
  bool average_boundary = false;       // mesh has a boundary and options.boundary_average
  Permutation order, inverse_order;   // AMD ordering: matrices are factored as P A P^T
  Solver heat_neumann, heat_dirichlet, poisson;

  Eigen::ComputationInfo factor(Solver& solver, const SparseMatrix& symmetric) const;
  void find_components(const TriMesh& mesh, const MeshTopology& topology, const HeatGeodesicsOptions& options);
  SparseMatrix build_operators(const TriMesh& mesh, const MeshTopology& topology, const HeatGeodesicsOptions& options,
                               Eigen::VectorXd& areas);
  void factor_all(const SparseMatrix& heat, const SparseMatrix& dirichlet, const SparseMatrix& poisson);
  Eigen::VectorXd solve_with(const Solver& solver, const Eigen::VectorXd& rhs) const {
    // Eigen's solve leaves the result empty when the factorization is not usable: a clear error
    // instead of an empty vector that the caller would read out of bounds.
    Eigen::VectorXd x;
    if (solver.info() == Eigen::Success) x = inverse_order * solver.solve(order * rhs);
    require(x.size() == rhs.size() && x.allFinite(), MCON_ERROR_NUMERICAL,
            "heat geodesics: the linear solve failed (degenerate or folded triangles; smooth or remesh the input)");
    return x;
  }

  // Initial heat as (vertex, amount) pairs, all vertices valid. Returns phi before shifting.
  Eigen::VectorXd solve(const std::vector<std::pair<int, double>>& heat) const;
  // Subtracts `value_at_source(component)` in each component that has a source,
  // clamps negatives to 0 and sets components without sources to +infinity.
  template <typename SourceValue>
  void shift(Eigen::VectorXd& phi, const std::vector<char>& has_source, SourceValue value_at_source) const;
};

// Components (through shared edges; on a manifold mesh a vertex's triangles are one fan, so
// every vertex belongs to exactly one) and boundary vertices.
void HeatGeodesics::Impl::find_components(const TriMesh& mesh, const MeshTopology& topology,
                                          const HeatGeodesicsOptions& options) {
  const int n = mesh.num_vertices(), nt = mesh.num_triangles();
  std::vector<int> triangle_component;
  const int num_components = triangle_components(mesh, topology, triangle_component);
  component.assign(n, -1);
  for (int t = 0; t < nt; ++t)
    for (int v : mesh.triangles[t]) component[v] = triangle_component[t];
  pinned.assign(num_components, -1);
  for (int v = 0; v < n; ++v) {
    if (component[v] < 0)
      fail(MCON_ERROR_ISOLATED_VERTEX, "heat geodesics: vertex " + str(v) + " is not used by any triangle");
    if (pinned[component[v]] < 0) pinned[component[v]] = v;
  }
  on_boundary.assign(n, 0);
  for (const auto& loop : topology.boundary_loops)
    for (int v : loop) on_boundary[v] = 1;
  average_boundary = options.boundary_average && !topology.boundary_loops.empty();
}

// The operators' triangulation: intrinsic Delaunay (same vertices, boundary and components) or
// the mesh itself. Returns the cotan Laplacian L on it, with the lumped vertex areas.
SparseMatrix HeatGeodesics::Impl::build_operators(const TriMesh& mesh, const MeshTopology& topology,
                                                  const HeatGeodesicsOptions& options, Eigen::VectorXd& areas) {
  const int nt = mesh.num_triangles();
  IntrinsicTriangulation triangulation = intrinsic_triangulation(mesh, topology);
  if (options.intrinsic_delaunay) make_delaunay(triangulation);
  triangles = triangulation.triangles;
  gradients.resize(nt);
  for (int f = 0; f < nt; ++f) gradients[f] = triangle_gradient(triangulation.lengths[f]);
  SparseMatrix L = options.intrinsic_delaunay ? cotan_laplacian(triangulation) : cotan_laplacian(mesh);
  areas = options.intrinsic_delaunay ? vertex_areas(triangulation) : vertex_areas(mesh);
  min_area = areas.minCoeff();
  require(min_area > 0, MCON_ERROR_DEGENERATE_TRIANGLE, "heat geodesics: a vertex has zero area");
  return L;
}

// The factorizations are independent: run them side by side (in the caller's task arena). The two
// parallel_invoke calls run in their own isolated task_group_context: inside a caller's parallel
// loop whose group was cancelled (a sibling iteration threw), a nested parallel_invoke of the
// cancelled group skips its functions and returns normally, which left the solvers unfactored
// and the heat solution empty, read out of bounds (a crash found by eval-retrieval --noise).
void HeatGeodesics::Impl::factor_all(const SparseMatrix& heat, const SparseMatrix& dirichlet,
                                     const SparseMatrix& poisson_matrix) {
  Eigen::ComputationInfo info[3] = {Eigen::Success, Eigen::Success, Eigen::Success};
  tbb::task_group_context own(tbb::task_group_context::isolated);
  tbb::parallel_invoke([&] { info[0] = factor(heat_neumann, heat); },
                       [&] { info[1] = average_boundary ? factor(heat_dirichlet, dirichlet) : Eigen::Success; },
                       [&] { info[2] = factor(poisson, poisson_matrix); }, own);
  const char* what[3] = {"the heat operator", "the Dirichlet heat operator", "the cotan Laplacian"};
  for (int k = 0; k < 3; ++k)
    if (info[k] != Eigen::Success)
      fail(MCON_ERROR_NUMERICAL, std::string("heat geodesics: factorizing ") + what[k] + " failed (degenerate triangles?)");
}

HeatGeodesics::HeatGeodesics(const TriMesh& mesh, const HeatGeodesicsOptions& options) : impl_(new Impl) {
  Impl& m = *impl_;
  check_input(mesh, options);
  m.num_vertices = mesh.num_vertices();
  m.positions = mesh.positions;
  m.mesh_triangles = mesh.triangles;

  const MeshTopology topology = build_topology(mesh);
  m.find_components(mesh, topology, options);
  Eigen::VectorXd areas;
  const SparseMatrix L = m.build_operators(mesh, topology, options, areas);
  const double h = mean_edge_length(mesh);
  const double t = options.time_factor * h * h;

  // I. Neumann heat operator M + tL (eq. 6 with the natural boundary condition).
  SparseMatrix heat = t * L;
  heat.diagonal() += areas;
  {
    Permutation inverse;
    Eigen::AMDOrdering<int>()(heat, inverse);
    m.inverse_order = inverse;
    m.order = inverse.inverse();
  }
  const SparseMatrix dirichlet = m.average_boundary ? dirichlet_operator(heat, m.on_boundary) : SparseMatrix();
  const SparseMatrix poisson = pinned_poisson(L, m.pinned, m.num_vertices);
  m.factor_all(heat, dirichlet, poisson);
}

Eigen::ComputationInfo HeatGeodesics::Impl::factor(Solver& solver, const SparseMatrix& symmetric) const {
  SparseMatrix upper;
  upper.selfadjointView<Eigen::Upper>() = symmetric.selfadjointView<Eigen::Lower>().twistedBy(order);
  solver.compute(upper);
  return solver.info();
}

HeatGeodesics::~HeatGeodesics() = default;
HeatGeodesics::HeatGeodesics(HeatGeodesics&&) noexcept = default;
HeatGeodesics& HeatGeodesics::operator=(HeatGeodesics&&) noexcept = default;

Eigen::VectorXd HeatGeodesics::Impl::solve(const std::vector<std::pair<int, double>>& heat) const {
  const int n = num_vertices;
  double total = 0;
  for (const auto& source : heat) total += source.second;
  const int exponent =
      std::min(std::ilogb(min_area / total) + kHeatExponent, kLargestHeatExponent - std::ilogb(total));
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (const auto& [v, amount] : heat) rhs[v] += std::ldexp(amount, exponent);
  Eigen::VectorXd u;
  if (!average_boundary) {
    u = solve_with(heat_neumann, rhs);
  } else {
    // §3.2.2: the mean of the Neumann and Dirichlet flows. Heat placed on the boundary is
    // absorbed at once by the Dirichlet condition, so it only contributes to the Neumann half.
    Eigen::VectorXd rhs_dirichlet = rhs, u_dirichlet;
    for (int v = 0; v < n; ++v)
      if (on_boundary[v]) rhs_dirichlet[v] = 0.0;
    tbb::task_group_context own(tbb::task_group_context::isolated);
    tbb::parallel_invoke([&] { u = solve_with(heat_neumann, rhs); },
                         [&] { u_dirichlet = solve_with(heat_dirichlet, rhs_dirichlet); }, own);
    u = 0.5 * (u + u_dirichlet);
  }

  // II + divergence: b_i = sum over triangles of g_i . X with X = -grad u / |grad u|.
  Eigen::VectorXd div = Eigen::VectorXd::Zero(n);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Tri& tri = triangles[t];
    const TriangleGradient& g = gradients[t];
    if (std::max({u[tri[0]], u[tri[1]], u[tri[2]]}) < kSmallestUsefulHeat) continue;  // X = 0 there
    const double du1 = u[tri[1]] - u[tri[0]], du2 = u[tri[2]] - u[tri[0]];
    const double gx = du1 * g.g1x + du2 * g.g2x, gy = du1 * g.g1y + du2 * g.g2y;
    const double norm = std::hypot(gx, gy);
    if (!(norm > 0) || !std::isfinite(norm)) continue;  // no heat gradient: X = 0 there
    const double x = -gx / norm, y = -gy / norm;
    const double d1 = g.g1x * x + g.g1y * y, d2 = g.g2x * x + g.g2y * y;
    div[tri[0]] -= d1 + d2;
    div[tri[1]] += d1;
    div[tri[2]] += d2;
  }
  for (int v : pinned) div[v] = 0.0;
  return solve_with(poisson, div);
}

template <typename SourceValue>
void HeatGeodesics::Impl::shift(Eigen::VectorXd& phi, const std::vector<char>& has_source,
                                SourceValue value_at_source) const {
  std::vector<double> offset(pinned.size(), 0.0);
  for (std::size_t c = 0; c < pinned.size(); ++c)
    if (has_source[c]) offset[c] = value_at_source(static_cast<int>(c));
  const double inf = std::numeric_limits<double>::infinity();
  for (int v = 0; v < num_vertices; ++v) {
    const int c = component[v];
    phi[v] = has_source[c] ? std::max(0.0, phi[v] - offset[c]) : inf;
  }
}

Eigen::VectorXd HeatGeodesics::from_vertices(const std::vector<int>& sources) const {
  const Impl& m = *impl_;
  require(!sources.empty(), MCON_ERROR_INVALID_ARGUMENT, "heat geodesics: no source vertices given");
  for (int s : sources)
    if (s < 0 || s >= m.num_vertices)
      fail(MCON_ERROR_INVALID_ARGUMENT, "heat geodesics: source vertex " + str(s) + " is out of range (mesh has " +
                                            str(m.num_vertices) + " vertices)");
  // A set: order and repetition must not change the heat (nor the rounding).
  std::vector<int> unique_sources = sources;
  std::sort(unique_sources.begin(), unique_sources.end());
  unique_sources.erase(std::unique(unique_sources.begin(), unique_sources.end()), unique_sources.end());

  std::vector<std::pair<int, double>> heat;
  heat.reserve(unique_sources.size());
  std::vector<char> has_source(m.pinned.size(), 0);
  for (int s : unique_sources) {
    heat.emplace_back(s, 1.0);
    has_source[m.component[s]] = 1;
  }
  Eigen::VectorXd phi = m.solve(heat);
  // Several sources: shift each component by the mean over its sources (they agree up to the
  // method's error), then pin every source to exactly 0.
  std::vector<double> sum(m.pinned.size(), 0.0);
  std::vector<int> count(m.pinned.size(), 0);
  for (int s : unique_sources) {
    sum[m.component[s]] += phi[s];
    ++count[m.component[s]];
  }
  m.shift(phi, has_source, [&](int c) { return sum[c] / count[c]; });
  for (int s : unique_sources) phi[s] = 0.0;
  return phi;
}

Eigen::VectorXd HeatGeodesics::from_point(int triangle, const Vec3& barycentric) const {
  const Impl& m = *impl_;
  const int nt = static_cast<int>(m.mesh_triangles.size());
  if (triangle < 0 || triangle >= nt)
    fail(MCON_ERROR_INVALID_ARGUMENT,
         "heat geodesics: triangle " + str(triangle) + " is out of range (mesh has " + str(nt) + " triangles)");
  if (!barycentric.allFinite())
    fail(MCON_ERROR_INVALID_ARGUMENT, "heat geodesics: barycentric coordinates are not finite");
  constexpr double tolerance = 1e-6;
  if (barycentric.minCoeff() < -tolerance || std::abs(barycentric.sum() - 1.0) > tolerance)
    fail(MCON_ERROR_INVALID_ARGUMENT, "heat geodesics: barycentric coordinates (" + std::to_string(barycentric[0]) +
                                          ", " + std::to_string(barycentric[1]) + ", " +
                                          std::to_string(barycentric[2]) + ") must be >= 0 and sum to 1");
  const Vec3 w = barycentric.cwiseMax(0.0) / barycentric.cwiseMax(0.0).sum();
  const Tri& tri = m.mesh_triangles[triangle];
  std::vector<std::pair<int, double>> heat;
  for (int i = 0; i < 3; ++i)
    if (w[i] > 0) heat.emplace_back(tri[i], w[i]);
  Eigen::VectorXd phi = m.solve(heat);

  // The exact distances from the point to the corners are straight segments in the (flat)
  // triangle. phi is only defined up to a constant: choose it so that the corners match those
  // distances in the barycentric mean. Requiring the interpolated phi to vanish at the point
  // instead would bias every distance low by about a third of an edge, since the true distance is
  // a cone, not linear, inside the triangle. For a point on a corner both reduce to phi = 0 there.
  const Vec3 point = w[0] * m.positions[tri[0]] + w[1] * m.positions[tri[1]] + w[2] * m.positions[tri[2]];
  std::vector<char> has_source(m.pinned.size(), 0);
  has_source[m.component[tri[0]]] = 1;
  m.shift(phi, has_source, [&](int) {
    double offset = 0;
    for (int i = 0; i < 3; ++i) offset += w[i] * (phi[tri[i]] - (m.positions[tri[i]] - point).norm());
    return offset;
  });
  return phi;
}

}  // namespace mcon
