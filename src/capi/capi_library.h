// The object behind mcon_library (constraint libraries, macrocon.h "mcon_library_*"), shared by
// capi_library.cpp (lifetime, files, info, merge, build), capi_library_entries.cpp (add, remove,
// getters) and capi_library_query.cpp. Follows capi_handles.h: magic tag, reference count, one
// reference on its context.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "capi/capi_handles.h"
#include "library/constraint_library.h"
#include "library/library_retrieval.h"
#include "retrieval/retrieval_descriptors.h"

struct mcon_library_t {
  static constexpr std::uint32_t kMagic = 0x4d434c0a;  // "MCL"
  mcon::capi::HandleHeader header{kMagic};
  mcon_context context = nullptr;  // retained
  mcon::ConstraintLibrary library;
  // flat_histograms(library), kept in step with every change: the array a query scans, so a
  // query never touches the entries themselves.
  std::vector<float> flat;
  ~mcon_library_t();

  // Strong guarantee for whole-library changes: the new state is complete before it replaces
  // the old one (the moves cannot throw).
  void replace(mcon::ConstraintLibrary next) {
    std::vector<float> next_flat = mcon::flat_histograms(next);
    library = std::move(next);
    flat = std::move(next_flat);
  }
};

namespace mcon::capi {

// The entry at `index`, or MCON_ERROR_INVALID_ARGUMENT naming the range.
inline const MacroConstraint& entry_at(const mcon_library_t* library, std::size_t index) {
  const auto& entries = library->library.entries();
  require(index < entries.size(), MCON_ERROR_INVALID_ARGUMENT,
          "entry index " + std::to_string(index) + " is out of range (the library has " +
              std::to_string(entries.size()) + " entries)");
  return entries[index];
}

// mcon_retrieval_descriptor of a stored descriptor name (0 for a name this build does not know).
inline std::uint32_t descriptor_code(const std::string& name) {
  if (const BuiltinDescriptor* d = find_builtin_descriptor(name)) return d->code;
  if (is_custom_descriptor(name)) return MCON_RETRIEVAL_DESCRIPTOR_CUSTOM;
  return 0;
}

// Per-vertex doubles from a caller array: `rows` rows of `dimension` values, `stride` bytes
// apart (0 = packed). Read with memcpy: the caller's stride need not keep doubles aligned.
Eigen::MatrixXd read_rows(const double* values, std::size_t rows, std::uint32_t dimension, std::size_t stride,
                          const std::string& what);

// A caller's string (NULL = ""): stored strings are UTF-8 (base/text.h), and a C string cannot
// hold a NUL, so only the encoding needs checking. `what` names it in the error.
std::string caller_text(const char* s, const std::string& what);

// A stored string out through the C convention: *out_size (may be NULL) = bytes with the NUL;
// with out_text non-NULL, capacity must hold them.
void copy_string(const std::string& s, char* out_text, std::size_t capacity, std::size_t* out_size);

}  // namespace mcon::capi
