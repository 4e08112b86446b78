// FlatBuffer -> ConstraintLibrary for hostile input (docs/design.md §6), in this order:
//   1. size within [kLibraryMinBytes, kLibraryMaxBytes] (the Verifier only asserts its limit);
//   2. file identifier "MCLB" (a clear message for files that are not libraries at all);
//   3. format_version (verifying only the root table and that field): absent -> INVALID_LIBRARY,
//      newer than this build -> UNSUPPORTED, whatever the rest of a newer layout looks like;
//   4. flatbuffers::Verifier with explicit depth / table limits: after it, every offset, vector
//      and string the schema reaches lies inside the buffer, so reading is memory-safe;
//   5. copy out into the data model, charging every byte read against the buffer size: a genuine
//      buffer never reuses an object, so a forged one that points many offsets at one big object
//      is stopped before we copy more than the file holds;
//   6. meaning, entry by entry as it is read (so a forged file cannot pile up invalid entries in
//      memory): validate_retrieval_config (a known descriptor of its own dimension) /
//      validate_library_entry / unique ids, the same checks add_entry runs, and every string
//      UTF-8 without NUL bytes, all reported as MCON_ERROR_INVALID_LIBRARY.
// Memory use stays within a small multiple of the buffer size even for forged buffers.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "base/error.h"
#include "base/whole_file.h"
#include "library/library_file.h"
#include "macrocon_library_generated.h"

namespace mcon {
namespace {

namespace fb = mcon::fb;

static_assert(FLATBUFFERS_LITTLEENDIAN, "vectors are copied with memcpy: little-endian hosts only");
static_assert(kLibraryMaxBytes < FLATBUFFERS_MAX_BUFFER_SIZE, "the Verifier asserts size < FLATBUFFERS_MAX_BUFFER_SIZE");

// Tables nest Library -> Entry -> Polyline at most 3 deep today; room for appended nesting.
constexpr flatbuffers::uoffset_t kMaxDepth = 16;

[[noreturn]] void invalid(const std::string& message) { fail(MCON_ERROR_INVALID_LIBRARY, message); }

// Files store triangle indices as uint32; one past INT32_MAX can never name a triangle, so larger
// values are kept out of range (validate_library_entry reports them) instead of wrapping negative.
int triangle_index(std::uint32_t face) {
  return static_cast<int>(std::min<std::uint32_t>(face, static_cast<std::uint32_t>(INT32_MAX)));
}

Vec3 vec3(const std::array<double, 3>& a) { return Vec3(a[0], a[1], a[2]); }

// Every byte copied out is charged here; a buffer without aliasing never exceeds its own size.
class ReadBudget {
 public:
  explicit ReadBudget(std::size_t bytes) : left_(bytes) {}
  void charge(std::size_t bytes) {
    if (bytes > left_)
      invalid("library refers to the same data more than once (aliased FlatBuffer objects are not accepted)");
    left_ -= bytes;
  }

 private:
  std::size_t left_;
};

class Reader {
 public:
  explicit Reader(std::size_t size) : budget_(size) {}

  // The Verifier has checked the vector lies in the buffer and is aligned.
  template <typename T>
  std::vector<T> vector(const flatbuffers::Vector<T>* v) {
    if (!v) return {};
    const std::size_t n = v->size();
    budget_.charge(n * sizeof(T));
    std::vector<T> out(n);
    if (n) std::memcpy(out.data(), v->Data(), n * sizeof(T));
    return out;
  }

  std::string string(const flatbuffers::String* s) {
    if (!s) return {};
    budget_.charge(s->size() + 1);
    return std::string(s->c_str(), s->size());
  }

  // A table costs at least its 4-byte vtable offset.
  void table() { budget_.charge(4); }

  // A vector of offsets costs 4 bytes per element (charged before its elements are read).
  template <typename T>
  flatbuffers::uoffset_t offsets(const flatbuffers::Vector<flatbuffers::Offset<T>>* v) {
    if (!v) return 0;
    budget_.charge(4 * static_cast<std::size_t>(v->size()));
    return v->size();
  }

  std::array<double, 3> triple(const flatbuffers::Vector<double>* v, const std::string& what) {
    const std::vector<double> values = vector(v);
    if (values.size() != 3) invalid(what + " has " + std::to_string(values.size()) + " values, expected 3");
    return {values[0], values[1], values[2]};
  }

