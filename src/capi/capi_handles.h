// The objects behind the opaque handles of macrocon.h. Every object but the context keeps one
// reference on the context it was made in, and drops it in its destructor.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <oneapi/tbb/task_arena.h>

#include "capi/capi_common.h"
#include "patch/geodesic_disk_patch.h"
#include "mesh/closest_point_3d.h"
#include "operators/heat_geodesics.h"
#include "mesh/mesh.h"
#include "mesh/orientation.h"

namespace mcon::capi {

// A closest-point tree made on first use, once, whichever thread asks first.
class LazyTree {
 public:
  // Over `mesh`, which outlives this object and never changes (the handle's own mesh): no copy.
  const TriangleTree3D& over(const TriMesh& mesh) {
    std::call_once(once_, [&] { tree_ = std::make_unique<TriangleTree3D>(mesh); });
    return *tree_;
  }
  // Over the mesh `make` returns (derived from the handle's data), kept here for the tree.
  template <typename Make>
  const TriangleTree3D& over_made(const Make& make) {
    std::call_once(once_, [&] {
      made_ = make();
      tree_ = std::make_unique<TriangleTree3D>(made_);
    });
    return *tree_;
  }

 private:
  std::once_flag once_;
  TriMesh made_;
  std::unique_ptr<TriangleTree3D> tree_;
};

// The heat-method operators of a patch (operators/heat_geodesics.h), factored on the first
// distance query and then shared by every call, from any thread (solves only read them).
class LazyHeat {
 public:
  const HeatGeodesics& over(const TriMesh& mesh) {
    std::call_once(once_, [&] { heat_ = std::make_unique<HeatGeodesics>(mesh); });
    return *heat_;
  }

 private:
  std::once_flag once_;
  std::unique_ptr<HeatGeodesics> heat_;
};

// A caller's point on a patch of `triangle_count` triangles: the face must be one of them, the
// weights finite (else NON_FINITE), each in [0, 1] and summing to 1 (capi_patch.cpp). `what`
// names it in the error.
SurfacePoint read_point(const mcon_surface_point& p, std::size_t triangle_count, const std::string& what);

// mcon_mesh_closest_points / mcon_patch_closest_points on a tree (capi_mesh.cpp).
void write_closest_points(mcon_context context, const TriangleTree3D& tree, const double* xyz, std::size_t count,
                          std::uint32_t* out_triangles, double* out_barycentric, double* out_distances);

}  // namespace mcon::capi

struct mcon_context_t {
  static constexpr std::uint32_t kMagic = 0x4d43430a;  // "MCC"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context_options options{};
  // All parallel work of this context runs inside this arena (never the host's global one).
  std::unique_ptr<tbb::task_arena> arena;
  // Count the contexts alive, which mcon_shutdown waits for.
  mcon_context_t();
  ~mcon_context_t();
};

struct mcon_mesh_t {
  static constexpr std::uint32_t kMagic = 0x4d434d0a;  // "MCM"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // retained
  mcon::TriMesh mesh;
  mcon::OrientationReport orientation;  // what the input needed to be consistent and outward
  bool validated_locally = false;       // MCON_MESH_VALIDATE_LOCALLY: operations validate what they read
  // Built on the first mcon_mesh_closest_points (the mesh never changes), shared by every caller.
  mcon::capi::LazyTree closest_tree;
  ~mcon_mesh_t();
};

struct mcon_patch_t {
  static constexpr std::uint32_t kMagic = 0x4d43500a;  // "MCP"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // retained
  mcon::Patch patch;
  // Measured once on the finished patch (mcon_patch_info), not assumed.
  std::uint32_t boundary_loops = 0;
  std::int32_t euler_characteristic = 0;
  // The host's orientation repair (mcon_patch_info), and the patch triangles in reoriented ones.
  std::size_t host_reoriented_triangles = 0;
  std::uint32_t host_outward_turned_components = 0;
  std::uint32_t host_inconsistent_components = 0;
  std::size_t reoriented_triangles = 0;
  // The patch in host units and its tree, built on the first mcon_patch_closest_points.
  mcon::capi::LazyTree closest_tree;
  // The patch's heat-method operators, factored on the first mcon_patch_compute_distance_from_*.
  mcon::capi::LazyHeat heat;
  ~mcon_patch_t();
};

namespace mcon::capi {

// mcon_mesh_create's work (copy, orient with `rule`, validate) for the calls that build a mesh
// themselves; throws mcon::Error.
std::unique_ptr<mcon_mesh_t> make_mesh(mcon_context context, const mcon_mesh_desc* desc, OrientationRule rule);

// Barycentric weights in the caller's corner order -> the oriented triangle's corner order.
inline Vec3 oriented_barycentric(const OrientationReport& report, std::size_t triangle, const Vec3& b) {
  return report.reoriented.size() > triangle && report.reoriented[triangle] ? Vec3(b[0], b[2], b[1]) : b;
}

// Runs `f` inside the context's arena, isolated from any outer work of the calling thread
// (docs/design.md §5: hosts with their own TBB must never see our tasks). Exceptions propagate.
template <typename F>
auto run_in_arena(mcon_context context, const F& f) -> decltype(f()) {
  return context->arena->execute([&] { return tbb::this_task_arena::isolate(f); });
}

// guard() for a call on one object: validates the handle first, then sends any later error to
// the log callback of the object's context as well.
template <typename T, typename F>
mcon_status guard_object(const char* function, T* handle, const char* what, F&& body) noexcept {
  mcon_context log_context = nullptr;
  return guard(
      function,
      [&] {
        check_handle(handle, what);
        log_context = handle->context;
        body();
      },
      log_context);
}

// The context a handle's errors are logged to: a context is its own, every other object keeps
// the one it was made in.
inline mcon_context context_of(mcon_context context) { return context; }
template <typename T>
mcon_context context_of(const T* handle) {
  return handle->context;
}

// guard() for a call that makes a new object: the output pointer must not be NULL and is cleared
// first (so a failed call always leaves NULL there), then `handle`, the object it is made from,
// is validated and any later error also goes to the log callback of that object's context.
template <typename Out, typename T, typename F>
mcon_status guard_create(const char* function, Out** out, const char* out_name, T* handle, const char* what,
                         F&& body) noexcept {
  mcon_context log_context = nullptr;
  return guard(
      function,
      [&] {
        require_pointer(out, out_name);
        *out = nullptr;
        check_handle(handle, what);
        log_context = context_of(handle);
        body();
      },
      log_context);
}

}  // namespace mcon::capi
