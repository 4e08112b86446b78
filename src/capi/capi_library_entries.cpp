// Library entries: adding (every caller array checked and named before anything changes),
// removing, finding, and reading entries back by index.
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

#include "base/text.h"
#include "capi/capi_library.h"

using namespace mcon;
using namespace mcon::capi;

namespace {

// The first published versions of the entry structs (before has_up): older callers pass these sizes.
constexpr std::size_t kEntryDescMinSize = offsetof(mcon_library_entry_desc, has_up);
// An older caller's struct has no tail padding the appended field could be read from (docs/api.md).
static_assert(kEntryDescMinSize % alignof(mcon_library_entry_desc) == 0);
constexpr std::size_t kEntryInfoMinSize = offsetof(mcon_library_entry_info, has_up);

mcon_library_entry_desc default_entry_desc() {
  auto d = zeroed_struct<mcon_library_entry_desc>();
  return d;
}


// Per-vertex values of one field, checked for finiteness (and float range) per value.
VertexField read_field(const mcon_vertex_field& f, std::size_t n, const std::string& what) {
  VertexField out;
  require(f.name != nullptr && f.name[0] != '\0', MCON_ERROR_INVALID_ARGUMENT, what + ": name is NULL or empty");
  out.name = caller_text(f.name, what + ".name");
  const std::string where = what + " '" + printable_text(out.name) + "'";
  require(f.kind >= MCON_FIELD_SCALAR && f.kind <= MCON_FIELD_UV, MCON_ERROR_INVALID_ARGUMENT,
          where + ": kind " + std::to_string(f.kind) + " is not an mcon_field_kind");
  out.kind = static_cast<FieldKind>(f.kind);
  require(f.dimension >= 1 && f.dimension <= 1024, MCON_ERROR_INVALID_ARGUMENT,
          where + ": dimension " + std::to_string(f.dimension) + " is outside 1..1024");
  out.dimension = f.dimension;
  const std::uint32_t fixed = f.kind == MCON_FIELD_UV ? 2u
                              : (f.kind == MCON_FIELD_VECTOR3 || f.kind == MCON_FIELD_TANGENT_VECTOR) ? 3u
                                                                                                         : 0u;
  require(fixed == 0 || f.dimension == fixed, MCON_ERROR_INVALID_ARGUMENT,
          where + ": dimension " + std::to_string(f.dimension) + ", its kind needs " + std::to_string(fixed));
  if (f.kind == MCON_FIELD_INTEGER_LABEL) {
    require(f.labels != nullptr, MCON_ERROR_NULL_POINTER, where + ": labels is NULL (an INTEGER_LABEL field)");
    const std::size_t row = sizeof(std::int32_t) * f.dimension, step = f.stride == 0 ? row : f.stride;
    require(step >= row, MCON_ERROR_INVALID_ARGUMENT, where + ": stride is smaller than a row");
    const unsigned char* base = reinterpret_cast<const unsigned char*>(f.labels);
    out.labels.resize(n * f.dimension);
    for (std::size_t v = 0; v < n; ++v)
      std::memcpy(&out.labels[v * f.dimension], base + v * step, row);
  } else {
    require(f.values != nullptr, MCON_ERROR_NULL_POINTER, where + ": values is NULL");
    const Eigen::MatrixXd values = read_rows(f.values, n, f.dimension, f.stride, where + " values");
    out.values.resize(n * f.dimension);
    for (std::size_t v = 0; v < n; ++v)
      for (std::uint32_t j = 0; j < f.dimension; ++j) {
        const double x = values(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(j));
        require(std::abs(x) <= std::numeric_limits<float>::max(), MCON_ERROR_NON_FINITE,
                where + ": value " + std::to_string(j) + " of vertex " + std::to_string(v) + " is too large for float");
        out.values[v * f.dimension + j] = static_cast<float>(x);
      }
  }
  return out;
}

// The desc's metadata, constraints and fields as the core's entry (geometry comes later).
MacroConstraint read_content(const mcon_library_entry_desc& d, const Patch& patch) {
  const std::size_t n = patch.mesh.positions.size(), m = patch.mesh.triangles.size();
  MacroConstraint e;
  e.id = d.id;
  e.name = caller_text(d.name, "desc.name");
  e.class_label = caller_text(d.class_label, "desc.class_label");
  e.author = caller_text(d.author, "desc.author");
  e.licence = caller_text(d.licence, "desc.licence");
  require(d.tags != nullptr || d.tag_count == 0, MCON_ERROR_NULL_POINTER, "tags is NULL but tag_count > 0");
  for (std::size_t i = 0; i < d.tag_count; ++i)
    e.tags.push_back(caller_text(d.tags[i], "desc.tags[" + std::to_string(i) + "]"));

  require(d.polylines != nullptr || d.polyline_count == 0, MCON_ERROR_NULL_POINTER,
          "polylines is NULL but polyline_count > 0");
  for (std::size_t i = 0; i < d.polyline_count; ++i) {
    const mcon_polyline& p = d.polylines[i];
    const std::string what = "polylines[" + std::to_string(i) + "]";
    require(p.kind == MCON_POLYLINE_GUIDE || p.kind == MCON_POLYLINE_FEATURE, MCON_ERROR_INVALID_ARGUMENT,
            what + ": kind " + std::to_string(p.kind) + " is not an mcon_polyline_kind (GUIDE 1, FEATURE 2)");
    require(p.points != nullptr || p.point_count == 0, MCON_ERROR_NULL_POINTER, what + ".points is NULL");
    ConstraintPolyline line;
    line.closed = p.closed != 0;
    const std::size_t minimum = line.closed ? 3 : 2;
    require(p.point_count >= minimum, MCON_ERROR_INVALID_ARGUMENT,
            what + " has " + std::to_string(p.point_count) + " points, needs at least " + std::to_string(minimum));
    for (std::size_t j = 0; j < p.point_count; ++j)
      line.points.push_back(read_point(p.points[j], m, what + ".points[" + std::to_string(j) + "]"));
    (p.kind == MCON_POLYLINE_GUIDE ? e.guides : e.features).push_back(std::move(line));
  }

  require(d.singularities != nullptr || d.singularity_count == 0, MCON_ERROR_NULL_POINTER,
          "singularities is NULL but singularity_count > 0");
  for (std::size_t i = 0; i < d.singularity_count; ++i) {
    const mcon_singularity& s = d.singularities[i];
    const std::string what = "singularities[" + std::to_string(i) + "]";
    require(s.index_quarters != 0 && s.index_quarters >= -12 && s.index_quarters <= 3, MCON_ERROR_INVALID_ARGUMENT,
            what + ": index_quarters " + std::to_string(s.index_quarters) + " is outside -12..3 or 0");
    e.singularities.push_back({read_point(s.location, m, what + ".location"), s.index_quarters});
  }

  require(d.fields != nullptr || d.field_count == 0, MCON_ERROR_NULL_POINTER, "fields is NULL but field_count > 0");
  for (std::size_t i = 0; i < d.field_count; ++i)
    e.fields.push_back(read_field(d.fields[i], n, "fields[" + std::to_string(i) + "]"));

  if (d.has_up != 0) {
    require(std::isfinite(d.up[0]) && std::isfinite(d.up[1]) && std::isfinite(d.up[2]), MCON_ERROR_NON_FINITE,
            "desc.up is not finite");
    require(d.up[0] != 0 || d.up[1] != 0 || d.up[2] != 0, MCON_ERROR_INVALID_ARGUMENT,
            "desc.up is the zero vector (set has_up = 0 for no up direction)");
    e.up = std::array<double, 3>{{d.up[0], d.up[1], d.up[2]}};
  }
  return e;
}

mcon_surface_point to_c(const SurfacePoint& p) {
  mcon_surface_point out{};
  out.face = static_cast<std::uint32_t>(p.triangle);
  for (int k = 0; k < 3; ++k) out.barycentric[k] = p.barycentric[k];
  return out;
}

}  // namespace

