// Everything a retrieval query needs besides the query patch itself: which descriptor, how its
// dimensions are normalized, the vocabulary and the soft-assignment width (thesis §3.2). A
// library file stores one of these, so a query needs nothing else.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mcon {

// Concentric geodesic rings of the default bag-of-features (1 = plain, thesis eq. 3.1; > 1 = the
// ringed variant of docs/design.md §1). The one place the measured best default lives: the C API's
// mcon_retrieval_options_init and the CLI read it from here.
inline constexpr std::uint32_t kDefaultRetrievalRings = 1;

// The default descriptor's name as stored in RetrievalConfig::descriptor. Every built-in
// descriptor (name, C API code, dimension, how it is computed) is one row of builtin_descriptors()
// in retrieval/retrieval_descriptors.cpp; caller-supplied ones are named "custom:<name>".
inline constexpr const char* kDescriptorCurv9 = "curv9";
inline constexpr const char* kCustomDescriptorPrefix = "custom:";

// "custom:<name>" with a non-empty <name>: descriptors supplied by the caller, of any dimension.
inline bool is_custom_descriptor(const std::string& name) {
  const std::string prefix = kCustomDescriptorPrefix;
  return name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0;
}

struct RetrievalConfig {
  std::string descriptor = kDescriptorCurv9;  // "curv9", "hks", "wks", "custom:<name>"
  std::uint32_t dimension = 0;             // descriptor values per vertex (d)
  std::vector<double> normalization_mean;  // d values: subtracted first
  std::vector<double> normalization_scale; // d values: then divided (std over the library, thesis §3.2)
  std::uint32_t vocabulary_size = 0;       // k
  std::vector<double> vocabulary;          // k * d, word-major (normalized descriptor space)
  double sigma_bof = 0;                    // soft-assignment width (thesis eq. 3.1)
  std::uint32_t rings = 1;                 // concentric geodesic rings (1 = plain bag-of-features)
  std::uint64_t seed = 0;                  // seed the vocabulary was built with

  // Histogram length of one entry: k * rings.
  std::size_t histogram_length() const { return static_cast<std::size_t>(vocabulary_size) * rings; }
};

}  // namespace mcon
