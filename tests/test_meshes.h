// Analytic test meshes shared by the tests: planes, spheres, cylinders, disks.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mesh/mesh.h"

namespace mcon::test_meshes {

// n x n vertex grid on [0, size]^2 in the z = 0 plane, alternating diagonals (so the mesh has no
// preferred direction), counter-clockwise seen from +z.
inline TriMesh make_grid(int n, double size = 1.0, double jitter = 0.0) {
  TriMesh m;
  const double h = size / (n - 1);
  unsigned state = 12345u;
  auto rnd = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool inner = i > 0 && j > 0 && i < n - 1 && j < n - 1;
      const double dx = inner ? jitter * h * rnd() : 0.0, dy = inner ? jitter * h * rnd() : 0.0;
      m.positions.emplace_back(i * h + dx, j * h + dy, 0.0);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
    }
  return m;
}

// Icosphere of radius r: 10 * 4^subdivisions + 2 vertices (4: 2562, 5: 10242), outward CCW.
inline TriMesh make_icosphere(int subdivisions, double r = 1.0) {
  TriMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double raw[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                             {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& p : raw) m.positions.push_back(Vec3(p[0], p[1], p[2]).normalized());
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
      const int idx = static_cast<int>(m.positions.size()) - 1;
      mid.emplace(key, idx);
      return idx;
    };
    std::vector<Tri> next;
    for (const Tri& tri : m.triangles) {
      const int ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    m.triangles = std::move(next);
  }
  for (auto& p : m.positions) p *= r;
  return m;
}

// Open cylinder of radius r around the z axis, z in [0, height], outward CCW. n_around
// vertices per ring, n_along rings; rows of quads split with alternating diagonals.
inline TriMesh make_cylinder(double r, double height, int n_around, int n_along) {
  TriMesh m;
  const double pi = std::acos(-1.0);
  for (int j = 0; j < n_along; ++j)
    for (int i = 0; i < n_around; ++i) {
      const double a = 2 * pi * (i + 0.5 * (j % 2)) / n_around;
      m.positions.emplace_back(r * std::cos(a), r * std::sin(a), height * j / (n_along - 1));
    }
  for (int j = 0; j + 1 < n_along; ++j)
    for (int i = 0; i < n_around; ++i) {
      const int a = j * n_around + i, b = j * n_around + (i + 1) % n_around;
      const int c = (j + 1) * n_around + (i + 1) % n_around, d = (j + 1) * n_around + i;
      if (j % 2 == 0) {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      } else {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      }
    }
  return m;
}

// Unit-radius flat disk made of `rings` concentric rings (polar grid), CCW seen from +z.
inline TriMesh make_disk(int rings, double radius = 1.0) {
  TriMesh m;
  const double pi = std::acos(-1.0);
  m.positions.emplace_back(0, 0, 0);
  std::vector<int> ring_start{0};
  for (int k = 1; k <= rings; ++k) {
    ring_start.push_back(static_cast<int>(m.positions.size()));
    const int n = 6 * k;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * pi * i / n;
      m.positions.emplace_back(radius * k / rings * std::cos(a), radius * k / rings * std::sin(a), 0);
    }
  }
  // Triangulate between consecutive rings by walking both rings by angle.
  for (int k = 1; k <= rings; ++k) {
    const int n_in = k == 1 ? 1 : 6 * (k - 1), n_out = 6 * k;
    const int s_in = ring_start[k - 1], s_out = ring_start[k];
    if (k == 1) {
      for (int i = 0; i < n_out; ++i) m.triangles.push_back({0, s_out + i, s_out + (i + 1) % n_out});
      continue;
    }
    int i = 0, o = 0;
    while (i < n_in || o < n_out) {
      const double a_in = (i + 1.0) / n_in, a_out = (o + 1.0) / n_out;
      if (o < n_out && (i >= n_in || a_out <= a_in)) {
        m.triangles.push_back({s_in + i % n_in, s_out + o, s_out + (o + 1) % n_out});
        ++o;
      } else {
        m.triangles.push_back({s_in + i % n_in, s_out + o % n_out, s_in + (i + 1) % n_in});
        ++i;
      }
    }
  }
  return m;
}

// A bumpy open patch over [-1, 1]^2 (n x n grid, jitter 0.4: no folded triangle): waves plus a
// narrow bump, so curvature varies in sign and size and nothing is symmetric.
inline TriMesh make_bumpy_grid(int n) {
  TriMesh m = make_grid(n, 2.0, 0.4);
  for (Vec3& p : m.positions) {
    p.x() -= 1;
    p.y() -= 1;
    p.z() = 0.3 * std::sin(3 * p.x()) * std::cos(2 * p.y()) + 0.2 * std::exp(-(p.x() * p.x() + p.y() * p.y()) / 0.05);
  }
  return m;
}

// The triangles whose three vertices all satisfy keep(p), with unused vertices dropped: a patch
// made of whole faces (its boundary runs along the original edges).
template <typename Keep>
inline TriMesh select_faces(TriMesh mesh, Keep keep) {
  std::vector<Tri> kept;
  for (const Tri& t : mesh.triangles)
    if (keep(mesh.positions[t[0]]) && keep(mesh.positions[t[1]]) && keep(mesh.positions[t[2]])) kept.push_back(t);
  mesh.triangles = kept;
  remove_unreferenced_vertices(mesh);
  return mesh;
}

}  // namespace mcon::test_meshes
