// The in-memory constraint library: macro constraints (a normalized disk patch plus the quad-meshing
// constraints it carries and its retrieval data) and the RetrievalConfig they were computed with.
// The types mirror the file schema (schema/macrocon_library.fbs) field for field and use the
// file's scalar types, so a save/load round trip is bit-exact. A ConstraintLibrary only ever holds
// entries that passed validate_library_entry, so anything it holds can be saved and loaded again.
#pragma once

#include <array>
#include <optional>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "macrocon/macrocon.h"
#include "mesh/mesh.h"
#include "mesh/surface_point.h"
#include "retrieval/retrieval_config.h"

namespace mcon {

// Meaning of a per-vertex field; values match the schema's FieldKind.
enum class FieldKind : std::uint8_t {
  scalar = 1,          // dimension >= 1 real channels (values)
  vector3 = 2,         // dimension 3, a vector in patch coordinates (values)
  tangent_vector = 3,  // dimension 3, tangent to the patch (values)
  integer_label = 4,   // dimension >= 1 integer channels (labels)
  uv = 5,              // dimension 2 (values)
};

struct ConstraintPolyline {
  std::vector<SurfacePoint> points;  // >= 2 (>= 3 when closed)
  bool closed = false;               // the last point joins the first
};

// A cross-field singularity. Index in quarter turns: valence = 4 - index_quarters, so +1 is a
// valence-3 vertex (index +1/4) and -1 a valence-5 vertex (index -1/4). Never 0; valence 1..16.
struct Singularity {
  SurfacePoint location;
  std::int32_t index_quarters = 0;
};

struct VertexField {
  std::string name;  // non-empty, unique within its entry
  FieldKind kind = FieldKind::scalar;
  std::uint32_t dimension = 1;     // fixed by the kind for vector3 / tangent_vector (3) and uv (2)
  std::vector<float> values;       // vertex-major, n * dimension (every kind but integer_label)
  std::vector<std::int32_t> labels;  // vertex-major, n * dimension (integer_label only)
};

struct MacroConstraint {
  std::uint64_t id = 0;  // unique, never 0 inside a library (0 asks add_entry to assign one)
  std::string name;
  std::string class_label;
  std::vector<std::string> tags;
  std::string author;
  std::string licence;

  // Patch normalized to geodesic radius 1 around `center`; a valid disk mesh (validate_mesh).
  std::vector<float> positions;            // x, y, z per vertex
  std::vector<std::uint32_t> triangles;    // 3 vertex indices per triangle, CCW
  SurfacePoint center;
  double source_scale = 1.0;               // normalized = (source - source_origin) / source_scale
  std::array<double, 3> source_origin{0.0, 0.0, 0.0};

  std::vector<ConstraintPolyline> guides;    // the quad mesh should follow these
  std::vector<ConstraintPolyline> features;  // the quad mesh must preserve these
  std::vector<Singularity> singularities;
  std::vector<VertexField> fields;

  std::vector<float> descriptors;  // n * RetrievalConfig::dimension, vertex-major
  std::vector<float> histogram;    // RetrievalConfig::histogram_length(), ring-major
  // The source mesh's up direction in its coordinates (finite, not zero), if the author gave one.
  std::optional<std::array<double, 3>> up;

  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t triangle_count() const { return triangles.size() / 3; }
};

// Conversions between the entry's flat float arrays and the core's TriMesh.
TriMesh entry_mesh(const MacroConstraint& entry);
void set_entry_mesh(MacroConstraint& entry, const TriMesh& mesh);

// Throw mcon::Error(status, ...) naming the first problem ("retrieval config: ...",
// "entry 3 'nose_07': triangle 12 uses vertex 900 of 850"). `index` only labels the message.
// Mesh problems found by validate_mesh keep their status name in the message.
void validate_retrieval_config(const RetrievalConfig& config, mcon_status status);
void validate_library_entry(const MacroConstraint& entry, std::size_t index, const RetrievalConfig& config,
                            mcon_status status);

// Library-wide strings (name, description) follow the entries' rule: UTF-8 without NUL bytes.
// Throws mcon::Error(status, "<what> is not valid UTF-8 (...)").
void validate_library_text(const std::string& text, const std::string& what, mcon_status status);

// "entry 3 'nose_07'" for messages (the name shortened and made printable: it comes from files).
std::string entry_label(std::size_t index, const std::string& name);

// Field-by-field equality of two retrieval configurations (a merge requires it).
bool same_retrieval_config(const RetrievalConfig& a, const RetrievalConfig& b);

class ConstraintLibrary {
 public:
  // An empty library with a default (vocabulary-less) configuration.
  ConstraintLibrary() = default;
  // Validates the config and every entry (ids non-zero and unique); throws mcon::Error(status):
  // MCON_ERROR_INVALID_ARGUMENT for callers, MCON_ERROR_INVALID_LIBRARY when loading a file.
  explicit ConstraintLibrary(RetrievalConfig config, std::vector<MacroConstraint> entries = {},
                             mcon_status status = MCON_ERROR_INVALID_ARGUMENT);

  const RetrievalConfig& retrieval() const { return config_; }
  const std::vector<MacroConstraint>& entries() const { return entries_; }
  std::size_t size() const { return entries_.size(); }

  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  void set_name(std::string name) { name_ = std::move(name); }
  void set_description(std::string description) { description_ = std::move(description); }

  // Where a loaded library came from: its file's format version (0 = made in memory) and whether
  // a content checksum was verified (format 2 on; format 1 files carry none).
  struct Origin {
    std::uint32_t format_version = 0;
    bool checksum_verified = false;
  };
  const Origin& origin() const { return origin_; }
  void set_origin(Origin origin) { origin_ = origin; }

  // Validates and appends; id 0 gets (largest id in the library) + 1. Returns the entry's id.
  // A duplicate id or an invalid entry throws MCON_ERROR_INVALID_ARGUMENT and changes nothing.
  std::uint64_t add_entry(MacroConstraint entry);

  // Appends the entry exactly as given (no id assignment), after the constructor's checks
  // (validate_library_entry, id non-zero and unused), throwing `status`. Loaders use it to
  // validate entry by entry as they read them.
  void append_entry(MacroConstraint entry, mcon_status status);

  // Removes the entry (later entries keep their order); MCON_ERROR_NOT_FOUND if absent.
  void remove_entry(std::uint64_t id);

  // nullptr if absent.
  const MacroConstraint* find_entry(std::uint64_t id) const;

  struct IdChange {
    std::uint64_t old_id;
    std::uint64_t new_id;
  };
  // Appends copies of all of `other`'s entries, in order. Both libraries must have the same
  // retrieval config (same_retrieval_config), because histograms over different vocabularies are
  // not comparable: otherwise MCON_ERROR_INVALID_ARGUMENT and the caller recomputes descriptors and
  // histograms with one config first. Incoming entries whose id is already taken are renumbered to
  // fresh ids (largest id so far + 1, in order); the returned list says which. Name and
  // description stay this library's. All or nothing; `other` may be *this.
  std::vector<IdChange> merge(const ConstraintLibrary& other);

 private:
  std::uint64_t next_free_id() const;

  RetrievalConfig config_;
  std::vector<MacroConstraint> entries_;
  std::unordered_map<std::uint64_t, std::size_t> position_of_id_;
  std::string name_;
  Origin origin_;
  std::string description_;
};

}  // namespace mcon
