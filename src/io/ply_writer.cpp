// Binary little-endian PLY for inspecting results in any viewer: float positions, per-vertex
// float attributes and per-face int attributes. Bytes are composed explicitly in little-endian
// order, so the output does not depend on the host.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>

#include "io/mesh_io.h"
#include "io/writer_input.h"

namespace mcon::io {
namespace {

void append_u32_le(std::string& out, std::uint32_t bits) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((bits >> (8 * i)) & 0xFF);
}

void append_float(std::string& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  append_u32_le(out, bits);
}

void append_int(std::string& out, int value) { append_u32_le(out, static_cast<std::uint32_t>(value)); }

// PLY names are single tokens; keep [A-Za-z0-9_] so every reader accepts them.
std::string sanitize(const std::string& name) {
  std::string out = name.empty() ? std::string("attribute") : name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  return out;
}

// The property names of one attribute, made distinct from every name already used.
std::vector<std::string> unique_names(const std::string& name, int components, std::set<std::string>& used) {
  static const char* suffixes[3] = {"_x", "_y", "_z"};
  const std::string base = sanitize(name);
  for (int attempt = 0;; ++attempt) {
    const std::string stem = attempt == 0 ? base : base + "_" + std::to_string(attempt);
    std::vector<std::string> names;
    for (int c = 0; c < components; ++c) names.push_back(components == 1 ? stem : stem + suffixes[c]);
    bool clash = false;
    for (const std::string& n : names) clash = clash || used.count(n) > 0;
    if (clash) continue;
    used.insert(names.begin(), names.end());
    return names;
  }
}

void check_attributes(const std::string& path, const TriMesh& mesh, const std::vector<VertexAttribute>& vertex_attributes,
                      const std::vector<FaceAttribute>& face_attributes) {
  const std::size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  for (const VertexAttribute& a : vertex_attributes) {
    require(a.components >= 1 && a.components <= 3, MCON_ERROR_INVALID_ARGUMENT,
            "cannot write '" + path + "': vertex attribute '" + a.name + "' has " + std::to_string(a.components) +
                " components (1 to 3 allowed)");
    require(a.values.size() == nv * static_cast<std::size_t>(a.components), MCON_ERROR_INVALID_ARGUMENT,
            "cannot write '" + path + "': vertex attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                " values, expected " + std::to_string(nv * static_cast<std::size_t>(a.components)));
  }
  for (const FaceAttribute& a : face_attributes)
    require(a.values.size() == nt, MCON_ERROR_INVALID_ARGUMENT,
            "cannot write '" + path + "': face attribute '" + a.name + "' has " + std::to_string(a.values.size()) +
                " values for " + std::to_string(nt) + " triangles");
}

}  // namespace

void write_ply(const std::string& path, const TriMesh& mesh, const std::vector<VertexAttribute>& vertex_attributes,
               const std::vector<FaceAttribute>& face_attributes) {
  check_writable(mesh, path);
  check_attributes(path, mesh, vertex_attributes, face_attributes);

  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by macrocon\n";
  out += "element vertex " + std::to_string(mesh.num_vertices()) + "\n";
  out += "property float x\nproperty float y\nproperty float z\n";
  std::set<std::string> used = {"x", "y", "z"};
  for (const VertexAttribute& a : vertex_attributes)
    for (const std::string& name : unique_names(a.name, a.components, used)) out += "property float " + name + "\n";
  out += "element face " + std::to_string(mesh.num_triangles()) + "\n";
  out += "property list uchar int vertex_indices\n";
  used = {"vertex_indices"};
  for (const FaceAttribute& a : face_attributes) out += "property int " + unique_names(a.name, 1, used)[0] + "\n";
  out += "end_header\n";

  std::size_t vertex_floats = 3;
  for (const VertexAttribute& a : vertex_attributes) vertex_floats += static_cast<std::size_t>(a.components);
  out.reserve(out.size() + 4 * vertex_floats * mesh.positions.size() +
              (13 + 4 * face_attributes.size()) * mesh.triangles.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    for (int i = 0; i < 3; ++i) append_float(out, mesh.positions[v][i]);
    for (const VertexAttribute& a : vertex_attributes)
      for (int c = 0; c < a.components; ++c) append_float(out, a.values[v * static_cast<std::size_t>(a.components) + c]);
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    out += static_cast<char>(3);
    for (int v : mesh.triangles[t]) append_int(out, v);
    for (const FaceAttribute& a : face_attributes) append_int(out, a.values[t]);
  }
  write_file_maybe_gz(path, out);
}

}  // namespace mcon::io
