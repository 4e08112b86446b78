#include "patch/patch_from_arrays.h"

#include <cmath>
#include <string>

#include "patch/disk_parametrization.h"
#include "base/error.h"
#include "operators/heat_geodesics.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_point.h"

namespace mcon {

Patch patch_from_mesh(TriMesh mesh, const PatchFrame& frame) {
  require(frame.origin.allFinite(), MCON_ERROR_NON_FINITE, "frame origin is not finite");
  require(std::isfinite(frame.scale), MCON_ERROR_NON_FINITE, "frame scale is not finite");
  require(frame.scale > 0, MCON_ERROR_INVALID_ARGUMENT, "frame scale must be > 0 (got " + std::to_string(frame.scale) + ")");
  require(frame.center.triangle >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "no center: set the frame's center triangle and barycentric weights");
  const Vec3 center_b = checked_barycentric(frame.center.triangle, frame.center.barycentric, mesh.num_triangles(),
                                            "frame center");

  const MeshTopology topo = build_topology(mesh);
  {
    std::vector<int> component;
    const int pieces = triangle_components(mesh, topo, component);
    require(pieces == 1, MCON_ERROR_NOT_A_DISK, "not a disk: " + std::to_string(pieces) + " separate pieces");
  }
  require(!topo.boundary_loops.empty(), MCON_ERROR_NOT_A_DISK, "not a disk: a closed surface (no boundary)");
  const int chi = euler_characteristic(mesh, topo);
  require(topo.boundary_loops.size() == 1 && chi == 1, MCON_ERROR_NOT_A_DISK,
          "not a disk: " + std::to_string(topo.boundary_loops.size()) + " boundary loops and Euler characteristic " +
              std::to_string(chi) + " (a disk has 1 and 1: holes or a handle)");

  Patch patch;
  patch.boundary_loop = topo.boundary_loops[0];
  patch.host_vertex.resize(mesh.positions.size());
  for (int v = 0; v < mesh.num_vertices(); ++v) patch.host_vertex[v] = {v, v, 0.0};
  patch.host_triangle.resize(mesh.triangles.size());
  for (int t = 0; t < mesh.num_triangles(); ++t) patch.host_triangle[t] = t;
  patch.center_position = frame.origin;
  patch.radius = frame.scale;
  patch.center.triangle = frame.center.triangle;
  patch.center.barycentric = center_b;
  patch.uv = disk_parametrization(mesh, patch.boundary_loop);
  patch.param_flipped_triangles = count_flipped_triangles(mesh, patch.uv);
  {
    HeatGeodesics heat(mesh);
    patch.max_geodesic_distance = heat.from_point(patch.center.triangle, patch.center.barycentric).maxCoeff();
  }
  patch.mesh = std::move(mesh);
  return patch;
}

}  // namespace mcon
