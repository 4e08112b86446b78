// Shared by the `macrocon library` commands: entry specs (mesh file, center vertex in file
// numbering, radius, metadata), reading meshes once, cutting patches through the public API, and
// the JSON of a library.
#pragma once

#include <array>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "base/error.h"
#include "command/args.h"
#include "command/command.h"
#include "entry_authoring.h"
#include "io/mesh_io.h"
#include "json/json_file.h"
#include "macrocon/macrocon.hpp"
#include "sdk_arrays.h"

namespace mcon::cli {

// One patch to cut, with what the entry records about it.
struct EntrySpec {
  std::string mesh;        // mesh file
  std::string face_range;  // "BEGIN:END" (file faces) or empty for all
  long center_vertex = -1; // file vertex numbering
  double radius = 0;       // geodesic radius in mesh units
  std::string class_label, name, author, licence;
  std::vector<std::string> tags;
  std::optional<std::array<double, 3>> up;  // the mesh's up direction (file coordinates)
  AuthoringSpec authoring;  // constraints from DCC files (guides, features, singularities, fields)
};

inline long parse_integer(const std::string& option, const std::string& s) { return ArgParser::parse_integer(option, s); }
inline double parse_real(const std::string& option, const std::string& s) { return ArgParser::parse_number(option, s); }

// Meshes read once per (file, face range), each with its SDK mesh.
class MeshCache {
 public:
  explicit MeshCache(macrocon::Context context) : context_(std::move(context)) {}

  // The mesh of an entry (one must have been given).
  const HostMesh& of(const EntrySpec& spec) {
    require(!spec.mesh.empty(), MCON_ERROR_INVALID_ARGUMENT, "no --mesh given for the entry");
    return get(spec.mesh, spec.face_range);
  }
  // Reads the file on first use; later calls only look it up (safe from several threads then).
  const HostMesh& get(const std::string& path, const std::string& face_range) {
    const std::string key = path + "\n" + face_range;
    auto it = meshes_.find(key);
    if (it != meshes_.end()) return it->second;
    io::MeshFileOptions options;
    if (!face_range.empty()) parse_range("face-range", face_range, options.face_begin, options.face_end);
    HostMesh host{io::read_mesh(path, options), {}};
    host.sdk = sdk_mesh(context_, host.file.mesh);
    return meshes_.emplace(key, std::move(host)).first->second;
  }

 private:
  macrocon::Context context_;
  std::map<std::string, HostMesh> meshes_;
};

// The geodesic disk of the spec (file vertex -> mesh vertex checked).
inline macrocon::Patch cut_patch(const HostMesh& host, const EntrySpec& spec) {
  const int center = io::mesh_vertex_of_file_vertex(host.file, spec.center_vertex, "--center-vertex", spec.mesh);
  require(spec.radius > 0, MCON_ERROR_INVALID_ARGUMENT,
          "--radius must be > 0 (got " + std::to_string(spec.radius) + ")");
  return macrocon::Patch::extract(host.sdk,
                                  macrocon::PatchOptions::at_vertex(static_cast<std::uint32_t>(center), spec.radius));
}

// The metadata part of a library entry.
inline macrocon::EntryData entry_content(const EntrySpec& spec) {
  macrocon::EntryData e;
  e.name = spec.name;
  e.class_label = spec.class_label;
  e.author = spec.author;
  e.licence = spec.licence;
  e.tags = spec.tags;
  e.up = spec.up;
  return e;
}

// Library-wide summary (counts and retrieval config) for `info` and `build`.
inline tools::Json library_summary(const macrocon::Library& lib) {
  const mcon_library_info c = lib.info();
  tools::Json j = tools::Json::object();
  j.set("entries", static_cast<unsigned long>(c.entry_count));
  j.set("descriptor", lib.string(MCON_LIBRARY_DESCRIPTOR));
  j.set("descriptor_dimension", static_cast<unsigned long>(c.descriptor_dimension));
  j.set("vocabulary_size", static_cast<unsigned long>(c.vocabulary_size));
  j.set("rings", static_cast<unsigned long>(c.rings));
  j.set("histogram_length", static_cast<unsigned long>(c.histogram_length));
  j.set("sigma_bof", c.sigma_bof);
  j.set("seed", std::to_string(c.seed));  // a string: 64-bit seeds do not fit a JSON double
  return j;
}

}  // namespace mcon::cli
