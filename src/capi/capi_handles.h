// The objects behind the opaque handles of macrocon.h.
#pragma once

#include <memory>

#include <oneapi/tbb/task_arena.h>

#include "capi_common.h"
#include "geodesic_disk_patch.h"
#include "mesh.h"

struct mcon_context_t {
  static constexpr std::uint32_t kMagic = 0x4d43430a;  // "MCC"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context_options options{};
  // All parallel work of this context runs inside this arena (never the host's global one).
  std::unique_ptr<tbb::task_arena> arena;
};

struct mcon_mesh_t {
  static constexpr std::uint32_t kMagic = 0x4d434d0a;  // "MCM"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // retained
  mcon::TriMesh mesh;
  ~mcon_mesh_t();
};

struct mcon_patch_t {
  static constexpr std::uint32_t kMagic = 0x4d43500a;  // "MCP"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // retained
  mcon::Patch patch;
  ~mcon_patch_t();
};
