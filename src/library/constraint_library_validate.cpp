// Meaning checks for library contents. The loader runs them after the FlatBuffers Verifier has
// proven the buffer is structurally safe to read; add_entry runs the same checks, so whatever a
// library holds is exactly what a loader accepts. Indices, lengths and values all come from
// third-party files: each check names the entry and the element that failed.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "library/constraint_library.h"
#include "base/error.h"
#include "base/text.h"
#include "mesh/mesh_topology.h"
#include "retrieval/retrieval_descriptors.h"

namespace mcon {
namespace {

// Barycentric weights are computed in double by the writer; this only absorbs round-off.
constexpr double kBarycentricTolerance = 1e-6;
constexpr std::uint32_t kMaxRings = 256;
constexpr std::int32_t kMinIndexQuarters = 4 - 16;  // valence 16
constexpr std::int32_t kMaxIndexQuarters = 4 - 1;   // valence 1

// Checks build their message only on failure: the per-value loops run over whole libraries.
class Checker {
 public:
  Checker(mcon_status status, std::string where) : status_(status), where_(std::move(where)) {}

  [[noreturn]] void fail_with(const std::string& what) const { fail(status_, where_ + ": " + what); }

  void operator()(bool ok, const std::string& what) const {
    if (!ok) fail_with(what);
  }

  // Stored strings are UTF-8 without NUL bytes (base/text.h says why).
  void text(const std::string& s, const std::string& what) const {
    const std::string problem = text_problem(s);
    if (!problem.empty()) fail_with(what + " " + problem);
  }

  template <typename T>
  void finite(const std::vector<T>& values, const std::string& what) const {
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i])) fail_with(what + " value " + std::to_string(i) + " is not finite");
  }

  // `count` items of `per_item` values each, without overflow (counts come from the file).
  void length(std::size_t actual, std::size_t count, std::size_t per_item, const std::string& what,
              const std::string& expected) const {
    const bool overflow = per_item != 0 && count > std::numeric_limits<std::size_t>::max() / per_item;
    if (overflow || actual != count * per_item)
      fail_with(what + " has " + std::to_string(actual) + " values, expected " + expected + " = " +
                (overflow ? std::string("too many") : std::to_string(count * per_item)));
  }

  // `what()` names the point, e.g. "guide 2 point 5".
  template <typename What>
  void surface_point(const SurfacePoint& p, std::size_t triangle_count, const What& what) const {
    if (p.triangle < 0 || static_cast<std::size_t>(p.triangle) >= triangle_count)
      fail_with(what() + " lies on triangle " + std::to_string(p.triangle) + " of " + std::to_string(triangle_count));
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
      const double b = p.barycentric[k];
      if (!(std::isfinite(b) && b >= -kBarycentricTolerance && b <= 1 + kBarycentricTolerance))
        fail_with(what() + " has barycentric weight " + std::to_string(k) + " = " + std::to_string(b) +
                  " outside [0, 1]");
      sum += b;
    }
    if (!(std::abs(sum - 1) <= kBarycentricTolerance))
      fail_with(what() + " has barycentric weights summing to " + std::to_string(sum) + ", not 1");
  }

 private:
  mcon_status status_;
  std::string where_;
};

// Names come from files: keep messages short and printable (cut at a character boundary).
std::string quoted(const std::string& name) {
  std::size_t length = std::min<std::size_t>(name.size(), 64);
  while (length < name.size() && length > 0 && (static_cast<unsigned char>(name[length]) & 0xc0) == 0x80) --length;
  return "'" + printable_text(std::string_view(name).substr(0, length)) + (length < name.size() ? "...'" : "'");
}

void check_polyline(const Checker& check, const ConstraintPolyline& line, std::size_t triangle_count,
                    const std::string& what) {
  const std::size_t minimum = line.closed ? 3 : 2;
  check(line.points.size() >= minimum, what + " has " + std::to_string(line.points.size()) +
                                           " points, needs at least " + std::to_string(minimum) +
                                           (line.closed ? " (closed)" : ""));
  for (std::size_t i = 0; i < line.points.size(); ++i)
    check.surface_point(line.points[i], triangle_count, [&] { return what + " point " + std::to_string(i); });
}

