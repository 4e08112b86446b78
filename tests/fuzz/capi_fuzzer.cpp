// Structured libFuzzer target for the C API boundary (include/macrocon/macrocon.h): the input
// bytes build a small mesh (a perturbed grid, or raw vertex and index arrays), in float32 or
// float64, with fuzzed strides and counts inside the buffers, then mcon_mesh_create, two
// mcon_patch_extract calls with fuzzed options (center, radius, flags, snap_fraction) and, when
// both succeed, a cheap mcon_map_compute between them (few alignment samples and iterations), then
// closest points of fuzzed query points on the mesh and the patch, and geodesic distances on the
// patch from a fuzzed point and vertex set.
// Every call must return a documented mcon_status (the enum's values, never UNKNOWN, and never
// NULL_POINTER or STRUCT_SIZE for the valid pointers and sizes passed here) with a message when it
// fails; a crash or sanitizer report is a finding.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "macrocon/macrocon.h"

namespace {

[[noreturn]] void finding(const char* call, mcon_status status) {
  const char* message = "";
  mcon_get_last_error(nullptr, &message);
  std::fprintf(stderr, "%s returned undocumented status %d: %s\n", call, static_cast<int>(status), message);
  std::abort();
}

void check(const char* call, mcon_status status) {
  switch (status) {
    case MCON_OK: return;
    case MCON_ERROR_UNKNOWN:
    case MCON_ERROR_NULL_POINTER:
    case MCON_ERROR_STRUCT_SIZE: finding(call, status);
    default: break;
  }
  const char* name = nullptr;
  if (mcon_get_status_name(status, &name) != MCON_OK || name == nullptr) finding(call, status);
  const char* message = nullptr;
  if (mcon_get_last_error(nullptr, &message) != status || message == nullptr || *message == '\0')
    finding(call, status);  // a failure must say what went wrong
}

struct MeshBuffers {
  std::vector<unsigned char> positions, indices;
  mcon_mesh_desc desc{};
};

// Writes `value` as the scalar type into the strided position buffer.
void put_scalar(MeshBuffers& b, std::size_t offset, bool f32, double value) {
  if (f32) {
    const float v = static_cast<float>(value);
    std::memcpy(&b.positions[offset], &v, sizeof v);
  } else {
    std::memcpy(&b.positions[offset], &value, sizeof value);
  }
}

// A grid of n x m vertices (two triangles per cell) with fuzzed heights, or raw arrays; then a
// few fuzzed index overwrites so that validation sees near-valid meshes too.
MeshBuffers build_mesh(FuzzedDataProvider& in) {
  MeshBuffers b;
  const bool f32 = in.ConsumeBool();
  const bool grid = in.ConsumeIntegralInRange(0, 3) != 0;
  const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(2, 7), m = in.ConsumeIntegralInRange<std::size_t>(2, 7);
  const std::size_t nv = grid ? n * m : in.ConsumeIntegralInRange<std::size_t>(0, 12);
  const std::size_t nt = grid ? 2 * (n - 1) * (m - 1) : in.ConsumeIntegralInRange<std::size_t>(0, 12);
  const std::size_t scalar = f32 ? 4 : 8;
  const std::size_t pstride = 3 * scalar + in.ConsumeIntegralInRange<std::size_t>(0, 2) * scalar;
  const std::size_t istride = 12 + 4 * in.ConsumeIntegralInRange<std::size_t>(0, 2);
  b.positions.assign(nv * pstride, 0);
  b.indices.assign(nt * istride, 0);
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t k = 0; k < 3; ++k) {
      double value;
      if (grid && k < 2)
        value = static_cast<double>(k == 0 ? v % n : v / n);
      else if (grid)
        value = in.ConsumeIntegralInRange(-8, 8) / 8.0;
      else
        value = in.ConsumeFloatingPoint<double>();
      put_scalar(b, v * pstride + k * scalar, f32, value);
    }
  std::vector<std::uint32_t> tri(3 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    if (grid) {
      const std::uint32_t c = static_cast<std::uint32_t>(t / 2), x = c % (n - 1), y = c / (n - 1);
      const std::uint32_t a = y * n + x, r = a + 1, u = a + n, d = a + n + 1;
      const std::uint32_t cell[2][3] = {{a, r, d}, {a, d, u}};
      std::memcpy(&tri[3 * t], cell[t % 2], sizeof cell[0]);
    } else {
      for (int k = 0; k < 3; ++k) tri[3 * t + k] = in.ConsumeIntegralInRange<std::uint32_t>(0, 15);
    }
  }
  const int overwrites = in.ConsumeIntegralInRange(0, 2);
  for (int i = 0; i < overwrites && nt > 0; ++i)
    tri[in.ConsumeIntegralInRange<std::size_t>(0, 3 * nt - 1)] = in.ConsumeIntegral<std::uint32_t>() % (nv + 2);
  for (std::size_t t = 0; t < nt; ++t) std::memcpy(&b.indices[t * istride], &tri[3 * t], 12);
  mcon_mesh_desc_init(&b.desc);
  b.desc.positions = b.positions.empty() ? nullptr : b.positions.data();
  b.desc.position_type = f32 ? MCON_SCALAR_FLOAT32 : MCON_SCALAR_FLOAT64;
  b.desc.position_stride = pstride == 3 * scalar && in.ConsumeBool() ? 0 : pstride;
  b.desc.vertex_count = nv;
  b.desc.indices = b.indices.empty() ? nullptr : reinterpret_cast<const std::uint32_t*>(b.indices.data());
  b.desc.index_stride = istride == 12 && in.ConsumeBool() ? 0 : istride;
  b.desc.triangle_count = nt;
  return b;
}

