// The objects behind mcon_map and mcon_polyline_set (macrocon.h, "Re-embedding maps and
// constraint transfer"). A map keeps one reference on each of its patches (so the correspondences
// it holds always refer to live meshes); a polyline set keeps one on the patch it lies on, so
// mcon_patch_compute_cross_field can tell whether guides belong to the patch.
#pragma once

#include <vector>

#include "capi/capi_handles.h"
#include "transfer/map_view.h"
#include "transfer/polyline_transfer.h"
#include "map/surface_map.h"

namespace mcon::capi {
// Patch coordinates -> the patch's host units (host = center + radius * p).
inline Vec3 to_host(const Patch& p, const Vec3& x) { return p.center_position + p.radius * x; }
}  // namespace mcon::capi

struct mcon_map_t {
  static constexpr std::uint32_t kMagic = 0x4d434d50;  // "MCMP"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // the source patch's (not retained: the patch holds it)
  mcon_patch source = nullptr;     // retained
  mcon_patch target = nullptr;     // retained
  mcon::SurfaceMap map;
  std::uint32_t flipped_triangles = 0;  // counted again on the returned phi (always 0)
  mcon::MapView view() const {
    return {source->patch.mesh, source->patch.uv, target->patch.mesh, target->patch.uv,
            map.phi,            map.source_to_target, map.target_to_source};
  }
  ~mcon_map_t();
};

struct mcon_polyline_set_t {
  static constexpr std::uint32_t kMagic = 0x4d43504c;  // "MCPL"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // the patch's (not retained: the patch holds it)
  mcon_patch patch = nullptr;      // retained: the patch the points lie on
  std::vector<mcon::TracedPolyline> polylines;
  std::size_t point_count = 0;
  ~mcon_polyline_set_t();
};
