// Meshes: strided caller arrays -> a validated, copied mcon::TriMesh (mesh_from_arrays).
#include <limits>

#include "capi/capi_handles.h"

using namespace mcon;
using namespace mcon::capi;

mcon_mesh_t::~mcon_mesh_t() { release_owned(context); }

namespace {

// The last byte read is (count - 1) * stride + element bytes: it must be addressable.
void require_addressable(std::size_t count, std::size_t stride, std::size_t element, const char* what) {
  if (count == 0) return;
  require((count - 1) <= (std::numeric_limits<std::size_t>::max() - element) / stride, MCON_ERROR_INVALID_ARGUMENT,
          std::string(what) + ": " + std::to_string(count) + " elements " + std::to_string(stride) +
              " bytes apart overflow the address space");
}

}  // namespace

extern "C" {

mcon_status mcon_mesh_desc_init(mcon_mesh_desc* desc) {
  // position_type stays 0: the caller must say whether positions are floats or doubles.
  return init_struct("mcon_mesh_desc_init", desc, "desc", zeroed_struct<mcon_mesh_desc>());
}

mcon_status mcon_mesh_create(mcon_context context, const mcon_mesh_desc* desc, mcon_mesh* out_mesh) {
  return guard_create("mcon_mesh_create", out_mesh, "out_mesh", context, "context", [&] {
    require_pointer(desc, "desc");
    auto defaults = zeroed_struct<mcon_mesh_desc>();
    const auto d = read_options(desc, sizeof(mcon_mesh_desc), "mcon_mesh_desc", defaults);
    require(d.position_type == MCON_SCALAR_FLOAT32 || d.position_type == MCON_SCALAR_FLOAT64,
            MCON_ERROR_INVALID_ARGUMENT,
            "position_type " + std::to_string(d.position_type) +
                " is not an mcon_scalar_type (set MCON_SCALAR_FLOAT32 = 1 or MCON_SCALAR_FLOAT64 = 2)");

    MeshArrays arrays;
    arrays.positions = d.positions;
    arrays.positions_are_double = d.position_type == MCON_SCALAR_FLOAT64;
    arrays.position_stride = d.position_stride;
    arrays.vertex_count = d.vertex_count;
    arrays.indices = d.indices;
    arrays.index_stride = d.index_stride;
    arrays.triangle_count = d.triangle_count;
    const std::size_t scalar = arrays.positions_are_double ? sizeof(double) : sizeof(float);
    require_addressable(d.vertex_count, d.position_stride ? d.position_stride : 3 * scalar, 3 * scalar,
                        "positions");
    require_addressable(d.triangle_count, d.index_stride ? d.index_stride : 12, 12, "indices");

    auto mesh = std::make_unique<mcon_mesh_t>();
    mesh->mesh = run_in_arena(context, [&] { return mesh_from_arrays(arrays); });
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

}  // extern "C"
