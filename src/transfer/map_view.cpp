#include "transfer/map_view.h"

#include <string>

#include "base/error.h"
#include "mesh/point_location_2d.h"

namespace mcon {

Correspondences locate_correspondences(const TriMesh& source, const std::vector<Vec2>& phi, const TriMesh& target,
                                       const std::vector<Vec2>& target_uv) {
  require(phi.size() == source.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
          "locate_correspondences: phi has " + std::to_string(phi.size()) + " points for " +
              std::to_string(source.positions.size()) + " source vertices");
  require(target_uv.size() == target.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
          "locate_correspondences: target uv has " + std::to_string(target_uv.size()) + " points for " +
              std::to_string(target.positions.size()) + " target vertices");
  Correspondences out;
  const TriangleLocator2D target_locator(target_uv, target.triangles);
  out.source_to_target.resize(phi.size());
  for (std::size_t v = 0; v < phi.size(); ++v) {
    const PointLocation loc = target_locator.locate(phi[v]);
    out.source_to_target[v] = {loc.triangle, loc.barycentric};
  }
  const TriangleLocator2D deformed(phi, source.triangles);
  out.target_to_source.resize(target_uv.size());
  for (std::size_t w = 0; w < target_uv.size(); ++w) {
    const PointLocation loc = deformed.locate(target_uv[w]);
    out.target_to_source[w] = {loc.triangle, loc.barycentric};
  }
  return out;
}

void check_map_view(const MapView& v) {
  const std::size_t ns = v.source.positions.size(), nt = v.target.positions.size();
  require(v.source_uv.size() == ns && v.phi.size() == ns && v.source_to_target.size() == ns,
          MCON_ERROR_INVALID_ARGUMENT, "map view: source uv, phi and source_to_target need one entry per source vertex");
  require(v.target_uv.size() == nt && v.target_to_source.size() == nt, MCON_ERROR_INVALID_ARGUMENT,
          "map view: target uv and target_to_source need one entry per target vertex");
  for (const SurfacePoint& p : v.source_to_target)
    require(p.triangle < v.target.num_triangles(), MCON_ERROR_INVALID_ARGUMENT,
            "map view: a source_to_target triangle is out of range");
  for (const SurfacePoint& p : v.target_to_source)
    require(p.triangle < v.source.num_triangles(), MCON_ERROR_INVALID_ARGUMENT,
            "map view: a target_to_source triangle is out of range");
}

int count_phi_flips(const TriMesh& source, const std::vector<Vec2>& phi, bool reflected) {
  require(phi.size() == source.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
          "count_phi_flips: phi needs one point per source vertex");
  const double sign = reflected ? -1.0 : 1.0;
  int flips = 0;
  for (const Tri& t : source.triangles) {
    const Vec2 e1 = phi[t[1]] - phi[t[0]], e2 = phi[t[2]] - phi[t[0]];
    const double area2 = e1.x() * e2.y() - e1.y() * e2.x();
    if (!(sign * area2 > 0)) ++flips;
  }
  return flips;
}

}  // namespace mcon
