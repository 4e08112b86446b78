// Meshes: strided caller arrays -> a copied, oriented, validated mcon::TriMesh (orient_and_validate).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "base/parallel_blocks.h"
#include "capi/capi_handles.h"

using namespace mcon;
using namespace mcon::capi;

mcon_mesh_t::~mcon_mesh_t() { release_owned(context); }

namespace {

// The first published mcon_mesh_desc ended with triangle_count; index_format was appended.
constexpr std::size_t kMeshDescMinSize = offsetof(mcon_mesh_desc, index_format);
// An older caller's struct has no tail padding the appended field could be read from (docs/api.md).
static_assert(kMeshDescMinSize % alignof(mcon_mesh_desc) == 0);

// The last byte read is (count - 1) * stride + element bytes: it must be addressable.
void require_addressable(std::size_t count, std::size_t stride, std::size_t element, const char* what) {
  if (count == 0) return;
  require((count - 1) <= (std::numeric_limits<std::size_t>::max() - element) / stride, MCON_ERROR_INVALID_ARGUMENT,
          std::string(what) + ": " + std::to_string(count) + " elements " + std::to_string(stride) +
              " bytes apart overflow the address space");
}

}  // namespace

std::unique_ptr<mcon_mesh_t> mcon::capi::make_mesh(mcon_context context, const mcon_mesh_desc* desc,
                                                   OrientationRule rule) {
  require_pointer(desc, "desc");
  auto defaults = zeroed_struct<mcon_mesh_desc>();
  auto d = read_options(desc, kMeshDescMinSize, "mcon_mesh_desc", defaults);
  // An older caller's struct ends before index_format (or inside it): its indices are uint32.
  if (desc->struct_size < offsetof(mcon_mesh_desc, index_format) + sizeof(d.index_format))
    d.index_format = MCON_INDEX_FORMAT_UINT32;
  require(d.index_format == MCON_INDEX_FORMAT_UINT32 || d.index_format == MCON_INDEX_FORMAT_INT32 ||
              d.index_format == MCON_INDEX_FORMAT_INT64,
          MCON_ERROR_INVALID_ARGUMENT,
          "index_format " + std::to_string(d.index_format) +
              " is not an mcon_index_format (MCON_INDEX_FORMAT_UINT32 = 0, INT32 = 1, INT64 = 2)");
  require(d.position_type == MCON_SCALAR_FLOAT32 || d.position_type == MCON_SCALAR_FLOAT64, MCON_ERROR_INVALID_ARGUMENT,
          "position_type " + std::to_string(d.position_type) +
              " is not an mcon_scalar_type (set MCON_SCALAR_FLOAT32 = 1 or MCON_SCALAR_FLOAT64 = 2)");

  require((d.flags & ~static_cast<std::uint32_t>(MCON_MESH_VALIDATE_LOCALLY)) == 0, MCON_ERROR_INVALID_ARGUMENT,
          "flags " + std::to_string(d.flags) + " has bits that are not mcon_mesh_flags (MCON_MESH_VALIDATE_LOCALLY = 1)");
  const bool locally = (d.flags & MCON_MESH_VALIDATE_LOCALLY) != 0;

  MeshArrays arrays;
  arrays.positions = d.positions;
  arrays.positions_are_double = d.position_type == MCON_SCALAR_FLOAT64;
  arrays.position_stride = d.position_stride;
  arrays.vertex_count = d.vertex_count;
  arrays.indices = d.indices;
  arrays.index_type = d.index_format == MCON_INDEX_FORMAT_INT64   ? IndexType::int64
                      : d.index_format == MCON_INDEX_FORMAT_INT32 ? IndexType::int32
                                                                  : IndexType::uint32;
  arrays.index_stride = d.index_stride;
  arrays.triangle_count = d.triangle_count;
  const std::size_t scalar = arrays.positions_are_double ? sizeof(double) : sizeof(float);
  require_addressable(d.vertex_count, d.position_stride ? d.position_stride : 3 * scalar, 3 * scalar, "positions");
  const std::size_t triangle_bytes = 3 * index_size(arrays.index_type);
  require_addressable(d.triangle_count, d.index_stride ? d.index_stride : triangle_bytes, triangle_bytes, "indices");

  auto mesh = std::make_unique<mcon_mesh_t>();
  run_in_arena(context, [&] {
    mesh->mesh = copy_mesh_arrays(arrays);
    mesh->orientation = orient_and_validate(mesh->mesh, rule, locally ? DefectPolicy::defer : DefectPolicy::reject);
  });
  mesh->validated_locally = locally;
  return mesh;
}

