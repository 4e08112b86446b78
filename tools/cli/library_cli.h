// Shared by `macrocon library` and `macrocon query`: entry specs (mesh file, center vertex in file
// numbering, radius, metadata), reading meshes once, cutting patches, and the JSON of a library.
#pragma once

#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "command/args.h"
#include "command/command.h"
#include "entry_authoring.h"
#include "library/constraint_library.h"
#include "base/error.h"
#include "patch/geodesic_disk_patch.h"
#include "io/mesh_io.h"
#include "json/json_file.h"

namespace mcon::cli {

// One patch to cut, with what the entry records about it.
struct EntrySpec {
  std::string mesh;        // mesh file
  std::string face_range;  // "BEGIN:END" (file faces) or empty for all
  long center_vertex = -1; // file vertex numbering
  double radius = 0;       // geodesic radius in mesh units
  std::string class_label, name, author, licence;
  std::vector<std::string> tags;
  AuthoringSpec authoring;  // constraints from DCC files (guides, features, singularities, fields)
};

inline long parse_integer(const std::string& option, const std::string& s) { return ArgParser::parse_integer(option, s); }
inline double parse_real(const std::string& option, const std::string& s) { return ArgParser::parse_number(option, s); }

// Meshes read once per (file, face range).
class MeshCache {
 public:
  const io::LoadedMesh& get(const std::string& path, const std::string& face_range) {
    const std::string key = path + "\n" + face_range;
    auto it = meshes_.find(key);
    if (it != meshes_.end()) return it->second;
    io::MeshFileOptions options;
    if (!face_range.empty()) parse_range("face-range", face_range, options.face_begin, options.face_end);
    return meshes_.emplace(key, io::read_mesh(path, options)).first->second;
  }

 private:
  std::map<std::string, io::LoadedMesh> meshes_;
};

// The geodesic disk of the spec (file vertex -> mesh vertex checked).
inline Patch cut_patch(MeshCache& cache, const EntrySpec& spec) {
  require(!spec.mesh.empty(), MCON_ERROR_INVALID_ARGUMENT, "no --mesh given for the entry");
  const io::LoadedMesh& loaded = cache.get(spec.mesh, spec.face_range);
  const int center = io::mesh_vertex_of_file_vertex(loaded, spec.center_vertex, "--center-vertex", spec.mesh);
  require(spec.radius > 0, MCON_ERROR_INVALID_ARGUMENT, "--radius must be > 0 (got " + std::to_string(spec.radius) + ")");
  PatchOptions options;
  options.center.vertex = center;
  options.radius = spec.radius;
  return extract_geodesic_disk(loaded.mesh, options);
}

// The metadata part of a library entry.
inline MacroConstraint entry_content(const EntrySpec& spec) {
  MacroConstraint e;
  e.name = spec.name;
  e.class_label = spec.class_label;
  e.author = spec.author;
  e.licence = spec.licence;
  e.tags = spec.tags;
  return e;
}

// Library-wide summary (counts and retrieval config) for `info` and `build`.
inline tools::Json library_summary(const ConstraintLibrary& lib) {
  const RetrievalConfig& c = lib.retrieval();
  tools::Json j = tools::Json::object();
  j.set("entries", static_cast<unsigned long>(lib.size()));
  j.set("descriptor", c.descriptor);
  j.set("descriptor_dimension", static_cast<unsigned long>(c.dimension));
  j.set("vocabulary_size", static_cast<unsigned long>(c.vocabulary_size));
  j.set("rings", static_cast<unsigned long>(c.rings));
  j.set("histogram_length", static_cast<unsigned long>(c.histogram_length()));
  j.set("sigma_bof", c.sigma_bof);
  j.set("seed", std::to_string(c.seed));  // a string: 64-bit seeds do not fit a JSON double
  return j;
}

}  // namespace mcon::cli
