// Polylines on a patch expressed on the host mesh the patch was cut from, so that guides of one or
// several macro constraints can be cut into the whole host and one cross field solved over every
// face of it (docs/design.md §15).
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"
#include "patch/geodesic_disk_patch.h"
#include "transfer/polyline_transfer.h"

namespace mcon {

struct HostPolylines {
  std::vector<std::vector<SurfacePoint>> lines;  // on the host, consecutive points in one host triangle
  std::vector<bool> closed;
  std::vector<int> origin;      // per line: the index of the input polyline it comes from
  int dropped_points = 0;       // points on triangles that fill a hole of the host (no host triangle)
  int split_polylines = 0;      // input polylines cut into pieces by such points
};

// A point of a patch triangle as a point of the host triangle it lies in: each patch corner is
// (1 - t) host[v0] + t host[v1] with v0, v1 corners of that host triangle (a patch triangle is the
// host triangle itself or a piece of it cut at the geodesic iso-line), so the host weights are the
// patch weights pushed through that linear map. Returns an invalid point for a hole-filling
// triangle. Throws INVALID_ARGUMENT if the patch does not belong to `host` (index out of range, a
// corner that is not on its host triangle).
SurfacePoint patch_point_on_host(const TriMesh& host, const Patch& patch, const SurfacePoint& point);

// Every polyline of `polylines` (traced on `patch`) on the host; a polyline crossing a hole-filling
// triangle is split there (pieces with fewer than 2 points are dropped), a closed one that is split
// becomes open. Throws as patch_point_on_host.
HostPolylines polylines_on_host(const TriMesh& host, const Patch& patch, const std::vector<TracedPolyline>& polylines);

// Checks that `patch` was cut from `host`: every patch vertex's host point exists (no patch from
// arrays) and lies at the patch vertex's position in host units within 1e-6 of the patch radius.
// Throws INVALID_ARGUMENT naming the first vertex that does not.
void check_patch_of_host(const TriMesh& host, const Patch& patch);

}  // namespace mcon