extern "C" {

mcon_status mcon_mesh_desc_init_sized(mcon_mesh_desc* desc, size_t struct_size) {
  // position_type stays 0: the caller must say whether positions are floats or doubles.
  return init_struct("mcon_mesh_desc_init_sized", desc, struct_size, kMeshDescMinSize, "desc",
                     zeroed_struct<mcon_mesh_desc>());
}

mcon_status mcon_mesh_create(mcon_context context, const mcon_mesh_desc* desc, mcon_mesh* out_mesh) {
  return guard_create("mcon_mesh_create", out_mesh, "out_mesh", context, "context", [&] {
    auto mesh = make_mesh(context, desc, OrientationRule::outward);
    retain_owned(context);
    mesh->context = context;
    *out_mesh = mesh.release();
  });
}

mcon_status mcon_mesh_retain(mcon_mesh mesh) {
  return guard("mcon_mesh_retain", [&] { retain(mesh, "mesh"); });
}

mcon_status mcon_mesh_release(mcon_mesh mesh) {
  return guard("mcon_mesh_release", [&] { release(mesh, "mesh"); });
}

mcon_status mcon_mesh_get_counts(mcon_mesh mesh, size_t* vertex_count, size_t* triangle_count) {
  return guard_object("mcon_mesh_get_counts", mesh, "mesh", [&] {
    require_pointer(vertex_count, "vertex_count");
    require_pointer(triangle_count, "triangle_count");
    *vertex_count = mesh->mesh.positions.size();
    *triangle_count = mesh->mesh.triangles.size();
  });
}

mcon_status mcon_mesh_orientation_info_init_sized(mcon_mesh_orientation_info* info, size_t struct_size) {
  return init_struct("mcon_mesh_orientation_info_init_sized", info, struct_size, sizeof(mcon_mesh_orientation_info),
                     "info", zeroed_struct<mcon_mesh_orientation_info>());
}

mcon_status mcon_mesh_get_orientation(mcon_mesh mesh, mcon_mesh_orientation_info* info) {
  return guard_object("mcon_mesh_get_orientation", mesh, "mesh", [&] {
    const OrientationReport& r = mesh->orientation;
    auto v = zeroed_struct<mcon_mesh_orientation_info>();
    v.reoriented_triangles = static_cast<std::size_t>(r.reoriented_triangles);
    v.component_count = static_cast<std::uint32_t>(r.components);
    v.closed_component_count = static_cast<std::uint32_t>(r.closed_components);
    v.inconsistent_component_count = static_cast<std::uint32_t>(r.inconsistent_components);
    v.outward_turned_component_count = static_cast<std::uint32_t>(r.components_turned_outward);
    write_info(info, sizeof(mcon_mesh_orientation_info), "mcon_mesh_orientation_info", v);
  });
}

mcon_status mcon_mesh_get_reoriented_triangles(mcon_mesh mesh, uint8_t* out_flags, size_t capacity) {
  return guard_object("mcon_mesh_get_reoriented_triangles", mesh, "mesh", [&] {
    const auto& flags = mesh->orientation.reoriented;
    require_pointer(out_flags, "out_flags");
    require(capacity >= flags.size(), MCON_ERROR_BUFFER_TOO_SMALL,
            "out_flags: capacity " + std::to_string(capacity) + " < " + std::to_string(flags.size()) + " triangles");
    std::copy(flags.begin(), flags.end(), out_flags);
  });
}

mcon_status mcon_mesh_get_triangles(mcon_mesh mesh, uint32_t* out_indices, size_t capacity) {
  return guard_object("mcon_mesh_get_triangles", mesh, "mesh", [&] {
    write_rows<3>(mesh->mesh.triangles, out_indices, capacity, "out_indices", "out_indices (capacity in indices)");
  });
}

mcon_status mcon_mesh_closest_points(mcon_mesh mesh, const double* xyz, size_t count, uint32_t* out_triangles,
                                     double* out_barycentric, double* out_distances) {
  return guard_object("mcon_mesh_closest_points", mesh, "mesh", [&] {
    const TriangleTree3D& tree = mesh->closest_tree.over(mesh->mesh);
    write_closest_points(mesh->context, tree, xyz, count, out_triangles, out_barycentric, out_distances);
  });
}

}  // extern "C"

namespace mcon::capi {

void write_closest_points(mcon_context context, const TriangleTree3D& tree, const double* xyz, std::size_t count,
                          std::uint32_t* out_triangles, double* out_barycentric, double* out_distances) {
  if (count == 0) return;
  require_pointer(xyz, "xyz");
  for (std::size_t i = 0; i < 3 * count; ++i)
    require(std::isfinite(xyz[i]), MCON_ERROR_NON_FINITE,
            "xyz: coordinate " + std::to_string(i % 3) + " of point " + std::to_string(i / 3) + " is not finite");
  std::vector<ClosestSurfacePoint> found(count);
  // Each point on its own: the same answers on any thread count (the tree's ties go to the lowest
  // triangle). Written out only once every point is found.
  run_in_arena(context, [&] {
    for_each_block(count, std::size_t{256}, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i)
        found[i] = tree.closest(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
    });
  });
  for (std::size_t i = 0; i < count; ++i) {
    if (out_triangles) out_triangles[i] = static_cast<std::uint32_t>(found[i].point.triangle);
    if (out_barycentric)
      for (int k = 0; k < 3; ++k) out_barycentric[3 * i + k] = found[i].point.barycentric[k];
    if (out_distances) out_distances[i] = std::sqrt(found[i].squared_distance);
  }
}

}  // namespace mcon::capi
