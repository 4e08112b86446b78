// Distinct suggestions (issue "meshes from anywhere"): the top of a query's ranking without
// near-duplicates. Entries of one class count once — a left and a right copy of one patch, or five
// instances of one class — so the n suggestions are n different things, each with the others of
// its group as alternatives and a confidence (docs/design.md §10).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "library/constraint_library.h"
#include "retrieval/retrieval_index.h"

namespace mcon {

// The group an entry belongs to: its class label, lower-cased, without a side suffix ("_l", "_r",
// "_left", "_right", ".l", ".r", "-l", "-r", " left", " right"). Empty for an unlabelled entry,
// which is a group of its own.
std::string suggestion_group(const std::string& class_label);

struct DistinctSuggestion {
  std::size_t entry = 0;                  // the group's best entry (index into the library)
  double distance = 0;                    // its query distance
  double confidence = 0;                  // in [0, 1]; sums to 1 over the suggestions returned
  std::vector<std::size_t> alternatives;  // the group's other entries, best first
};

// Up to n suggestions from `ranked` (every hit of a query, sorted by distance: query_top_n with
// n = the library's size). confidence_i = exp(-(d_i - d_1) / tau) / sum_j exp(-(d_j - d_1) / tau)
// over the returned suggestions, tau = d_1 (the best distance; an exact match, d_1 = 0, gets 1):
// how far the others fall behind the best in units of its own distance. INVALID_ARGUMENT for n = 0.
std::vector<DistinctSuggestion> distinct_suggestions(const std::vector<RetrievalHit>& ranked,
                                                     const std::vector<MacroConstraint>& entries, std::size_t n);

}  // namespace mcon