void check_field(const Checker& check, const VertexField& field, std::size_t n, const std::string& what) {
  check(!field.name.empty(), what + " has an empty name");
  std::uint32_t fixed_dimension = 0;  // 0: any dimension >= 1
  bool integer = false;
  switch (field.kind) {
    case FieldKind::scalar:
      break;
    case FieldKind::vector3:
    case FieldKind::tangent_vector:
      fixed_dimension = 3;
      break;
    case FieldKind::uv:
      fixed_dimension = 2;
      break;
    case FieldKind::integer_label:
      integer = true;
      break;
    default:
      check.fail_with(what + " has unknown kind " + std::to_string(static_cast<unsigned>(field.kind)) +
                       " (a newer format, or a corrupt file)");
  }
  check(field.dimension >= 1, what + " has dimension 0");
  check(fixed_dimension == 0 || field.dimension == fixed_dimension,
        what + " has dimension " + std::to_string(field.dimension) + ", its kind needs " +
            std::to_string(fixed_dimension));
  const std::string expected = std::to_string(n) + " vertices * " + std::to_string(field.dimension);
  if (integer) {
    check.length(field.labels.size(), n, field.dimension, what + " labels", expected);
    check(field.values.empty(), what + " is an integer label field but has float values");
  } else {
    check.length(field.values.size(), n, field.dimension, what + " values", expected);
    check(field.labels.empty(), what + " is not an integer label field but has integer labels");
    check.finite(field.values, what);
  }
}

void check_mesh(const Checker& check, const MacroConstraint& e) {
  const std::size_t n = e.vertex_count(), m = e.triangle_count();
  check(e.positions.size() % 3 == 0, "positions has " + std::to_string(e.positions.size()) +
                                         " values, not a multiple of 3");
  check(e.triangles.size() % 3 == 0, "triangles has " + std::to_string(e.triangles.size()) +
                                         " indices, not a multiple of 3");
  check(n >= 3 && m >= 1, "the patch mesh is empty (" + std::to_string(n) + " vertices, " + std::to_string(m) +
                              " triangles)");
  check(n <= static_cast<std::size_t>(std::numeric_limits<int>::max()) &&
            m <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
        "the patch mesh has more than 2^31 - 1 vertices or triangles");
  for (std::size_t i = 0; i < e.positions.size(); ++i)
    if (!std::isfinite(e.positions[i])) check.fail_with("vertex " + std::to_string(i / 3) + " has a non-finite coordinate");
  for (std::size_t t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = e.triangles[3 * t + k];
      if (v >= n)
        check.fail_with("triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) + " of " + std::to_string(n));
    }
  const TriMesh mesh = entry_mesh(e);
  try {
    validate_mesh(mesh);
  } catch (const Error& err) {
    const char* name = status_name(err.status());
    check.fail_with(std::string("patch mesh: ") + (name ? name : "error") + ": " + err.what());
  }
  // A macro constraint is a geodesic disk: one component, one boundary loop, Euler characteristic 1.
  const MeshTopology topology = build_topology(mesh);
  std::vector<int> component_of;
  const int components = triangle_components(mesh, topology, component_of);
  const int chi = euler_characteristic(mesh, topology);
  check(components == 1 && topology.boundary_loops.size() == 1 && chi == 1,
        "patch mesh is not a topological disk (" + std::to_string(components) + " components, " +
            std::to_string(topology.boundary_loops.size()) + " boundary loops, Euler characteristic " +
            std::to_string(chi) + ")");
}

}  // namespace

std::string entry_label(std::size_t index, const std::string& name) {
  return "entry " + std::to_string(index) + " " + quoted(name);
}

void validate_retrieval_config(const RetrievalConfig& c, mcon_status status) {
  const Checker check(status, "retrieval config");
  const std::size_t d = c.dimension, k = c.vocabulary_size;
  check(!c.descriptor.empty(), "descriptor name is empty");
  check.text(c.descriptor, "descriptor " + quoted(c.descriptor));
  const std::uint32_t builtin = builtin_descriptor_values(c.descriptor);
  check(builtin > 0 || is_custom_descriptor(c.descriptor),
        "unknown descriptor " + quoted(c.descriptor) + " (this build knows " + builtin_descriptor_names() +
            ", and custom:<name>)");
  // 0: no descriptors computed yet (an empty library); otherwise the descriptor's own dimension.
  check(builtin == 0 || d == 0 || d == builtin,
        "descriptor " + quoted(c.descriptor) + " has " + std::to_string(builtin) +
            " values per vertex, the library declares dimension " + std::to_string(d));
  check(c.rings >= 1 && c.rings <= kMaxRings,
        "rings is " + std::to_string(c.rings) + ", expected 1.." + std::to_string(kMaxRings));
  check.length(c.normalization_mean.size(), d, 1, "normalization_mean", "dimension " + std::to_string(d));
  check.length(c.normalization_scale.size(), d, 1, "normalization_scale", "dimension " + std::to_string(d));
  check.finite(c.normalization_mean, "normalization_mean");
  check.finite(c.normalization_scale, "normalization_scale");
  for (std::size_t i = 0; i < c.normalization_scale.size(); ++i)
    if (!(c.normalization_scale[i] > 0))
      check.fail_with("normalization_scale value " + std::to_string(i) + " is not positive");
  check(k == 0 || d > 0, "a vocabulary of " + std::to_string(k) + " words needs a descriptor dimension > 0");
  check.length(c.vocabulary.size(), k, d, "vocabulary",
               "vocabulary_size " + std::to_string(k) + " * dimension " + std::to_string(d));
  check.finite(c.vocabulary, "vocabulary");
  check(std::isfinite(c.sigma_bof) && c.sigma_bof >= 0 && (k == 0 || c.sigma_bof > 0),
        "sigma_bof is " + std::to_string(c.sigma_bof) + ", expected a finite value > 0 (>= 0 without vocabulary)");
}

