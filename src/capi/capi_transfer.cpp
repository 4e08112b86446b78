// Constraint transfer through a map: points, polylines (re-traced on the target), per-vertex
// fields by kind and integer labels (field_transfer.h, polyline_transfer.h).
#include <cmath>

#include "capi/capi_map_handles.h"
#include "transfer/field_transfer.h"

using namespace mcon;
using namespace mcon::capi;

mcon_polyline_set_t::~mcon_polyline_set_t() { release_owned(patch); }

namespace {

// Source points from the caller's arrays (validated: triangle range, finite, on the triangle).
std::vector<SurfacePoint> read_points(const Patch& source, const uint32_t* triangles, const double* barycentric,
                                            std::size_t count) {
  if (count > 0) {
    require_pointer(triangles, "triangles");
    require_pointer(barycentric, "barycentric");
  }
  std::vector<SurfacePoint> points(count);
  const std::size_t nt = source.mesh.triangles.size();
  for (std::size_t i = 0; i < count; ++i) {
    require(triangles[i] < nt, MCON_ERROR_INVALID_ARGUMENT,
            "point " + std::to_string(i) + ": triangle " + std::to_string(triangles[i]) +
                " is out of range (the source patch has " + std::to_string(nt) + " triangles)");
    const Vec3 b(barycentric[3 * i], barycentric[3 * i + 1], barycentric[3 * i + 2]);
    points[i].triangle = static_cast<int>(triangles[i]);
    points[i].barycentric =
        checked_barycentric(points[i].triangle, b, static_cast<int>(nt), "point " + std::to_string(i));
  }
  return points;
}

struct VertexCounts {
  std::size_t source, target;
};

// The array sizes of a per-vertex transfer (values or labels, `dimension` per vertex): the input
// holds exactly source vertices x dimension items (`count`, named `count_name` in the message) and
// the output room for target vertices x dimension (`capacity`, described by `capacity_name`).
VertexCounts require_vertex_array_sizes(const mcon_map_t& map, std::uint32_t dimension, std::size_t count,
                                        const char* count_name, std::size_t capacity, const char* capacity_name) {
  const VertexCounts n{map.map.source_to_target.size(), map.map.target_to_source.size()};
  require(count == n.source * dimension, MCON_ERROR_INVALID_ARGUMENT,
          std::string(count_name) + " is " + std::to_string(count) +
              ", expected source vertices x dimension = " + std::to_string(n.source * dimension));
  require_capacity(capacity, n.target * dimension, capacity_name);
  return n;
}

// mcon_map_transfer_field for double or float values: checked, widened to double, transferred in
// double and written back as Scalar (so the float call equals the double call on the widened input,
// rounded once).
// k: the caller's mcon_field_kind as its bits (enum_bits at the entry point: a value outside the
// enum must not be loaded as the enum type).
template <typename Scalar>
void transfer_field(const mcon_map_t& map, std::int32_t k, std::uint32_t dimension, const Scalar* source_values,
                    std::size_t value_count, Scalar* out_values, std::size_t capacity, const char* capacity_name) {
  require(k != MCON_FIELD_INTEGER_LABEL, MCON_ERROR_INVALID_ARGUMENT,
          "integer labels are never interpolated: use mcon_map_transfer_labels");
  require(k == MCON_FIELD_SCALAR || k == MCON_FIELD_VECTOR3 || k == MCON_FIELD_TANGENT_VECTOR || k == MCON_FIELD_UV,
          MCON_ERROR_INVALID_ARGUMENT, "kind " + std::to_string(k) + " is not an mcon_field_kind");
  const std::uint32_t needed_dim = k == MCON_FIELD_UV ? 2u : (k == MCON_FIELD_SCALAR ? 0u : 3u);
  if (needed_dim == 0)
    require(dimension >= 1, MCON_ERROR_INVALID_ARGUMENT, "a scalar field needs dimension >= 1");
  else
    require(dimension == needed_dim, MCON_ERROR_INVALID_ARGUMENT,
            "this field kind has dimension " + std::to_string(needed_dim) + ", not " + std::to_string(dimension));
  require_pointer(source_values, "source_values");
  require_pointer(out_values, "out_values");
  const auto [ns, nt] =
      require_vertex_array_sizes(map, dimension, value_count, "value_count", capacity, capacity_name);
  for (std::size_t i = 0; i < value_count; ++i)
    require(std::isfinite(source_values[i]), MCON_ERROR_NON_FINITE,
            "source_values[" + std::to_string(i) + "] is not finite");
  const MapView view = map.view();
  if (k == MCON_FIELD_TANGENT_VECTOR) {
    std::vector<Vec3> v(ns);
    for (std::size_t i = 0; i < ns; ++i)
      v[i] = Vec3(static_cast<double>(source_values[3 * i]), static_cast<double>(source_values[3 * i + 1]),
                  static_cast<double>(source_values[3 * i + 2]));
    const std::vector<Vec3> out = transfer_tangent_vectors(view, v);
    for (std::size_t w = 0; w < nt; ++w)
      for (int c = 0; c < 3; ++c) out_values[3 * w + c] = static_cast<Scalar>(out[w][c]);
    return;
  }
  const Eigen::MatrixXd in =
      Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          source_values, static_cast<Eigen::Index>(ns), static_cast<Eigen::Index>(dimension))
          .template cast<double>();
  const Eigen::MatrixXd out = transfer_interpolated(view, in);
  for (std::size_t w = 0; w < nt; ++w)
    for (std::size_t c = 0; c < dimension; ++c)
      out_values[dimension * w + c] =
          static_cast<Scalar>(out(static_cast<Eigen::Index>(w), static_cast<Eigen::Index>(c)));
}

}  // namespace

