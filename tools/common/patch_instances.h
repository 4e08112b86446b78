// A bench class on another person or face (shared/bench/README.md, "Patches on other people and
// faces", way 2): same center vertex, radius scaled by s = sqrt(area of the base patch's faces on
// the instance / their area on the base mesh), so the geodesic ball keeps covering the same part on
// a bigger or smaller instance (with the unscaled radius some hands, arms and noses stop being disks).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "common/bench_spec.h"
#include "base/error.h"
#include "mesh/mesh.h"

namespace mcon::tools {

struct InstancePatch {
  int center_vertex = -1;
  double radius = 0.0;  // bench radius x scale
  double scale = 1.0;   // s
};

// `base` and `instance` must have the same triangles (an instance of the base mesh).
// `base_patch_vertices` is the class's vertex list on the base (bench patches file); the patch's
// faces are the file faces whose vertices are all in it. With `triangle_to_face` (io::LoadedMesh)
// a triangle counts only if its whole file face is in the patch, exactly as the README defines the
// patch faces; without it, triangle by triangle (half quads at the patch boundary count too, which
// changes the scale very little).
inline InstancePatch instance_patch(const BenchClass& bench_class, const std::vector<int>& base_patch_vertices,
                                    const TriMesh& base, const TriMesh& instance,
                                    const std::vector<int>& triangle_to_face = {}) {
  require(instance.triangles == base.triangles && instance.positions.size() == base.positions.size(),
          MCON_ERROR_INVALID_ARGUMENT, "instance_patch: the instance does not have the base mesh's connectivity");
  require(triangle_to_face.empty() || triangle_to_face.size() == base.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
          "instance_patch: triangle_to_face does not match the triangles");
  require(bench_class.center_vertex >= 0 && bench_class.center_vertex < base.num_vertices(),
          MCON_ERROR_INDEX_OUT_OF_RANGE, "instance_patch: center vertex of '" + bench_class.name + "' is outside the mesh");
  std::vector<char> in_patch(base.positions.size(), 0);
  for (const int v : base_patch_vertices) {
    require(v >= 0 && v < base.num_vertices(), MCON_ERROR_INDEX_OUT_OF_RANGE,
            "instance_patch: patch vertex " + std::to_string(v) + " is outside the mesh");
    in_patch[static_cast<std::size_t>(v)] = 1;
  }
  const auto all_in = [&](int t) {
    const Tri& tri = base.triangles[static_cast<std::size_t>(t)];
    return in_patch[static_cast<std::size_t>(tri[0])] && in_patch[static_cast<std::size_t>(tri[1])] &&
           in_patch[static_cast<std::size_t>(tri[2])];
  };
  // A file face is in the patch if all of its triangles are (faces' triangles are consecutive).
  std::vector<char> counts(base.triangles.size(), 0);
  for (int t = 0; t < base.num_triangles();) {
    int end = t + 1;
    if (!triangle_to_face.empty())
      while (end < base.num_triangles() && triangle_to_face[end] == triangle_to_face[t]) ++end;
    bool face_in = true;
    for (int k = t; k < end; ++k) face_in = face_in && all_in(k);
    for (int k = t; k < end; ++k) counts[static_cast<std::size_t>(k)] = face_in;
    t = end;
  }
  double base_area = 0.0, instance_area = 0.0;
  for (int t = 0; t < base.num_triangles(); ++t) {
    if (!counts[static_cast<std::size_t>(t)]) continue;
    base_area += triangle_area(base, t);
    instance_area += triangle_area(instance, t);
  }
  require(base_area > 0.0, MCON_ERROR_INVALID_ARGUMENT,
          "instance_patch: the patch of '" + bench_class.name + "' has no faces");
  InstancePatch out;
  out.center_vertex = bench_class.center_vertex;
  out.scale = std::sqrt(instance_area / base_area);
  out.radius = bench_class.radius * out.scale;
  return out;
}

}  // namespace mcon::tools
