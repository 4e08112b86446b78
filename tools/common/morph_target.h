// MakeHuman morph targets (`*.target[.gz]`): sparse per-vertex offsets on the base mesh, a shape
// being base + sum_k w_k * target_k. Text format: `#` comment lines, data lines
// `vertex_index dx dy dz` with 0-based indices into the base OBJ (shared/meshes/SOURCES.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh.h"

namespace mcon::tools {

struct MorphTarget {
  std::vector<int> indices;   // vertex indices, file order
  std::vector<Vec3> offsets;  // one per index
};

// Throws mcon::Error(MCON_ERROR_IO) naming `source` and the line on malformed data.
MorphTarget parse_morph_target(std::string_view text, const std::string& source);

// Reads a target file once per process: later calls with the same path return the cached target
// (thread-safe; the reference stays valid until the process ends).
const MorphTarget& load_morph_target(const std::string& path);

// Adds weight * target to positions, ignoring indices >= positions.size() (offsets of the helper
// geometry that follows the body in the base OBJ).
void add_morph_target(std::vector<Vec3>& positions, const MorphTarget& target, double weight);

}  // namespace mcon::tools
