#include "transfer/guide_self_crossing.h"

#include <map>
#include <string>

#include "base/error.h"

namespace mcon {

namespace {

// The weights of point p in triangle t (which must hold every corner p has weight on).
bool weights_in(const TriMesh& mesh, const SurfacePoint& p, int t, Vec3& out) {
  const Tri& from = mesh.triangles[p.triangle];
  const Tri& to = mesh.triangles[t];
  out = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    if (p.barycentric[k] == 0.0) continue;
    int at = -1;
    for (int j = 0; j < 3; ++j)
      if (to[j] == from[k]) at = j;
    if (at < 0) return false;
    out[at] += p.barycentric[k];
  }
  return true;
}

struct Piece {
  int segment;
  Vec2 a, b;  // the ends' weights of corners 1 and 2 of the triangle
};

}  // namespace

SelfCrossing find_self_crossing(const TriMesh& mesh, const std::vector<SurfacePoint>& line, bool closed) {
  const int n = static_cast<int>(line.size());
  const bool loop = closed && n > 2;
  const int segments = loop ? n : n - 1;
  std::map<int, std::vector<Piece>> in_triangle;
  for (int i = 0; i < segments; ++i) {
    const SurfacePoint& p = line[i];
    const SurfacePoint& q = line[(i + 1) % n];
    Vec3 wp, wq;
    int t = p.triangle;
    if (!weights_in(mesh, q, t, wq)) {
      t = q.triangle;
      if (!weights_in(mesh, p, t, wp)) continue;
      wq = q.barycentric;
    } else {
      wp = p.barycentric;
    }
    in_triangle[t].push_back({i, wp.tail<2>(), wq.tail<2>()});
  }
  for (const auto& [t, pieces] : in_triangle)
    for (std::size_t a = 0; a < pieces.size(); ++a)
      for (std::size_t b = a + 1; b < pieces.size(); ++b) {
        const int i = pieces[a].segment, j = pieces[b].segment;
        const bool adjacent = j - i == 1 || (loop && i == 0 && j == segments - 1);
        if (!adjacent && segments_cross_properly(pieces[a].a, pieces[a].b, pieces[b].a, pieces[b].b, 1e-12))
          return {t, i, j};
      }
  return {};
}

void refuse_self_crossing_guides(const TriMesh& mesh, const std::vector<std::vector<SurfacePoint>>& polylines,
                                 const std::vector<bool>& closed) {
  for (std::size_t g = 0; g < polylines.size(); ++g) {
    const SelfCrossing x = find_self_crossing(mesh, polylines[g], g < closed.size() && closed[g]);
    require(x.triangle < 0, MCON_ERROR_INVALID_ARGUMENT,
            "guide " + std::to_string(g) + " crosses itself in triangle " + std::to_string(x.triangle) +
                " (segments " + std::to_string(x.segment_a) + " and " + std::to_string(x.segment_b) +
                "): give it as polylines that do not cross themselves (split it where it crosses)");
  }
}

}  // namespace mcon
