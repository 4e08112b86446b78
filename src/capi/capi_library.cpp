// Constraint libraries: lifetime, files (hostile-input loader, atomic save), info,
// merge and building retrieval (thesis ch. 3). A call that fails leaves the library as it was.
#include <cmath>
#include <cstring>

#include "base/text.h"
#include "capi/capi_library.h"
#include "library/library_file.h"
#include "retrieval/retrieval_descriptors.h"

using namespace mcon;
using namespace mcon::capi;

mcon_library_t::~mcon_library_t() { release_owned(context); }

namespace mcon::capi {

Eigen::MatrixXd read_rows(const double* values, std::size_t rows, std::uint32_t dimension, std::size_t stride,
                          const std::string& what) {
  require(dimension >= 1, MCON_ERROR_INVALID_ARGUMENT, what + ": dimension is 0");
  require(values != nullptr || rows == 0, MCON_ERROR_NULL_POINTER, what + " is NULL");
  const std::size_t row_bytes = sizeof(double) * dimension;
  const std::size_t step = stride == 0 ? row_bytes : stride;
  require(step >= row_bytes, MCON_ERROR_INVALID_ARGUMENT,
          what + ": stride " + std::to_string(stride) + " is smaller than a row (" + std::to_string(row_bytes) +
              " bytes)");
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(dimension));
  const unsigned char* base = reinterpret_cast<const unsigned char*>(values);
  for (std::size_t v = 0; v < rows; ++v)
    for (std::uint32_t j = 0; j < dimension; ++j) {
      double x;
      std::memcpy(&x, base + v * step + j * sizeof(double), sizeof x);
      require(std::isfinite(x), MCON_ERROR_NON_FINITE,
              what + ": value " + std::to_string(j) + " of vertex " + std::to_string(v) + " is not finite");
      out(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(j)) = x;
    }
  return out;
}

std::string caller_text(const char* s, const std::string& what) {
  if (s == nullptr) return std::string();
  std::string out(s);
  const std::string problem = text_problem(out);
  require(problem.empty(), MCON_ERROR_INVALID_ARGUMENT, what + " " + problem);
  return out;
}

void copy_string(const std::string& s, char* out_text, std::size_t capacity, std::size_t* out_size) {
  if (out_size) *out_size = s.size() + 1;
  if (out_text == nullptr) return;
  require_capacity(capacity, s.size() + 1, "out_text (capacity in bytes)");
  std::memcpy(out_text, s.c_str(), s.size() + 1);
}

}  // namespace mcon::capi

namespace {

// The stored descriptor name of an mcon_retrieval_descriptor (builtin_descriptors() or, for
// CUSTOM, the library's own caller-supplied name).
std::string descriptor_name(std::uint32_t code, const std::string& library_descriptor) {
  if (const BuiltinDescriptor* d = find_builtin_descriptor_code(code)) return d->name;
  if (code == MCON_RETRIEVAL_DESCRIPTOR_CUSTOM) {
    require(is_custom_descriptor(library_descriptor), MCON_ERROR_INVALID_ARGUMENT,
            "descriptor CUSTOM needs entries added with caller-supplied descriptors (the library's are '" +
                library_descriptor + "')");
    return library_descriptor;
  }
  std::string known;
  for (const BuiltinDescriptor& d : builtin_descriptors())
    known += std::string(d.name) + " " + std::to_string(d.code) + ", ";
  fail(MCON_ERROR_INVALID_ARGUMENT, "descriptor " + std::to_string(code) + " is not an mcon_retrieval_descriptor (" +
                                        known + "custom " + std::to_string(MCON_RETRIEVAL_DESCRIPTOR_CUSTOM) + ")");
}

mcon_retrieval_options default_retrieval_options() {
  auto o = zeroed_struct<mcon_retrieval_options>();
  o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_CURV9;
  o.vocabulary_size = kDefaultVocabularySize;
  o.rings = kDefaultRetrievalRings;  // the measured best (src/retrieval_config.h)
  o.sigma_bof = 0;
  o.seed = 0;
  return o;
}

// A new handle on `library`, retaining the context.
void make_handle(mcon_context context, ConstraintLibrary library, mcon_library* out) {
  auto handle = std::make_unique<mcon_library_t>();
  handle->replace(std::move(library));
  retain_owned(context);
  handle->context = context;
  *out = handle.release();
}

}  // namespace

