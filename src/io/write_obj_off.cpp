// ASCII OBJ and OFF. Coordinates use std::to_chars' shortest representation that parses back to
// the same double, so a write/read round trip is exact.
#include <charconv>
#include <string>

#include "io/mesh_io.h"
#include "io/writer_input.h"

namespace mcon::io {
namespace {

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

void append_number(std::string& out, int value) {
  char buffer[16];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

void append_position(std::string& out, const Vec3& p) {
  for (int i = 0; i < 3; ++i) {
    if (i > 0) out += ' ';
    append_number(out, p[i]);
  }
  out += '\n';
}

}  // namespace

void write_obj(const std::string& path, const TriMesh& mesh) {
  check_writable(mesh, path);
  std::string out = "# written by macrocon\n";
  out.reserve(out.size() + 64 * mesh.positions.size() + 32 * mesh.triangles.size());
  for (const Vec3& p : mesh.positions) {
    out += "v ";
    append_position(out, p);
  }
  for (const Tri& t : mesh.triangles) {
    out += 'f';
    for (int v : t) {
      out += ' ';
      append_number(out, v + 1);
    }
    out += '\n';
  }
  write_file_maybe_gz(path, out);
}

void write_off(const std::string& path, const TriMesh& mesh) {
  check_writable(mesh, path);
  std::string out = "OFF\n";
  out.reserve(64 * mesh.positions.size() + 32 * mesh.triangles.size() + 64);
  append_number(out, mesh.num_vertices());
  out += ' ';
  append_number(out, mesh.num_triangles());
  out += " 0\n";
  for (const Vec3& p : mesh.positions) append_position(out, p);
  for (const Tri& t : mesh.triangles) {
    out += '3';
    for (int v : t) {
      out += ' ';
      append_number(out, v);
    }
    out += '\n';
  }
  write_file_maybe_gz(path, out);
}

}  // namespace mcon::io
