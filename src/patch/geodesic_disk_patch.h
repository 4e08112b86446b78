// A geodesic disk cut out of a host mesh: the patch every later stage works on. It is cut exactly
// at the iso-line of the geodesic distance, is one topological disk, is scaled to geodesic radius
// 1, and remembers where each of its vertices and triangles came from on the host.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/surface_point.h"

namespace mcon {

struct PatchCenter {
  int vertex = -1;          // a host vertex, or -1 to use triangle + barycentric
  int triangle = -1;
  Vec3 barycentric = Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3);
};

struct PatchOptions {
  PatchCenter center;
  double radius = 0;           // geodesic radius in host units
  bool fill_holes = true;      // fill pockets with host faces and holes with new triangles
  double snap_fraction = 0.2;  // crossings this close (relative to the edge) snap onto the vertex
  // The host's defects were deferred (DefectPolicy::defer, mesh/orientation.h): validate the part
  // of the host this extraction reads, and only that (validate_mesh_part).
  bool validate_region = false;
  // With validate_region: repair instead of refusing what the patch reads (opt-in, reported in
  // Patch::repairs): zero-area triangles are removed without a hole (patch/region_repair.h) and
  // pinched vertices split into one vertex per fan. Other defects are still refused.
  bool repair_region = false;
  // Progress in [0, 1]; returning false cancels (MCON_ERROR_CANCELLED).
  std::function<bool(double)> progress;
};

// Where a patch vertex lies on the host: (1 - t) * host[v0] + t * host[v1]; v0 == v1 for a host
// vertex; v0 == v1 == -1 for a vertex created to fill a hole.
struct HostPoint {
  int v0 = -1;
  int v1 = -1;
  double t = 0;
};

// What PatchOptions::repair_region changed in the part of the host the patch reads.
struct PatchRepairs {
  int zero_area_triangles_removed = 0;
  int triangles_split = 0;     // neighbours of a removed cap, split at its corner
  int vertices_merged = 0;     // coincident corners of a zero-area triangle
  int pinched_vertices_split = 0;  // host vertices of the patch that joined separate fans
};

struct Patch {
  TriMesh mesh;                     // normalized: host = center + radius * p
  std::vector<HostPoint> host_vertex;
  std::vector<int> host_triangle;   // per patch triangle, -1 if it fills a hole
  std::vector<int> boundary_loop;   // the single boundary loop (mesh on its left)
  std::vector<Vec2> uv;             // disk parametrization
  Vec3 center_position = Vec3::Zero();  // in host units
  double radius = 1;                // in host units
  SurfacePoint center{-1, Vec3(1, 0, 0)};  // the center as a point of the patch
  double max_geodesic_distance = 0; // measured on the normalized patch
  int param_flipped_triangles = 0;
  PatchRepairs repairs;
  int filled_triangles() const;
};

// Throws mcon::Error: INVALID_ARGUMENT (bad center/radius), NOT_A_DISK (with the reason: a
// handle, an annulus around a limb, ...), CANCELLED.
Patch extract_geodesic_disk(const TriMesh& host, const PatchOptions& options);

}  // namespace mcon