extern "C" {

mcon_status mcon_library_create(mcon_context context, mcon_library* out_library) {
  return guard("mcon_library_create", [&] {
    require_pointer(out_library, "out_library");
    *out_library = nullptr;
    check_handle(context, "context");
    make_handle(context, ConstraintLibrary(), out_library);
  });
}

mcon_status mcon_library_open(mcon_context context, const char* path, mcon_library* out_library) {
  return guard("mcon_library_open", [&] {
    require_pointer(out_library, "out_library");
    *out_library = nullptr;
    check_handle(context, "context");
    require_pointer(path, "path");
    make_handle(context, load_library_from_file(path), out_library);
  });
}

mcon_status mcon_library_open_memory(mcon_context context, const void* data, size_t size, mcon_library* out_library) {
  return guard("mcon_library_open_memory", [&] {
    require_pointer(out_library, "out_library");
    *out_library = nullptr;
    check_handle(context, "context");
    require_pointer(data, "data");
    make_handle(context, load_library_from_buffer(data, size), out_library);
  });
}

mcon_status mcon_library_retain(mcon_library library) {
  return guard("mcon_library_retain", [&] { retain(library, "library"); });
}

mcon_status mcon_library_release(mcon_library library) {
  return guard("mcon_library_release", [&] { release(library, "library"); });
}

mcon_status mcon_library_save(mcon_library library, const char* path) {
  return guard_object("mcon_library_save", library, "library", [&] {
    require_pointer(path, "path");
    save_library_atomic(library->library, path);
  });
}

mcon_status mcon_library_save_memory(mcon_library library, void* out_data, size_t capacity, size_t* out_size) {
  return guard_object("mcon_library_save_memory", library, "library", [&] {
    require_pointer(out_size, "out_size");
    const std::vector<std::uint8_t> bytes = serialize_library(library->library);
    *out_size = bytes.size();
    if (out_data == nullptr) return;
    require_capacity(capacity, bytes.size(), "out_data (capacity in bytes)");
    std::memcpy(out_data, bytes.data(), bytes.size());
  });
}

mcon_status mcon_library_info_init_sized(mcon_library_info* info, size_t struct_size) {
  return init_struct("mcon_library_info_init_sized", info, struct_size, sizeof(mcon_library_info), "info",
                     zeroed_struct<mcon_library_info>());
}

mcon_status mcon_library_get_info(mcon_library library, mcon_library_info* info) {
  return guard_object("mcon_library_get_info", library, "library", [&] {
    const RetrievalConfig& c = library->library.retrieval();
    auto v = zeroed_struct<mcon_library_info>();
    v.entry_count = library->library.size();
    v.descriptor = descriptor_code(c.descriptor);
    v.descriptor_dimension = c.dimension;
    v.vocabulary_size = c.vocabulary_size;
    v.rings = c.rings;
    v.histogram_length = static_cast<std::uint32_t>(c.histogram_length());
    v.sigma_bof = c.sigma_bof;
    v.seed = c.seed;
    v.format_version = library->library.origin().format_version;
    v.checksum_verified = library->library.origin().checksum_verified ? 1u : 0u;
    write_info(info, sizeof(mcon_library_info), "mcon_library_info", v);
  });
}

mcon_status mcon_library_get_count(mcon_library library, size_t* out_count) {
  return guard_object("mcon_library_get_count", library, "library", [&] {
    require_pointer(out_count, "out_count");
    *out_count = library->library.size();
  });
}

mcon_status mcon_library_get_string(mcon_library library, mcon_library_string which, char* out_text, size_t capacity,
                                    size_t* out_size) {
  return guard_object("mcon_library_get_string", library, "library", [&] {
    const ConstraintLibrary& l = library->library;
    switch (enum_bits(which)) {
      case MCON_LIBRARY_NAME: return copy_string(l.name(), out_text, capacity, out_size);
      case MCON_LIBRARY_DESCRIPTION: return copy_string(l.description(), out_text, capacity, out_size);
      case MCON_LIBRARY_DESCRIPTOR: return copy_string(l.retrieval().descriptor, out_text, capacity, out_size);
      default:
        fail(MCON_ERROR_INVALID_ARGUMENT, "which " + std::to_string(enum_bits(which)) + " is not an mcon_library_string");
    }
  });
}

mcon_status mcon_library_set_string(mcon_library library, mcon_library_string which, const char* text) {
  return guard_object("mcon_library_set_string", library, "library", [&] {
    switch (enum_bits(which)) {
      case MCON_LIBRARY_NAME: return library->library.set_name(caller_text(text, "text"));
      case MCON_LIBRARY_DESCRIPTION: return library->library.set_description(caller_text(text, "text"));
      case MCON_LIBRARY_DESCRIPTOR:
        fail(MCON_ERROR_INVALID_ARGUMENT,
             "the descriptor is set by mcon_library_set_descriptor (empty library) or mcon_library_build_retrieval");
      default:
        fail(MCON_ERROR_INVALID_ARGUMENT, "which " + std::to_string(enum_bits(which)) + " is not an mcon_library_string");
    }
  });
}

mcon_status mcon_library_set_descriptor(mcon_library library, uint32_t descriptor) {
  return guard_object("mcon_library_set_descriptor", library, "library", [&] {
    const ConstraintLibrary& l = library->library;
    require(l.size() == 0, MCON_ERROR_INVALID_ARGUMENT,
            "the library has " + std::to_string(l.size()) +
                " entries: change its descriptor with mcon_library_build_retrieval (it recomputes them)");
    require(descriptor != MCON_RETRIEVAL_DESCRIPTOR_CUSTOM, MCON_ERROR_INVALID_ARGUMENT,
            "a CUSTOM library takes its descriptor from the first entry added with caller-supplied descriptors");
    // A fresh configuration: without entries there is no vocabulary or normalization to keep.
    RetrievalConfig config;
    config.descriptor = descriptor_name(descriptor, l.retrieval().descriptor);
    library->replace(with_config(l, config));
  });
}

mcon_status mcon_retrieval_descriptor_from_name(const char* name, uint32_t* out_descriptor) {
  return guard("mcon_retrieval_descriptor_from_name", [&] {
    require_pointer(name, "name");
    require_pointer(out_descriptor, "out_descriptor");
    *out_descriptor = builtin_descriptor(name).code;
  });
}

mcon_status mcon_library_merge(mcon_library library, mcon_library other) {
  return guard_object("mcon_library_merge", library, "library", [&] {
    check_handle(other, "other library");
    ConstraintLibrary& a = library->library;
    const ConstraintLibrary& b = other->library;
    const RetrievalConfig &ca = a.retrieval(), &cb = b.retrieval();
    if (b.size() == 0) return;  // nothing to append (whatever its configuration)
    if (a.size() == 0 && ca.vocabulary_size == 0) {
      // An empty library without vocabulary takes the other's configuration as it is.
      library->replace(with_config(a, cb, b.entries()));
      return;
    }
    if (same_retrieval_config(ca, cb)) {
      // Histograms over one vocabulary are comparable: ready for queries at once.
      std::vector<float> next_flat = library->flat;
      if (other == library) {
        next_flat.insert(next_flat.end(), library->flat.begin(), library->flat.end());
      } else {
        next_flat.insert(next_flat.end(), other->flat.begin(), other->flat.end());
      }
      a.merge(b);  // all or nothing
      library->flat = std::move(next_flat);
      return;
    }
    require(ca.descriptor == cb.descriptor && ca.dimension == cb.dimension, MCON_ERROR_INVALID_ARGUMENT,
            "cannot merge a library of descriptor '" + cb.descriptor + "' (dimension " + std::to_string(cb.dimension) +
                ") into one of '" + ca.descriptor + "' (dimension " + std::to_string(ca.dimension) + ")");
    // Different vocabularies: keep the descriptors, drop the vocabulary and every histogram;
    // mcon_library_build_retrieval must run before the next query.
    RetrievalConfig dropped = ca;
    dropped.vocabulary_size = 0;
    dropped.vocabulary.clear();
    dropped.sigma_bof = 0;
    auto strip = [](std::vector<MacroConstraint> entries) {
      for (MacroConstraint& e : entries) e.histogram.clear();
      return entries;
    };
    ConstraintLibrary next = with_config(a, dropped, strip(a.entries()));
    next.merge(ConstraintLibrary(dropped, strip(b.entries())));
    library->replace(std::move(next));
  });
}

mcon_status mcon_retrieval_options_init_sized(mcon_retrieval_options* options, size_t struct_size) {
  return init_struct("mcon_retrieval_options_init_sized", options, struct_size, sizeof(mcon_retrieval_options),
                     "options", default_retrieval_options());
}

mcon_status mcon_library_build_retrieval(mcon_library library, const mcon_retrieval_options* options) {
  return guard_object("mcon_library_build_retrieval", library, "library", [&] {
    const auto o =
        read_options(options, sizeof(mcon_retrieval_options), "mcon_retrieval_options", default_retrieval_options());
    LibraryRetrievalOptions lo;
    lo.descriptor = descriptor_name(o.descriptor, library->library.retrieval().descriptor);
    require(std::isfinite(o.sigma_bof), MCON_ERROR_NON_FINITE, "sigma_bof is not finite");
    lo.vocabulary_size = o.vocabulary_size;
    lo.rings = o.rings;
    lo.sigma_bof = o.sigma_bof;
    lo.seed = o.seed;
    std::shared_ptr<const std::atomic<bool>> cancelled;
    lo.progress = make_progress(o.progress, o.progress_user_data, &cancelled);
    ConstraintLibrary next =
        run_in_arena(library->context, [&] { return build_library_retrieval(library->library, lo); });
    require(!(cancelled && cancelled->load()), MCON_ERROR_CANCELLED, "cancelled by the progress callback");
    library->replace(std::move(next));
  });
}

}  // extern "C"
