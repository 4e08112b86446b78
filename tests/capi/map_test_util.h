// Shared by the mcon_map_* tests: two nose patches of the MakeHuman sample body (different
// radii, so different tessellations and boundaries), cut once per process, and small helpers.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "capi_test_util.h"
#include "io/mesh_io.h"

namespace map_test {

using namespace capi_test;

struct MapDeleter {
  void operator()(mcon_map m) const { EXPECT_EQ(mcon_map_release(m), MCON_OK); }
};
struct PolylineSetDeleter {
  void operator()(mcon_polyline_set p) const { EXPECT_EQ(mcon_polyline_set_release(p), MCON_OK); }
};
using MapPtr = std::unique_ptr<mcon_map_t, MapDeleter>;
using PolylineSetPtr = std::unique_ptr<mcon_polyline_set_t, PolylineSetDeleter>;

// The body (sample data) as arrays, and the mesh index of file vertex `v`.
struct Body {
  Arrays arrays;
  std::vector<int> file_to_mesh;
};
inline const Body& body() {
  static const Body b = [] {
    const mcon::io::LoadedMesh m =
        mcon::io::read_mesh(std::string(MACROCON_SOURCE_DIR) + "/samples/data/makehuman-body.obj.gz");
    return Body{arrays_of(m.mesh), m.file_to_mesh};
  }();
  return b;
}

inline PatchPtr extract(mcon_mesh mesh, int file_vertex, double radius) {
  mcon_patch_options o;
  EXPECT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_vertex = static_cast<uint32_t>(body().file_to_mesh[file_vertex]);
  o.radius = radius;
  mcon_patch p = nullptr;
  EXPECT_EQ(mcon_patch_extract(mesh, &o, &p), MCON_OK) << last_message();
  return PatchPtr(p);
}

// Small options so every test stays fast (also under the sanitizers).
inline mcon_map_options fast_options() {
  mcon_map_options o;
  EXPECT_EQ(mcon_map_options_init(&o), MCON_OK);
  o.alignment_samples = 200;
  o.max_iterations = 30;
  o.seed = 3;
  return o;
}

inline MapPtr compute(mcon_patch source, mcon_patch target, const mcon_map_options& o) {
  mcon_map m = nullptr;
  EXPECT_EQ(mcon_map_compute(source, target, &o, &m), MCON_OK) << last_message();
  return MapPtr(m);
}

struct PatchArrays {
  std::vector<double> xyz, uv;
  std::vector<uint32_t> tri;
  mcon_patch_info info{};
  size_t nv() const { return xyz.size() / 3; }
  size_t nt() const { return tri.size() / 3; }
};
inline PatchArrays arrays_of_patch(mcon_patch p) {
  PatchArrays a;
  EXPECT_EQ(mcon_patch_info_init(&a.info), MCON_OK);
  EXPECT_EQ(mcon_patch_get_info(p, &a.info), MCON_OK);
  a.xyz.resize(3 * a.info.vertex_count);
  a.uv.resize(2 * a.info.vertex_count);
  a.tri.resize(3 * a.info.triangle_count);
  EXPECT_EQ(mcon_patch_get_positions(p, a.xyz.data(), a.xyz.size()), MCON_OK);
  EXPECT_EQ(mcon_patch_get_uv(p, a.uv.data(), a.uv.size()), MCON_OK);
  EXPECT_EQ(mcon_patch_get_triangles(p, a.tri.data(), a.tri.size()), MCON_OK);
  return a;
}

// The patch triangle whose uv image contains (x, y), with barycentric weights (brute force).
inline bool locate_uv(const PatchArrays& a, double x, double y, uint32_t& triangle, double b[3]) {
  for (size_t t = 0; t < a.nt(); ++t) {
    const double* p0 = &a.uv[2 * a.tri[3 * t]];
    const double* p1 = &a.uv[2 * a.tri[3 * t + 1]];
    const double* p2 = &a.uv[2 * a.tri[3 * t + 2]];
    const double det = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
    const double l1 = ((x - p0[0]) * (p2[1] - p0[1]) - (y - p0[1]) * (p2[0] - p0[0])) / det;
    const double l2 = ((p1[0] - p0[0]) * (y - p0[1]) - (p1[1] - p0[1]) * (x - p0[0])) / det;
    const double l0 = 1 - l1 - l2;
    if (l0 >= 0 && l1 >= 0 && l2 >= 0) {
      triangle = static_cast<uint32_t>(t);
      b[0] = l0;
      b[1] = l1;
      b[2] = l2;
      return true;
    }
  }
  return false;
}

// Normalized position of a point of the patch -> host units.
inline void point_xyz(const PatchArrays& a, uint32_t t, const double* b, double out[3]) {
  for (int k = 0; k < 3; ++k) {
    double p = 0;
    for (int c = 0; c < 3; ++c) p += b[c] * a.xyz[3 * a.tri[3 * t + c] + k];
    out[k] = a.info.center[k] + a.info.radius * p;
  }
}

}  // namespace map_test