extern "C" {

mcon_status mcon_library_entry_desc_init_sized(mcon_library_entry_desc* desc, size_t struct_size) {
  return init_struct("mcon_library_entry_desc_init_sized", desc, struct_size, kEntryDescMinSize, "desc",
                     default_entry_desc());
}

mcon_status mcon_library_add_entry(mcon_library library, const mcon_library_entry_desc* desc, uint64_t* out_id) {
  return guard_object("mcon_library_add_entry", library, "library", [&] {
    require_pointer(desc, "desc");
    const auto d = read_options(desc, kEntryDescMinSize, "mcon_library_entry_desc", default_entry_desc());
    check_handle(d.patch, "patch");
    const Patch& patch = d.patch->patch;
    MacroConstraint content = read_content(d, patch);
    Eigen::MatrixXd custom;
    if (d.descriptors != nullptr)
      custom = read_rows(d.descriptors, patch.mesh.positions.size(), d.descriptor_dimension, d.descriptor_stride,
                         "descriptors");
    // Room for the new histogram first: after add_entry nothing may fail.
    const std::size_t length = library->library.retrieval().histogram_length();
    library->flat.reserve(library->flat.size() + length);
    const std::uint64_t id = run_in_arena(library->context, [&] {
      return add_library_entry(library->library, patch, std::move(content), d.descriptors ? &custom : nullptr);
    });
    const MacroConstraint& added = library->library.entries().back();
    // Within the reserved room (an empty library's array is empty whatever its configuration).
    library->flat.insert(library->flat.end(), added.histogram.begin(), added.histogram.end());
    if (out_id) *out_id = id;
  });
}

mcon_status mcon_library_remove_entry(mcon_library library, uint64_t id) {
  return guard_object("mcon_library_remove_entry", library, "library", [&] {
    ConstraintLibrary& lib = library->library;
    const MacroConstraint* e = lib.find_entry(id);
    require(e != nullptr, MCON_ERROR_NOT_FOUND, "no entry has id " + std::to_string(id));
    const std::size_t index = static_cast<std::size_t>(e - lib.entries().data());
    const std::size_t length = lib.retrieval().histogram_length();
    lib.remove_entry(id);
    library->flat.erase(library->flat.begin() + static_cast<std::ptrdiff_t>(index * length),
                        library->flat.begin() + static_cast<std::ptrdiff_t>((index + 1) * length));
  });
}

mcon_status mcon_library_find_entry(mcon_library library, uint64_t id, size_t* out_index) {
  return guard_object("mcon_library_find_entry", library, "library", [&] {
    require_pointer(out_index, "out_index");
    const MacroConstraint* e = library->library.find_entry(id);
    require(e != nullptr, MCON_ERROR_NOT_FOUND, "no entry has id " + std::to_string(id));
    *out_index = static_cast<std::size_t>(e - library->library.entries().data());
  });
}

mcon_status mcon_library_entry_info_init_sized(mcon_library_entry_info* info, size_t struct_size) {
  return init_struct("mcon_library_entry_info_init_sized", info, struct_size, kEntryInfoMinSize, "info",
                     zeroed_struct<mcon_library_entry_info>());
}

mcon_status mcon_library_get_entry_info(mcon_library library, size_t index, mcon_library_entry_info* info) {
  return guard_object("mcon_library_get_entry_info", library, "library", [&] {
    require_pointer(info, "info");
    const MacroConstraint& e = entry_at(library, index);
    auto v = zeroed_struct<mcon_library_entry_info>();
    v.id = e.id;
    v.vertex_count = e.vertex_count();
    v.triangle_count = e.triangle_count();
    v.tag_count = e.tags.size();
    v.polyline_count = e.guides.size() + e.features.size();
    v.singularity_count = e.singularities.size();
    v.field_count = e.fields.size();
    v.center = to_c(e.center);
    v.source_scale = e.source_scale;
    for (int k = 0; k < 3; ++k) v.source_origin[k] = e.source_origin[static_cast<std::size_t>(k)];
    v.has_up = e.up ? 1u : 0u;
    for (int k = 0; k < 3 && e.up; ++k) v.up[k] = (*e.up)[static_cast<std::size_t>(k)];
    write_info(info, kEntryInfoMinSize, "mcon_library_entry_info", v);
  });
}

mcon_status mcon_library_get_entry_string(mcon_library library, size_t index, mcon_entry_string which, size_t item,
                                          char* out_text, size_t capacity, size_t* out_size) {
  return guard_object("mcon_library_get_entry_string", library, "library", [&] {
    const MacroConstraint& e = entry_at(library, index);
    const std::int32_t code = enum_bits(which);
    auto item_of = [&](std::size_t count, const char* what) {
      require(item < count, MCON_ERROR_INVALID_ARGUMENT,
              std::string(what) + " " + std::to_string(item) + " is out of range (the entry has " +
                  std::to_string(count) + ")");
    };
    switch (code) {
      case MCON_ENTRY_NAME:
        return copy_string(e.name, out_text, capacity, out_size);
      case MCON_ENTRY_CLASS_LABEL:
        return copy_string(e.class_label, out_text, capacity, out_size);
      case MCON_ENTRY_AUTHOR:
        return copy_string(e.author, out_text, capacity, out_size);
      case MCON_ENTRY_LICENCE:
        return copy_string(e.licence, out_text, capacity, out_size);
      case MCON_ENTRY_TAG:
        item_of(e.tags.size(), "tag");
        return copy_string(e.tags[item], out_text, capacity, out_size);
      case MCON_ENTRY_FIELD_NAME:
        item_of(e.fields.size(), "field");
        return copy_string(e.fields[item].name, out_text, capacity, out_size);
      default:
        fail(MCON_ERROR_INVALID_ARGUMENT, "which " + std::to_string(code) + " is not an mcon_entry_string");
    }
  });
}

mcon_status mcon_library_get_entry_positions(mcon_library library, size_t index, double* out_xyz, size_t capacity) {
  return guard_object("mcon_library_get_entry_positions", library, "library", [&] {
    const MacroConstraint& e = entry_at(library, index);
    require_pointer(out_xyz, "out_xyz");
    require_capacity(capacity, e.positions.size(), "out_xyz (capacity in doubles)");
    for (std::size_t i = 0; i < e.positions.size(); ++i) out_xyz[i] = static_cast<double>(e.positions[i]);
  });
}

mcon_status mcon_library_get_entry_triangles(mcon_library library, size_t index, uint32_t* out_indices,
                                             size_t capacity) {
  return guard_object("mcon_library_get_entry_triangles", library, "library", [&] {
    const MacroConstraint& e = entry_at(library, index);
    require_pointer(out_indices, "out_indices");
    require_capacity(capacity, e.triangles.size(), "out_indices (capacity in indices)");
    std::copy(e.triangles.begin(), e.triangles.end(), out_indices);
  });
}

mcon_status mcon_library_get_entry_polyline(mcon_library library, size_t index, size_t polyline, uint32_t* out_kind,
                                            uint32_t* out_closed, size_t* out_point_count,
                                            mcon_surface_point* out_points, size_t capacity) {
  return guard_object("mcon_library_get_entry_polyline", library, "library", [&] {
    const MacroConstraint& e = entry_at(library, index);
    const std::size_t total = e.guides.size() + e.features.size();
    require(polyline < total, MCON_ERROR_INVALID_ARGUMENT,
            "polyline " + std::to_string(polyline) + " is out of range (the entry has " + std::to_string(total) + ")");
    const bool guide = polyline < e.guides.size();
    const ConstraintPolyline& line = guide ? e.guides[polyline] : e.features[polyline - e.guides.size()];
    if (out_points) require_capacity(capacity, line.points.size(), "out_points (capacity in points)");
    if (out_kind) *out_kind = guide ? MCON_POLYLINE_GUIDE : MCON_POLYLINE_FEATURE;
    if (out_closed) *out_closed = line.closed ? 1 : 0;
    if (out_point_count) *out_point_count = line.points.size();
    if (out_points)
      for (std::size_t i = 0; i < line.points.size(); ++i) out_points[i] = to_c(line.points[i]);
  });
}

mcon_status mcon_library_get_entry_singularities(mcon_library library, size_t index,
                                                 mcon_singularity* out_singularities, size_t capacity) {
  return guard_object("mcon_library_get_entry_singularities", library, "library", [&] {
    const MacroConstraint& e = entry_at(library, index);
    if (e.singularities.empty()) return;  // nothing to write (out_singularities may be NULL)
    require_pointer(out_singularities, "out_singularities");
    require_capacity(capacity, e.singularities.size(), "out_singularities (capacity in singularities)");
    for (std::size_t i = 0; i < e.singularities.size(); ++i) {
      out_singularities[i] = mcon_singularity{};
      out_singularities[i].location = to_c(e.singularities[i].location);
      out_singularities[i].index_quarters = e.singularities[i].index_quarters;
    }
  });
}

mcon_status mcon_library_get_entry_field(mcon_library library, size_t index, size_t field, uint32_t* out_kind,
                                         uint32_t* out_dimension, double* out_values, int32_t* out_labels,
                                         size_t capacity) {
  return guard_object("mcon_library_get_entry_field", library, "library", [&] {
    const MacroConstraint& e = entry_at(library, index);
    require(field < e.fields.size(), MCON_ERROR_INVALID_ARGUMENT,
            "field " + std::to_string(field) + " is out of range (the entry has " + std::to_string(e.fields.size()) +
                ")");
    const VertexField& f = e.fields[field];
    const bool integer = f.kind == FieldKind::integer_label;
    require(!(integer && out_values), MCON_ERROR_INVALID_ARGUMENT,
            "field '" + f.name + "' holds integer labels: read it with out_labels");
    require(!(!integer && out_labels), MCON_ERROR_INVALID_ARGUMENT,
            "field '" + f.name + "' holds real values: read it with out_values");
    const std::size_t count = integer ? f.labels.size() : f.values.size();
    if (out_values || out_labels) require_capacity(capacity, count, "field values (capacity in values)");
    if (out_kind) *out_kind = static_cast<std::uint32_t>(f.kind);
    if (out_dimension) *out_dimension = f.dimension;
    if (out_values)
      for (std::size_t i = 0; i < count; ++i) out_values[i] = static_cast<double>(f.values[i]);
    if (out_labels) std::copy(f.labels.begin(), f.labels.end(), out_labels);
  });
}

mcon_status mcon_library_get_entry_retrieval(mcon_library library, size_t index, double* out_descriptors,
                                             size_t descriptor_capacity, float* out_histogram,
                                             size_t histogram_capacity) {
  return guard_object("mcon_library_get_entry_retrieval", library, "library", [&] {
    const MacroConstraint& e = entry_at(library, index);
    if (out_descriptors)
      require_capacity(descriptor_capacity, e.descriptors.size(), "out_descriptors (capacity in values)");
    if (out_histogram) require_capacity(histogram_capacity, e.histogram.size(), "out_histogram (capacity in values)");
    if (out_descriptors)
      for (std::size_t i = 0; i < e.descriptors.size(); ++i) out_descriptors[i] = static_cast<double>(e.descriptors[i]);
    if (out_histogram) std::copy(e.histogram.begin(), e.histogram.end(), out_histogram);
  });
}

}  // extern "C"
