// Retrieval on a whole constraint library (thesis ch. 3): what the C API (src/capi/capi_library*.cpp)
// and the CLI (`macrocon library`, `macrocon query`) share, so both build the same entries, the
// same vocabularies and the same answers.
//  - make_library_entry: an extracted Patch + metadata/constraints/fields -> a MacroConstraint.
//  - add_library_entry: validates and appends, computing descriptors and (with a vocabulary) the
//    histogram, so the entry is found by queries at once.
//  - build_library_retrieval: descriptors (recomputed when the descriptor changes), normalization,
//    k-means++ vocabulary, sigma_BoF and every entry's histogram; returns a new library (all or
//    nothing: the caller swaps it in).
//  - query_histogram + query_top_n: the query side, a linear scan over a flat histogram array, so
//    a query costs O(entries * histogram length) whatever the entries' patch sizes.
//
// Every entry is described from what the library stores (its float mesh and its center), never
// from the caller's double-precision patch: descriptors, vertex areas and ring distances of an
// entry are then the same when it is added, when the vocabulary is rebuilt after a save/open, and
// when the same patch is used as a query (which is rounded to float the same way: a patch queried
// against its own entry is at L1 distance 0).
//
// Parallel work runs with oneTBB in the caller's current task arena; every result is the same for
// any thread count (per-entry work is independent, reductions run in a fixed order).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "retrieval/bag_of_features.h"
#include "library/constraint_library.h"
#include "patch/geodesic_disk_patch.h"
#include "retrieval/retrieval_index.h"

namespace mcon {

// Vocabulary size k of the default (thesis §3.2: 128 words).
inline constexpr std::uint32_t kDefaultVocabularySize = 128;

// The name the C API gives caller-supplied descriptors ("custom:<name>", is_custom_descriptor in
// retrieval/retrieval_config.h: per-vertex descriptors of a host's own).
inline constexpr const char* kCustomDescriptorApi = "custom:host";

// A library with `like`'s name and description, and `config` and `entries` (validated, throws
// mcon::Error): what a change of configuration keeps.
ConstraintLibrary with_config(const ConstraintLibrary& like, RetrievalConfig config,
                              std::vector<MacroConstraint> entries = {});

// `content` carries id, metadata, constraints and fields; its geometry (mesh, center, source
// scale and origin) is taken from the patch. Descriptors: `custom_descriptors` (n x d, for a
// custom library) rounded to float, else the config's built-in descriptor computed on the stored
// (float) mesh. The histogram is computed when the config has a vocabulary. Not validated here
// (ConstraintLibrary::add_entry does that). Throws mcon::Error.
MacroConstraint make_library_entry(const Patch& patch, MacroConstraint content, const RetrievalConfig& config,
                                   const Eigen::MatrixXd* custom_descriptors = nullptr);

// Appends an entry built by make_library_entry and returns its id. The first entry of an empty
// library fixes the descriptor dimension (a library with no entries and no vocabulary switches to
// kCustomDescriptorApi when given custom descriptors). Rules: a built-in library computes its own
// descriptor (custom_descriptors must be null); a custom one needs them with its dimension.
// All or nothing. Throws mcon::Error (INVALID_ARGUMENT naming the problem, NON_FINITE).
std::uint64_t add_library_entry(ConstraintLibrary& library, const Patch& patch, MacroConstraint content,
                                const Eigen::MatrixXd* custom_descriptors = nullptr);

// The per-vertex input of retrieval of a stored entry: its stored descriptors (unless
// `recompute` names a built-in descriptor to compute instead), vertex areas, and center distances
// (from its mesh and center, only when `rings` > 1: they cost one heat-method solve).
PatchDescriptors describe_library_entry(const MacroConstraint& entry, std::uint32_t dimension,
                                        const std::string& recompute, std::uint32_t rings);

struct LibraryRetrievalOptions {
  std::string descriptor = "curv9";  // built-in name, or the library's own "custom:..." name
  std::uint32_t vocabulary_size = kDefaultVocabularySize;
  std::uint32_t rings = kDefaultRetrievalRings;
  double sigma_bof = 0;  // 0 = the median rule
  std::uint64_t seed = 0;
  // Fraction in [0, 1], called from any thread; false cancels (MCON_ERROR_CANCELLED).
  std::function<bool(double)> progress;
};

// The library with descriptors (recomputed from every entry's mesh if the descriptor or its
// dimension changed), normalization, vocabulary, sigma and histograms of `options`; `library`
// itself is not touched. Needs at least one entry. Throws mcon::Error: INVALID_ARGUMENT,
// NON_FINITE, NUMERICAL, CANCELLED.
ConstraintLibrary build_library_retrieval(const ConstraintLibrary& library, const LibraryRetrievalOptions& options);

// The histogram of a query patch under the library's config: the built-in descriptor computed on
// the float-rounded patch, or `custom_descriptors` (n x d) for a custom library. Throws
// INVALID_ARGUMENT without a vocabulary, UNSUPPORTED for a descriptor this build cannot compute.
std::vector<float> query_histogram(const RetrievalConfig& config, const Patch& patch,
                                   const Eigen::MatrixXd* custom_descriptors = nullptr);

// Every entry's histogram, entry-major (count * histogram_length floats): the array queries scan.
std::vector<float> flat_histograms(const ConstraintLibrary& library);

// The min(n, count) nearest entries (L1, sorted by (distance, index)) over `flat`
// (flat_histograms). INVALID_ARGUMENT for n = 0 or a histogram of the wrong length.
std::vector<RetrievalHit> query_top_n(const RetrievalConfig& config, const std::vector<float>& flat,
                                      const std::vector<float>& histogram, std::size_t n);

}  // namespace mcon