extern "C" {

mcon_status mcon_map_transfer_points(mcon_map map, const uint32_t* triangles, const double* barycentric, size_t count,
                                     uint32_t* out_triangles, double* out_barycentric, double* out_xyz,
                                     size_t capacity) {
  return guard_object("mcon_map_transfer_points", map, "map", [&] {
    const std::vector<SurfacePoint> points = read_points(map->source->patch, triangles, barycentric, count);
    if (out_triangles == nullptr && out_barycentric == nullptr && out_xyz == nullptr) return;
    require_capacity(capacity, count, "outputs (capacity in points)");
    const PolylineTransfer transfer(map->view());
    const Patch& target = map->target->patch;
    for (std::size_t i = 0; i < count; ++i) {
      const SurfacePoint q = transfer.map_point(points[i]);
      const bool inside = q.triangle >= 0;
      Vec3 x = Vec3::Zero();
      if (inside) {
        const Tri& t = target.mesh.triangles[q.triangle];
        x = to_host(target, q.barycentric[0] * target.mesh.positions[t[0]] +
                                q.barycentric[1] * target.mesh.positions[t[1]] +
                                q.barycentric[2] * target.mesh.positions[t[2]]);
      }
      if (out_triangles) out_triangles[i] = inside ? static_cast<uint32_t>(q.triangle) : MCON_INVALID_INDEX;
      for (int k = 0; k < 3; ++k) {
        if (out_barycentric) out_barycentric[3 * i + k] = inside ? q.barycentric[k] : 0.0;
        if (out_xyz) out_xyz[3 * i + k] = inside ? x[k] : 0.0;
      }
    }
  });
}

mcon_status mcon_map_transfer_polylines(mcon_map map, const uint32_t* triangles, const double* barycentric,
                                        size_t point_count, const uint32_t* polyline_sizes,
                                        const uint8_t* polyline_closed, size_t polyline_count,
                                        mcon_polyline_set* out_polylines) {
  return guard_object("mcon_map_transfer_polylines", map, "map", [&] {
    require_pointer(out_polylines, "out_polylines");
    *out_polylines = nullptr;
    if (polyline_count > 0) require_pointer(polyline_sizes, "polyline_sizes");
    const std::vector<SurfacePoint> points = read_points(map->source->patch, triangles, barycentric, point_count);
    std::vector<PolylineInput> inputs(polyline_count);
    std::size_t used = 0;
    for (std::size_t i = 0; i < polyline_count; ++i) {
      const bool closed = polyline_closed != nullptr && polyline_closed[i] != 0;
      const std::size_t n = polyline_sizes[i];
      require(n >= (closed ? 3u : 2u), MCON_ERROR_INVALID_ARGUMENT,
              "polyline " + std::to_string(i) + " has " + std::to_string(n) + " points (an open polyline needs 2, a " +
                  "closed one 3)");
      require(n <= point_count - used, MCON_ERROR_INVALID_ARGUMENT,
              "polyline_sizes add up to more than point_count (" + std::to_string(point_count) + ")");
      inputs[i].closed = closed;
      inputs[i].points.assign(points.begin() + static_cast<std::ptrdiff_t>(used),
                              points.begin() + static_cast<std::ptrdiff_t>(used + n));
      used += n;
    }
    require(used == point_count, MCON_ERROR_INVALID_ARGUMENT,
            "polyline_sizes add up to " + std::to_string(used) + ", not point_count " + std::to_string(point_count));

    auto set = std::make_unique<mcon_polyline_set_t>();
    set->polylines = run_in_arena(map->context, [&] { return PolylineTransfer(map->view()).map_polylines(inputs); });
    const Patch& target = map->target->patch;
    for (TracedPolyline& p : set->polylines) {
      for (Vec3& x : p.positions) x = to_host(target, x);
      set->point_count += p.points.size();
    }
    retain_owned(map->target);
    set->patch = map->target;
    set->context = map->target->context;
    *out_polylines = set.release();
  });
}

mcon_status mcon_polyline_set_retain(mcon_polyline_set polylines) {
  return guard("mcon_polyline_set_retain", [&] { retain(polylines, "polyline set"); });
}

mcon_status mcon_polyline_set_release(mcon_polyline_set polylines) {
  return guard("mcon_polyline_set_release", [&] { release(polylines, "polyline set"); });
}

mcon_status mcon_polyline_set_get_counts(mcon_polyline_set polylines, size_t* polyline_count, size_t* point_count) {
  return guard_object("mcon_polyline_set_get_counts", polylines, "polyline set", [&] {
    require_pointer(polyline_count, "polyline_count");
    require_pointer(point_count, "point_count");
    *polyline_count = polylines->polylines.size();
    *point_count = polylines->point_count;
  });
}

mcon_status mcon_polyline_set_get_polylines(mcon_polyline_set polylines, uint32_t* out_sizes, uint8_t* out_closed,
                                            uint32_t* out_input_polyline, size_t capacity) {
  return guard_object("mcon_polyline_set_get_polylines", polylines, "polyline set", [&] {
    const auto& p = polylines->polylines;
    if (out_sizes == nullptr && out_closed == nullptr && out_input_polyline == nullptr) return;
    require_capacity(capacity, p.size(), "polyline arrays (capacity in polylines)");
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (out_sizes) out_sizes[i] = static_cast<uint32_t>(p[i].points.size());
      if (out_closed) out_closed[i] = p[i].closed ? 1 : 0;
      if (out_input_polyline) out_input_polyline[i] = static_cast<uint32_t>(p[i].input);
    }
  });
}

