#include "transfer/polyline_straightening.h"

#include <algorithm>
#include <cmath>

namespace mcon {

namespace {

// The free crossing's edge: corners a, b of its triangle (the nonzero weights), which the
// previous point's triangle must also have. Returns false if the point is not such a crossing.
bool crossing_edge(const TriMesh& mesh, const SurfacePoint& p, int previous_triangle, int& a, int& b) {
  if (previous_triangle < 0 || previous_triangle == p.triangle) return false;
  int zero = -1, zeros = 0;
  for (int k = 0; k < 3; ++k)
    if (p.barycentric[k] == 0.0) {
      zero = k;
      ++zeros;
    }
  if (zeros != 1) return false;
  a = (zero + 1) % 3;
  b = (zero + 2) % 3;
  const Tri& prev = mesh.triangles[previous_triangle];
  const int va = mesh.triangles[p.triangle][a], vb = mesh.triangles[p.triangle][b];
  const auto has = [&](int v) { return prev[0] == v || prev[1] == v || prev[2] == v; };
  return has(va) && has(vb);
}

// Where the straight line from P to N crosses edge u -> w once the triangle holding P (one side)
// and the one holding N (the other side) are unfolded about the edge: the point's parameter on the
// edge, clamped to [0, 1]. Each side's distance from the edge line is measured in its own plane,
// so the unfolding is exact (isometric) for both triangles.
double unfolded_crossing(const Vec3& u, const Vec3& w, const Vec3& P, const Vec3& N, double current) {
  const Vec3 e = w - u;
  const double L2 = e.squaredNorm();
  if (!(L2 > 0)) return current;
  const double xp = (P - u).dot(e) / L2, xn = (N - u).dot(e) / L2;  // in edge lengths
  const double yp = ((P - u) - xp * e).norm(), yn = ((N - u) - xn * e).norm();
  if (!(yp + yn > 1e-14 * std::sqrt(L2))) return current;  // both on the edge line: leave it
  return std::clamp(xp + (xn - xp) * yp / (yp + yn), 0.0, 1.0);
}

struct FreePoint {
  int index, a, b;  // point index and the corners of its triangle spanning its edge
};

// Consecutive points at the same place become one (the later one's triangle holds the segment
// that follows). A closed polyline also drops a last point that came back to the first.
void merge_coincident(const TriMesh& mesh, std::vector<StripPoint>& points, bool closed) {
  std::vector<StripPoint> out;
  for (const StripPoint& p : points) {
    if (!out.empty() && (position_on(mesh, out.back().point) - position_on(mesh, p.point)).norm() <= 1e-13) {
      const bool fixed = out.back().fixed || p.fixed;
      out.back() = p;
      out.back().fixed = fixed;
      continue;
    }
    out.push_back(p);
  }
  if (closed && out.size() > 2 && (position_on(mesh, out.back().point) - position_on(mesh, out.front().point)).norm() <= 1e-13) {
    out.pop_back();
  }
  points = std::move(out);
}

}  // namespace

void straighten_polyline(const TriMesh& mesh, std::vector<StripPoint>& points, bool closed) {
  const int n = static_cast<int>(points.size());
  if (n < 3) return;
  std::vector<FreePoint> free;
  for (int i = 0; i < n; ++i) {
    if (points[i].fixed || (!closed && (i == 0 || i == n - 1))) continue;
    const int prev = (i + n - 1) % n;
    FreePoint f{i, -1, -1};
    if (crossing_edge(mesh, points[i].point, points[prev].point.triangle, f.a, f.b)) free.push_back(f);
  }
  if (free.empty()) return;

  // Gauss-Seidel over the crossings: each update is the exact minimizer of the path length through
  // its edge with its neighbours held, so the length never grows; the strip's length is convex in
  // the edge parameters, so the sweeps converge to its shortest path.
  constexpr int kMaxSweeps = 200;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double largest = 0;
    for (const FreePoint& f : free) {
      SurfacePoint& p = points[f.index].point;
      const Tri& t = mesh.triangles[p.triangle];
      const Vec3 P = position_on(mesh, points[(f.index + n - 1) % n].point), N = position_on(mesh, points[(f.index + 1) % n].point);
      const double s0 = p.barycentric[f.b];
      const double s = unfolded_crossing(mesh.positions[t[f.a]], mesh.positions[t[f.b]], P, N, s0);
      largest = std::max(largest, std::abs(s - s0));
      p.barycentric[f.a] = 1.0 - s;
      p.barycentric[f.b] = s;
      p.barycentric[3 - f.a - f.b] = 0.0;
    }
    if (largest <= 1e-12) break;
  }
  // A shortest path that wraps around a vertex approaches it only slowly: within 1e-4 of its edge
  // it goes through the vertex exactly, rather than leave a sliver-making point 1e-6 beside it.
  constexpr double kAtVertex = 1e-4;
  for (std::size_t k = 0; k < free.size(); ++k) {
    Vec3& w = points[free[k].index].point.barycentric;
    const double s = w[free[k].b];
    if (s < kAtVertex || s > 1 - kAtVertex) {
      w[free[k].b] = s < kAtVertex ? 0.0 : 1.0;
      w[free[k].a] = 1.0 - w[free[k].b];
    }
  }
  merge_coincident(mesh, points, closed);
}

}  // namespace mcon
