// Helpers for the C API tests: flat arrays from the analytic test meshes, owning pointers for
// handles, and the calling thread's last error.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "macrocon/macrocon.h"
#include "test_meshes.h"

namespace capi_test {

struct ContextDeleter {
  void operator()(mcon_context c) const { EXPECT_EQ(mcon_context_release(c), MCON_OK); }
};
struct MeshDeleter {
  void operator()(mcon_mesh m) const { EXPECT_EQ(mcon_mesh_release(m), MCON_OK); }
};
struct PatchDeleter {
  void operator()(mcon_patch p) const { EXPECT_EQ(mcon_patch_release(p), MCON_OK); }
};
using ContextPtr = std::unique_ptr<mcon_context_t, ContextDeleter>;
using MeshPtr = std::unique_ptr<mcon_mesh_t, MeshDeleter>;
using PatchPtr = std::unique_ptr<mcon_patch_t, PatchDeleter>;

inline std::string last_message() {
  const char* message = nullptr;
  mcon_get_last_error(nullptr, &message);
  return message ? message : "<null>";
}

inline ContextPtr make_context(uint32_t max_threads = 0) {
  mcon_context_options o;
  EXPECT_EQ(mcon_context_options_init(&o), MCON_OK);
  o.max_threads = max_threads;
  mcon_context c = nullptr;
  EXPECT_EQ(mcon_context_create(&o, &c), MCON_OK) << last_message();
  return ContextPtr(c);
}

// Tightly packed copies of a test mesh.
struct Arrays {
  std::vector<double> positions;
  std::vector<uint32_t> indices;
  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return indices.size() / 3; }
};

inline Arrays arrays_of(const mcon::TriMesh& m) {
  Arrays a;
  for (const auto& p : m.positions) a.positions.insert(a.positions.end(), {p.x(), p.y(), p.z()});
  for (const auto& t : m.triangles)
    for (int v : t) a.indices.push_back(static_cast<uint32_t>(v));
  return a;
}

inline mcon_mesh_desc desc_of(const Arrays& a) {
  mcon_mesh_desc d;
  EXPECT_EQ(mcon_mesh_desc_init(&d), MCON_OK);
  d.positions = a.positions.data();
  d.position_type = MCON_SCALAR_FLOAT64;
  d.vertex_count = a.vertex_count();
  d.indices = a.indices.data();
  d.triangle_count = a.triangle_count();
  return d;
}

// Creates a mesh and fails the test (returning null) if that does not work.
inline MeshPtr make_mesh(mcon_context ctx, const Arrays& a) {
  const mcon_mesh_desc d = desc_of(a);
  mcon_mesh m = nullptr;
  EXPECT_EQ(mcon_mesh_create(ctx, &d, &m), MCON_OK) << last_message();
  return MeshPtr(m);
}

// The status of mcon_mesh_create on these arrays (and the mesh is released if it was made).
inline mcon_status create_status(mcon_context ctx, const Arrays& a) {
  const mcon_mesh_desc d = desc_of(a);
  mcon_mesh m = reinterpret_cast<mcon_mesh>(&m);  // must be overwritten with NULL on failure
  const mcon_status s = mcon_mesh_create(ctx, &d, &m);
  if (s == MCON_OK) {
    mcon_mesh_release(m);
  } else {
    EXPECT_EQ(m, nullptr) << "out_mesh must be NULL after a failed create";
  }
  return s;
}

// A zero-filled block that is no object of the library: every handle check must refuse it.
struct alignas(16) Garbage {
  unsigned char bytes[256] = {};
};

}  // namespace capi_test
