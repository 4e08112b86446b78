// Re-embedding maps with a known phi for the transfer tests: flat disks (uv = xy) from
// synthetic_maps.h, phi given in closed form (rotation, scale, mirror, translation), and the
// correspondences located exactly as compute_surface_map locates them.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "transfer/map_view.h"
#include "mesh/point_location_2d.h"
#include "synthetic_maps.h"

namespace mcon::known {

struct KnownMap {
  TriMesh source, target;
  std::vector<Vec2> source_uv, target_uv, phi;
  Correspondences c;
  std::function<Vec2(const Vec2&)> psi;  // phi as a formula on the source uv

  MapView view() const { return {source, source_uv, target, target_uv, phi, c.source_to_target, c.target_to_source}; }
};

// phi(p) = translation + scale * R(angle) * M p, M = diag(1, -1) if mirrored.
inline std::function<Vec2(const Vec2&)> similarity(double angle, double scale, const Vec2& translation,
                                                   bool mirrored = false) {
  return [=](const Vec2& p) {
    const Vec2 q = mirrored ? Vec2(p.x(), -p.y()) : p;
    const double c = std::cos(angle), s = std::sin(angle);
    return Vec2(translation + scale * Vec2(c * q.x() - s * q.y(), s * q.x() + c * q.y()));
  };
}

// `target_height` lifts the target off the plane (z = height(x, y)) while keeping uv = xy, so
// tests can check that transferred things lie on a curved surface.
inline KnownMap make(const TriMesh& source, const TriMesh& target, std::function<Vec2(const Vec2&)> psi,
                     const std::function<double(double, double)>& target_height = {}) {
  KnownMap m;
  m.source = source;
  m.target = target;
  m.source_uv = synthetic::planar_uv(m.source);
  m.target_uv = synthetic::planar_uv(m.target);
  if (target_height)
    for (Vec3& p : m.target.positions) p.z() = target_height(p.x(), p.y());
  m.psi = std::move(psi);
  for (const Vec2& p : m.source_uv) m.phi.push_back(m.psi(p));
  m.c = locate_correspondences(m.source, m.phi, m.target, m.target_uv);
  return m;
}

// The source point at uv position p (the flat source: uv = xy).
struct SourcePoint {
  int triangle;
  Vec3 barycentric;
};
inline SourcePoint source_point(const KnownMap& m, const Vec2& p) {
  const TriangleLocator2D loc(m.source_uv, m.source.triangles);
  const PointLocation l = loc.locate(p);
  return {l.triangle, l.barycentric};
}

}  // namespace mcon::known