void validate_library_text(const std::string& text, const std::string& what, mcon_status status) {
  const std::string problem = text_problem(text);
  if (!problem.empty()) fail(status, what + " " + problem);
}

void validate_library_entry(const MacroConstraint& e, std::size_t index, const RetrievalConfig& config,
                            mcon_status status) {
  const Checker check(status, entry_label(index, e.name));
  check.text(e.name, "name");
  check.text(e.class_label, "class_label");
  for (std::size_t i = 0; i < e.tags.size(); ++i) check.text(e.tags[i], "tag " + std::to_string(i));
  check.text(e.author, "author");
  check.text(e.licence, "licence");
  for (std::size_t i = 0; i < e.fields.size(); ++i)
    check.text(e.fields[i].name, "field " + std::to_string(i) + " " + quoted(e.fields[i].name) + " name");
  check(e.id != 0, "id 0 is reserved (it means 'assign one')");
  check_mesh(check, e);
  const std::size_t n = e.vertex_count(), m = e.triangle_count();

  check.surface_point(e.center, m, [] { return std::string("center"); });
  check(std::isfinite(e.source_scale) && e.source_scale > 0,
        "source_scale is " + std::to_string(e.source_scale) + ", expected a finite value > 0");
  for (int k = 0; k < 3; ++k) check(std::isfinite(e.source_origin[k]), "source_origin is not finite");
  if (e.up) {
    const std::array<double, 3>& u = *e.up;
    check(std::isfinite(u[0]) && std::isfinite(u[1]) && std::isfinite(u[2]), "up is not finite");
    check(u[0] != 0 || u[1] != 0 || u[2] != 0, "up is the zero vector (leave it out for no up direction)");
  }

  for (std::size_t i = 0; i < e.guides.size(); ++i) check_polyline(check, e.guides[i], m, "guide " + std::to_string(i));
  for (std::size_t i = 0; i < e.features.size(); ++i)
    check_polyline(check, e.features[i], m, "feature " + std::to_string(i));
  for (std::size_t i = 0; i < e.singularities.size(); ++i) {
    const Singularity& s = e.singularities[i];
    const std::string what = "singularity " + std::to_string(i);
    check.surface_point(s.location, m, [&] { return what; });
    check(s.index_quarters != 0 && s.index_quarters >= kMinIndexQuarters && s.index_quarters <= kMaxIndexQuarters,
          what + " has index_quarters " + std::to_string(s.index_quarters) + ", expected " +
              std::to_string(kMinIndexQuarters) + ".." + std::to_string(kMaxIndexQuarters) + " without 0 (valence 1..16)");
  }
  std::set<std::string> field_names;
  for (std::size_t i = 0; i < e.fields.size(); ++i) {
    const VertexField& f = e.fields[i];
    const std::string what = "field " + std::to_string(i) + " " + quoted(f.name);
    check_field(check, f, n, what);
    check(field_names.insert(f.name).second, what + " repeats a field name");
  }

  check.length(e.descriptors.size(), n, config.dimension, "descriptors",
               std::to_string(n) + " vertices * dimension " + std::to_string(config.dimension));
  check.finite(e.descriptors, "descriptors");
  check.length(e.histogram.size(), config.vocabulary_size, config.rings, "histogram",
               "vocabulary_size " + std::to_string(config.vocabulary_size) + " * rings " + std::to_string(config.rings));
  for (std::size_t i = 0; i < e.histogram.size(); ++i)
    if (!(std::isfinite(e.histogram[i]) && e.histogram[i] >= 0))
      check.fail_with("histogram value " + std::to_string(i) + " is not a finite value >= 0");
}

}  // namespace mcon
