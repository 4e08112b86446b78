#include "library/constraint_library.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "base/error.h"

namespace mcon {

TriMesh entry_mesh(const MacroConstraint& entry) {
  TriMesh mesh;
  mesh.positions.resize(entry.vertex_count());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    mesh.positions[v] = Vec3(entry.positions[3 * v], entry.positions[3 * v + 1], entry.positions[3 * v + 2]);
  mesh.triangles.resize(entry.triangle_count());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) mesh.triangles[t][k] = static_cast<int>(entry.triangles[3 * t + k]);
  return mesh;
}

void set_entry_mesh(MacroConstraint& entry, const TriMesh& mesh) {
  entry.positions.resize(3 * mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) entry.positions[3 * v + k] = static_cast<float>(mesh.positions[v][k]);
  entry.triangles.resize(3 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) entry.triangles[3 * t + k] = static_cast<std::uint32_t>(mesh.triangles[t][k]);
}

bool same_retrieval_config(const RetrievalConfig& a, const RetrievalConfig& b) {
  return a.descriptor == b.descriptor && a.dimension == b.dimension && a.normalization_mean == b.normalization_mean &&
         a.normalization_scale == b.normalization_scale && a.vocabulary_size == b.vocabulary_size &&
         a.vocabulary == b.vocabulary && a.sigma_bof == b.sigma_bof && a.rings == b.rings && a.seed == b.seed;
}

ConstraintLibrary::ConstraintLibrary(RetrievalConfig config, std::vector<MacroConstraint> entries, mcon_status status)
    : config_(std::move(config)) {
  validate_retrieval_config(config_, status);
  entries_.reserve(entries.size());
  for (MacroConstraint& e : entries) append_entry(std::move(e), status);
}

void ConstraintLibrary::append_entry(MacroConstraint entry, mcon_status status) {
  const std::size_t index = entries_.size();
  validate_library_entry(entry, index, config_, status);
  auto it = position_of_id_.find(entry.id);
  if (it != position_of_id_.end())
    fail(status, entry_label(index, entry.name) + ": id " + std::to_string(entry.id) + " is already used by entry " +
                     std::to_string(it->second));
  const std::uint64_t id = entry.id;
  entries_.push_back(std::move(entry));
  try {
    position_of_id_.emplace(id, index);
  } catch (...) {
    entries_.pop_back();
    throw;
  }
}

std::uint64_t ConstraintLibrary::next_free_id() const {
  std::uint64_t largest = 0;
  for (const MacroConstraint& e : entries_) largest = std::max(largest, e.id);
  require(largest < std::numeric_limits<std::uint64_t>::max(), MCON_ERROR_INVALID_ARGUMENT,
          "no id left above the largest id in the library");
  return largest + 1;
}

std::uint64_t ConstraintLibrary::add_entry(MacroConstraint entry) {
  if (entry.id == 0) entry.id = next_free_id();
  const std::uint64_t id = entry.id;
  append_entry(std::move(entry), MCON_ERROR_INVALID_ARGUMENT);
  return id;
}

void ConstraintLibrary::remove_entry(std::uint64_t id) {
  auto it = position_of_id_.find(id);
  require(it != position_of_id_.end(), MCON_ERROR_NOT_FOUND, "no entry with id " + std::to_string(id));
  const std::size_t pos = it->second;
  entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(pos));
  position_of_id_.erase(it);
  for (auto& [key, p] : position_of_id_)
    if (p > pos) --p;
}

const MacroConstraint* ConstraintLibrary::find_entry(std::uint64_t id) const {
  auto it = position_of_id_.find(id);
  return it == position_of_id_.end() ? nullptr : &entries_[it->second];
}

std::vector<ConstraintLibrary::IdChange> ConstraintLibrary::merge(const ConstraintLibrary& other) {
  require(same_retrieval_config(config_, other.config_), MCON_ERROR_INVALID_ARGUMENT,
          "cannot merge libraries with different retrieval configs (descriptor '" + config_.descriptor + "' d=" +
              std::to_string(config_.dimension) + " k=" + std::to_string(config_.vocabulary_size) + " rings=" +
              std::to_string(config_.rings) + " vs '" + other.config_.descriptor + "' d=" +
              std::to_string(other.config_.dimension) + " k=" + std::to_string(other.config_.vocabulary_size) +
              " rings=" + std::to_string(other.config_.rings) +
              "); recompute descriptors and histograms with one config first");
  // Copy first: `other` may be *this. Entries of a library are valid for an identical config.
  std::vector<MacroConstraint> incoming = other.entries_;
  std::vector<IdChange> changes;
  std::uint64_t largest = 0;
  for (const MacroConstraint& e : entries_) largest = std::max(largest, e.id);
  for (const MacroConstraint& e : incoming) largest = std::max(largest, e.id);
  std::unordered_map<std::uint64_t, std::size_t> ids = position_of_id_;
  for (std::size_t i = 0; i < incoming.size(); ++i) {
    MacroConstraint& e = incoming[i];
    if (ids.count(e.id) != 0) {
      require(largest < std::numeric_limits<std::uint64_t>::max(), MCON_ERROR_INVALID_ARGUMENT,
              "no id left to renumber " + entry_label(i, e.name) + " while merging");
      changes.push_back({e.id, ++largest});
      e.id = largest;
    }
    ids.emplace(e.id, entries_.size() + i);
  }
  entries_.reserve(entries_.size() + incoming.size());
  for (MacroConstraint& e : incoming) entries_.push_back(std::move(e));
  position_of_id_ = std::move(ids);
  return changes;
}

}  // namespace mcon