 private:
  ReadBudget budget_;
};

std::vector<ConstraintPolyline> read_polylines(Reader& r, const flatbuffers::Vector<flatbuffers::Offset<fb::Polyline>>* v,
                                               const std::string& where, const char* kind) {
  std::vector<ConstraintPolyline> lines;
  const flatbuffers::uoffset_t count = r.offsets(v);
  for (flatbuffers::uoffset_t i = 0; i < count; ++i) {
    const fb::Polyline* p = v->Get(i);
    r.table();
    const std::vector<std::uint32_t> faces = r.vector(p->faces());
    const std::vector<double> weights = r.vector(p->barycentrics());
    if (weights.size() != 3 * faces.size())
      invalid(where + ": " + kind + " " + std::to_string(i) + " has " + std::to_string(faces.size()) + " faces but " +
              std::to_string(weights.size()) + " barycentric weights (expected 3 per face)");
    ConstraintPolyline line;
    line.closed = p->closed();
    line.points.resize(faces.size());
    for (std::size_t k = 0; k < faces.size(); ++k)
      line.points[k] = SurfacePoint{triangle_index(faces[k]), Vec3(weights[3 * k], weights[3 * k + 1], weights[3 * k + 2])};
    lines.push_back(std::move(line));
  }
  return lines;
}

MacroConstraint read_entry(Reader& r, const fb::Entry* e, std::size_t index) {
  r.table();
  MacroConstraint m;
  m.id = e->id();
  m.name = r.string(e->name());
  const std::string where = entry_label(index, m.name);
  m.class_label = r.string(e->class_label());
  const auto* tags = e->tags();
  for (flatbuffers::uoffset_t i = 0, n = r.offsets(tags); i < n; ++i) {
    r.table();
    m.tags.push_back(r.string(tags->Get(i)->text()));
  }
  m.author = r.string(e->author());
  m.licence = r.string(e->licence());
  m.positions = r.vector(e->positions());
  m.triangles = r.vector(e->triangles());
  m.center.triangle = triangle_index(e->center_face());
  m.center.barycentric = vec3(r.triple(e->center_barycentric(), where + ": center barycentric"));
  m.source_scale = e->source_scale();
  m.source_origin = r.triple(e->source_origin(), where + ": source_origin");
  if (e->up() != nullptr) m.up = r.triple(e->up(), where + ": up");
  m.guides = read_polylines(r, e->guides(), where, "guide");
  m.features = read_polylines(r, e->features(), where, "feature");
  const auto* sings = e->singularities();
  for (flatbuffers::uoffset_t i = 0, n = r.offsets(sings); i < n; ++i) {
    const fb::Singularity* s = sings->Get(i);
    r.table();
    Singularity out;
    out.location.triangle = triangle_index(s->face());
    out.location.barycentric =
        vec3(r.triple(s->barycentric(), where + ": singularity " + std::to_string(i) + " barycentric"));
    out.index_quarters = s->index_quarters();
    m.singularities.push_back(out);
  }
  const auto* fields = e->fields();
  for (flatbuffers::uoffset_t i = 0, n = r.offsets(fields); i < n; ++i) {
    const fb::VertexField* f = fields->Get(i);
    r.table();
    VertexField out;
    out.name = r.string(f->name());
    // Unknown kinds (0 = absent, or newer than this build) are rejected by the validator.
    out.kind = static_cast<FieldKind>(static_cast<std::uint8_t>(f->kind()));
    out.dimension = f->dimension();
    out.values = r.vector(f->values());
    out.labels = r.vector(f->int_values());
    m.fields.push_back(std::move(out));
  }
  m.descriptors = r.vector(e->descriptors());
  m.histogram = r.vector(e->histogram());
  return m;
}

RetrievalConfig read_config(Reader& r, const fb::RetrievalConfig* c) {
  if (!c) invalid("library has no retrieval config");
  r.table();
  RetrievalConfig out;
  out.descriptor = r.string(c->descriptor());
  out.dimension = c->dimension();
  out.normalization_mean = r.vector(c->normalization_mean());
  out.normalization_scale = r.vector(c->normalization_scale());
  out.vocabulary_size = c->vocabulary_size();
  out.vocabulary = r.vector(c->vocabulary());
  out.sigma_bof = c->sigma_bof();
  out.rings = c->rings();
  out.seed = c->seed();
  return out;
}

std::string printable_identifier(const std::uint8_t* id) {
  std::string out;
  for (int i = 0; i < 4; ++i) {
    const unsigned char c = id[i];
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char hex[] = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

// Library.format_version, after verifying just the root offset, the root table's vtable and that
// field (the generated Library::Verify starts with the same checks).
std::uint32_t read_format_version(const std::uint8_t* bytes, std::size_t size) {
  flatbuffers::Verifier::Options options;
  options.max_depth = 1;
  options.max_tables = 1;
  flatbuffers::Verifier verifier(bytes, size, options);
  const flatbuffers::uoffset_t root_offset = verifier.VerifyOffset(0);
  const auto* table = reinterpret_cast<const flatbuffers::Table*>(bytes + root_offset);
  if (root_offset == 0 || !table->VerifyTableStart(verifier) ||
      !table->VerifyField<std::uint32_t>(verifier, fb::Library::VT_FORMAT_VERSION, sizeof(std::uint32_t)))
    invalid("library failed FlatBuffers verification (truncated or corrupt root table)");
  return table->GetField<std::uint32_t>(fb::Library::VT_FORMAT_VERSION, 0);
}

std::string hex64(std::uint64_t v) {
  static const char digits[] = "0123456789abcdef";
  std::string s = "0x";
  for (int shift = 60; shift >= 0; shift -= 4) s += digits[(v >> shift) & 15];
  return s;
}

// Format 2 on: the content checksum must be present and match (a flipped bit anywhere, even in a
// value every other check accepts, is caught here). Format 1 files carry none.
ConstraintLibrary::Origin verify_checksum(const std::uint8_t* bytes, std::size_t size, std::uint32_t version) {
  ConstraintLibrary::Origin origin;
  origin.format_version = version;
  if (version < 2) return origin;
  const std::size_t at = library_checksum_offset(bytes);
  if (at == 0) invalid("library format " + std::to_string(version) + " has no content checksum");
  const std::uint64_t stored = flatbuffers::ReadScalar<std::uint64_t>(bytes + at);
  const std::uint64_t computed = library_content_checksum(bytes, size, at);
  if (stored != computed)
    invalid("library content checksum mismatch (stored " + hex64(stored) + ", computed " + hex64(computed) +
            "): the file is corrupt or was changed after it was written");
  origin.checksum_verified = true;
  return origin;
}

}  // namespace

ConstraintLibrary load_library_from_buffer(const void* data, std::size_t size, bool check_checksum) {
  if (size < kLibraryMinBytes || size > kLibraryMaxBytes)
    invalid("library buffer has " + std::to_string(size) + " bytes, expected " + std::to_string(kLibraryMinBytes) +
            " to " + std::to_string(kLibraryMaxBytes));
  require(data != nullptr, MCON_ERROR_NULL_POINTER, "library buffer is NULL");
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  // FlatBuffers accessors assume the buffer start is aligned to the largest scalar (8 bytes): the
  // Verifier checks alignment relative to the start only. Copy a misaligned caller buffer.
  std::vector<std::uint64_t> aligned;
  if (reinterpret_cast<std::uintptr_t>(bytes) % alignof(std::uint64_t) != 0) {
    aligned.resize((size + 7) / 8);
    std::memcpy(aligned.data(), bytes, size);
    bytes = reinterpret_cast<const std::uint8_t*>(aligned.data());
  }

  if (!flatbuffers::BufferHasIdentifier(bytes, kLibraryFileIdentifier))
    invalid("not a Macrocon constraint library (file identifier '" +
            printable_identifier(bytes + sizeof(flatbuffers::uoffset_t)) + "', expected '" + kLibraryFileIdentifier +
            "')");

  // The format version first, verifying only the root table and that one field: a newer format
  // is UNSUPPORTED even if the rest of its layout would not pass this build's Verifier.
  const std::uint32_t version = read_format_version(bytes, size);
  if (version == 0) invalid("library has no format version");
  require(version <= kLibraryFormatVersion, MCON_ERROR_UNSUPPORTED,
          "library format version " + std::to_string(version) + " is newer than this build reads (" +
              std::to_string(kLibraryFormatVersion) + ")");

  flatbuffers::Verifier::Options options;
  options.max_depth = kMaxDepth;
  // Every distinct table occupies at least its 4-byte vtable offset, so a genuine buffer never has
  // more than size / 4 tables. Because all vectors of offsets hold tables, this also bounds the
  // Verifier's work on a forged buffer that points many offsets at one object.
  options.max_tables = static_cast<flatbuffers::uoffset_t>(size / 4);
  options.check_alignment = true;
  options.check_nested_flatbuffers = true;
  flatbuffers::Verifier verifier(bytes, size, options);
  if (!verifier.VerifyBuffer<fb::Library>(kLibraryFileIdentifier))
    invalid("library failed FlatBuffers verification (truncated or corrupt: an offset, vector or string lies "
            "outside the buffer, is misaligned, or the nesting or table count exceeds the limits)");

  const fb::Library* root = fb::GetLibrary(bytes);
  const ConstraintLibrary::Origin origin =
      check_checksum ? verify_checksum(bytes, size, version) : ConstraintLibrary::Origin{version, false};

  Reader r(size);
  r.table();
  ConstraintLibrary library(read_config(r, root->retrieval()), {}, MCON_ERROR_INVALID_LIBRARY);
  std::string name = r.string(root->name()), description = r.string(root->description());
  validate_library_text(name, "library name", MCON_ERROR_INVALID_LIBRARY);
  validate_library_text(description, "library description", MCON_ERROR_INVALID_LIBRARY);
  library.set_name(std::move(name));
  library.set_description(std::move(description));
  library.set_origin(origin);
  const auto* entries = root->entries();
  for (flatbuffers::uoffset_t i = 0, n = r.offsets(entries); i < n; ++i)
    library.append_entry(read_entry(r, entries->Get(i), i), MCON_ERROR_INVALID_LIBRARY);
  return library;
}

ConstraintLibrary load_library_from_file(const std::string& path) {
  // Read, not mapped: verification and copying must see the same bytes, whatever another process
  // does to the file meanwhile (a mapped file truncated under its reader raises SIGBUS).
  const std::vector<std::uint8_t> bytes =
      read_whole_file(path, kLibraryMinBytes, kLibraryMaxBytes, MCON_ERROR_INVALID_LIBRARY);
  try {
    return load_library_from_buffer(bytes.data(), bytes.size());
  } catch (const Error& e) {
    throw Error(e.status(), "'" + path + "': " + e.what());
  }
}

}  // namespace mcon