mcon_status mcon_polyline_set_get_points(mcon_polyline_set polylines, uint32_t* out_triangles,
                                         double* out_barycentric, double* out_xyz, size_t capacity) {
  return guard_object("mcon_polyline_set_get_points", polylines, "polyline set", [&] {
    if (out_triangles == nullptr && out_barycentric == nullptr && out_xyz == nullptr) return;
    require_capacity(capacity, polylines->point_count, "point arrays (capacity in points)");
    std::size_t i = 0;
    for (const TracedPolyline& p : polylines->polylines)
      for (std::size_t j = 0; j < p.points.size(); ++j, ++i) {
        if (out_triangles) out_triangles[i] = static_cast<uint32_t>(p.points[j].triangle);
        for (int k = 0; k < 3; ++k) {
          if (out_barycentric) out_barycentric[3 * i + k] = p.points[j].barycentric[k];
          if (out_xyz) out_xyz[3 * i + k] = p.positions[j][k];
        }
      }
  });
}

mcon_status mcon_map_transfer_field(mcon_map map, mcon_field_kind kind, uint32_t dimension,
                                    const double* source_values, size_t value_count, double* out_values,
                                    size_t capacity) {
  const std::int32_t k = enum_bits(kind);
  return guard_object("mcon_map_transfer_field", map, "map", [&] {
    transfer_field(*map, k, dimension, source_values, value_count, out_values, capacity,
                   "out_values (capacity in doubles)");
  });
}

mcon_status mcon_map_transfer_field_f32(mcon_map map, mcon_field_kind kind, uint32_t dimension,
                                        const float* source_values, size_t value_count, float* out_values,
                                        size_t capacity) {
  const std::int32_t k = enum_bits(kind);
  return guard_object("mcon_map_transfer_field_f32", map, "map", [&] {
    transfer_field(*map, k, dimension, source_values, value_count, out_values, capacity,
                   "out_values (capacity in floats)");
  });
}

mcon_status mcon_map_transfer_labels(mcon_map map, uint32_t dimension, const int32_t* source_labels,
                                     size_t label_count, int32_t outside_label, int32_t* out_labels,
                                     size_t capacity) {
  return guard_object("mcon_map_transfer_labels", map, "map", [&] {
    require(dimension >= 1 && dimension <= 65536u, MCON_ERROR_INVALID_ARGUMENT,
            "dimension must be in [1, 65536] (got " + std::to_string(dimension) + ")");
    require_pointer(source_labels, "source_labels");
    require_pointer(out_labels, "out_labels");
    require_vertex_array_sizes(*map, dimension, label_count, "label_count", capacity,
                               "out_labels (capacity in labels)");
    const std::vector<std::int32_t> in(source_labels, source_labels + label_count);
    const std::vector<std::int32_t> out = transfer_labels(map->view(), static_cast<int>(dimension), in, outside_label);
    std::copy(out.begin(), out.end(), out_labels);
  });
}

}  // extern "C"
