#include "library/distinct_suggestions.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "base/error.h"

namespace mcon {

std::string suggestion_group(const std::string& class_label) {
  std::string s = class_label;
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* suffix : {"_left", "_right", " left", " right", "-left", "-right", ".left", ".right", "_l", "_r",
                             ".l", ".r", "-l", "-r"}) {
    const std::string x = suffix;
    if (s.size() > x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0) return s.substr(0, s.size() - x.size());
  }
  return s;
}

namespace {

// The confidence of eq. in distinct_suggestions.h, over the suggestions' distances (ascending).
void set_confidences(std::vector<DistinctSuggestion>& out) {
  if (out.empty()) return;
  const double best = out.front().distance;
  if (!(best > 0)) {
    for (DistinctSuggestion& s : out) s.confidence = s.distance == best ? 1.0 : 0.0;
  } else {
    double total = 0;
    for (DistinctSuggestion& s : out) total += s.confidence = std::exp(-(s.distance - best) / best);
    for (DistinctSuggestion& s : out) s.confidence /= total;
  }
  double sum = 0;  // exact matches tied at distance 0 share the 1
  for (const DistinctSuggestion& s : out) sum += s.confidence;
  for (DistinctSuggestion& s : out) s.confidence /= sum;
}

}  // namespace

std::vector<DistinctSuggestion> distinct_suggestions(const std::vector<RetrievalHit>& ranked,
                                                     const std::vector<MacroConstraint>& entries, std::size_t n) {
  require(n >= 1, MCON_ERROR_INVALID_ARGUMENT, "n must be at least 1");
  std::vector<DistinctSuggestion> out;
  std::map<std::string, std::size_t> group_of;  // labelled group -> its suggestion
  for (const RetrievalHit& hit : ranked) {
    require(hit.entry < entries.size(), MCON_ERROR_INVALID_ARGUMENT, "a hit is not an entry of the library");
    const std::string group = suggestion_group(entries[hit.entry].class_label);
    const auto it = group.empty() ? group_of.end() : group_of.find(group);
    if (it != group_of.end()) {
      out[it->second].alternatives.push_back(hit.entry);
      continue;
    }
    if (out.size() == n) continue;  // later hits only fill the alternatives of the chosen groups
    if (!group.empty()) group_of.emplace(group, out.size());
    DistinctSuggestion s;
    s.entry = hit.entry;
    s.distance = hit.distance;
    out.push_back(std::move(s));
  }
  set_confidences(out);
  return out;
}

}  // namespace mcon