mcon_patch extract(FuzzedDataProvider& in, mcon_mesh mesh, std::size_t nv, std::size_t nt) {
  mcon_patch_options o;
  mcon_patch_options_init(&o);
  if (in.ConsumeBool()) {
    o.center_vertex = in.ConsumeIntegralInRange<std::uint32_t>(0, static_cast<std::uint32_t>(nv));
  } else {
    o.center_vertex = MCON_INVALID_INDEX;
    o.center_triangle = in.ConsumeIntegralInRange<std::uint32_t>(0, static_cast<std::uint32_t>(nt));
    for (double& w : o.center_barycentric) w = in.ConsumeIntegralInRange(-1, 9) / 8.0;
  }
  o.radius = in.ConsumeBool() ? in.ConsumeFloatingPoint<double>() : in.ConsumeIntegralInRange(0, 64) / 8.0;
  o.flags = in.ConsumeIntegralInRange<std::uint32_t>(0, 2);
  if (in.ConsumeBool()) o.snap_fraction = in.ConsumeIntegralInRange(-1, 10) / 20.0;
  mcon_patch patch = nullptr;
  check("mcon_patch_extract", mcon_patch_extract(mesh, &o, &patch));
  return patch;
}

void map(FuzzedDataProvider& in, mcon_patch source, mcon_patch target) {
  mcon_map_options o;
  mcon_map_options_init(&o);
  o.seed = in.ConsumeIntegral<std::uint8_t>();
  o.alignment_samples = in.ConsumeIntegralInRange<std::uint32_t>(0, 16);
  o.allow_reflection = in.ConsumeBool();
  o.max_iterations = in.ConsumeIntegralInRange<std::uint32_t>(0, 3);
  o.orientation = in.ConsumeIntegralInRange<std::uint32_t>(0, 3);
  o.refine_sigma_factor = in.ConsumeIntegralInRange(0, 3) / 2.0;
  o.use_world_frame = in.ConsumeBool();
  o.world_frame_mirror = in.ConsumeBool();
  mcon_map result = nullptr;
  check("mcon_map_compute", mcon_map_compute(source, target, &o, &result));
  check("mcon_map_release", mcon_map_release(result));
}

// A few fuzzed query points (any doubles, NaN and infinities included) against the mesh and, if
// one was cut, the patch.
void closest_points(FuzzedDataProvider& in, mcon_mesh mesh, mcon_patch patch) {
  const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, 4);
  std::vector<double> xyz(3 * n);
  for (double& x : xyz)
    x = in.ConsumeBool() ? in.ConsumeFloatingPoint<double>() : in.ConsumeIntegralInRange(-16, 16) / 4.0;
  std::vector<std::uint32_t> triangles(n);
  std::vector<double> barycentric(3 * n), distances(n);
  check("mcon_mesh_closest_points", mcon_mesh_closest_points(mesh, xyz.data(), n, triangles.data(),
                                                             barycentric.data(), distances.data()));
  if (patch != nullptr)
    check("mcon_patch_closest_points",
          mcon_patch_closest_points(patch, xyz.data(), n, triangles.data(), barycentric.data(), distances.data()));
}

// Geodesic distances on the patch from a fuzzed surface point (any face number and weights) and
// from a fuzzed vertex set (numbers in and past the patch).
void distances(FuzzedDataProvider& in, mcon_patch patch) {
  mcon_patch_info info;
  check("mcon_patch_info_init", mcon_patch_info_init(&info));
  check("mcon_patch_get_info", mcon_patch_get_info(patch, &info));
  std::vector<double> out(info.vertex_count + 1);
  const std::size_t capacity = in.ConsumeIntegralInRange<std::size_t>(info.vertex_count - 1, info.vertex_count + 1);
  mcon_surface_point point{};
  point.face = in.ConsumeIntegralInRange<std::uint32_t>(0, static_cast<std::uint32_t>(info.triangle_count));
  for (double& b : point.barycentric)
    b = in.ConsumeBool() ? in.ConsumeFloatingPoint<double>() : in.ConsumeProbability<double>();
  check("mcon_patch_compute_distance_from_point",
        mcon_patch_compute_distance_from_point(patch, &point, out.data(), capacity));
  std::vector<std::uint32_t> vertices(in.ConsumeIntegralInRange<std::size_t>(0, 3));
  for (std::uint32_t& v : vertices)
    v = in.ConsumeIntegralInRange<std::uint32_t>(0, static_cast<std::uint32_t>(info.vertex_count));
  check("mcon_patch_compute_distance_from_vertices",
        mcon_patch_compute_distance_from_vertices(patch, vertices.data(), vertices.size(), out.data(), capacity));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static mcon_context context = [] {
    mcon_context_options o;
    mcon_context_options_init(&o);
    o.max_threads = 1;  // libFuzzer runs one input at a time; keep the fuzzer deterministic
    mcon_context c = nullptr;
    if (mcon_context_create(&o, &c) != MCON_OK) std::abort();
    return c;
  }();
  FuzzedDataProvider in(data, size);
  MeshBuffers b = build_mesh(in);
  mcon_mesh mesh = nullptr;
  check("mcon_mesh_create", mcon_mesh_create(context, &b.desc, &mesh));
  if (mesh == nullptr) return 0;
  mcon_patch source = extract(in, mesh, b.desc.vertex_count, b.desc.triangle_count);
  mcon_patch target = source != nullptr ? extract(in, mesh, b.desc.vertex_count, b.desc.triangle_count) : nullptr;
  if (source != nullptr && target != nullptr) map(in, source, target);
  closest_points(in, mesh, source);
  if (source != nullptr) distances(in, source);
  check("mcon_patch_release", mcon_patch_release(target));
  check("mcon_patch_release", mcon_patch_release(source));
  check("mcon_mesh_release", mcon_mesh_release(mesh));
  return 0;
}
