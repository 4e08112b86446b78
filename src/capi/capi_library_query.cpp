// Queries: the top-n entries nearest to a patch (thesis §3.2: bag-of-features histograms under the
// L1 distance), by a linear scan over the library's flat histogram array (capi_library.h), so the
// cost depends on the entry count and histogram length only, never on the entries' patch sizes.
#include <limits>

#include "capi/capi_library.h"
#include "library/distinct_suggestions.h"

using namespace mcon;
using namespace mcon::capi;

namespace {

void query(mcon_library library, mcon_patch patch, const Eigen::MatrixXd* custom, size_t n, uint64_t* out_ids,
           uint32_t* out_indices, double* out_distances, size_t capacity, size_t* out_count) {
  require_pointer(out_count, "out_count");
  *out_count = 0;
  check_handle(patch, "patch");
  require(n >= 1, MCON_ERROR_INVALID_ARGUMENT, "n must be at least 1");
  const ConstraintLibrary& lib = library->library;
  const std::size_t wanted = std::min(n, lib.size());
  require_capacity(capacity, wanted, "output arrays (capacity in entries)");
  const RetrievalConfig& config = lib.retrieval();
  const std::vector<RetrievalHit> hits = run_in_arena(library->context, [&] {
    const std::vector<float> histogram = query_histogram(config, patch->patch, custom);
    return query_top_n(config, library->flat, histogram, n);
  });
  require(hits.size() == wanted, MCON_ERROR_UNKNOWN, "the scan returned " + std::to_string(hits.size()) + " hits");
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (out_ids) out_ids[i] = lib.entries()[hits[i].entry].id;
    if (out_indices) out_indices[i] = static_cast<std::uint32_t>(hits[i].entry);
    if (out_distances) out_distances[i] = static_cast<double>(hits[i].distance);
  }
  *out_count = hits.size();
}

}  // namespace

extern "C" {

mcon_status mcon_library_query_distinct(mcon_library library, mcon_patch patch, size_t n, uint32_t* out_indices,
                                        double* out_distances, double* out_confidence,
                                        uint32_t* out_alternative_counts, size_t capacity, size_t* out_count) {
  return guard_object("mcon_library_query_distinct", library, "library", [&] {
    require_pointer(out_count, "out_count");
    *out_count = 0;
    check_handle(patch, "patch");
    require(n >= 1, MCON_ERROR_INVALID_ARGUMENT, "n must be at least 1");
    const ConstraintLibrary& lib = library->library;
    require_capacity(capacity, std::min(n, lib.size()), "output arrays (capacity in suggestions)");
    const std::vector<DistinctSuggestion> s = run_in_arena(library->context, [&] {
      const std::vector<float> histogram = query_histogram(lib.retrieval(), patch->patch, nullptr);
      return distinct_suggestions(query_top_n(lib.retrieval(), library->flat, histogram, lib.size()), lib.entries(), n);
    });
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (out_indices) out_indices[i] = static_cast<std::uint32_t>(s[i].entry);
      if (out_distances) out_distances[i] = s[i].distance;
      if (out_confidence) out_confidence[i] = s[i].confidence;
      if (out_alternative_counts) out_alternative_counts[i] = static_cast<std::uint32_t>(s[i].alternatives.size());
    }
    *out_count = s.size();
  });
}

mcon_status mcon_library_query(mcon_library library, mcon_patch patch, size_t n, uint64_t* out_ids,
                               uint32_t* out_indices, double* out_distances, size_t capacity, size_t* out_count) {
  return guard_object("mcon_library_query", library, "library", [&] {
    query(library, patch, nullptr, n, out_ids, out_indices, out_distances, capacity, out_count);
  });
}

mcon_status mcon_library_query_descriptors(mcon_library library, mcon_patch patch, const double* descriptors,
                                           uint32_t dimension, size_t stride, size_t n, uint64_t* out_ids,
                                           uint32_t* out_indices, double* out_distances, size_t capacity,
                                           size_t* out_count) {
  return guard_object("mcon_library_query_descriptors", library, "library", [&] {
    require_pointer(out_count, "out_count");
    *out_count = 0;
    check_handle(patch, "patch");
    require_pointer(descriptors, "descriptors");
    require(dimension == library->library.retrieval().dimension, MCON_ERROR_INVALID_ARGUMENT,
            "dimension " + std::to_string(dimension) + " is not the library's (" +
                std::to_string(library->library.retrieval().dimension) + ")");
    const Eigen::MatrixXd custom =
        read_rows(descriptors, patch->patch.mesh.positions.size(), dimension, stride, "descriptors");
    query(library, patch, &custom, n, out_ids, out_indices, out_distances, capacity, out_count);
  });
}

}  // extern "C"
