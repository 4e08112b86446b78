// File numbering -> mesh numbering for what a user names on the command line or in a host
// (a vertex or face number as written in their file). One check, one message everywhere: the
// message gives the valid range and says why a number in range can still be refused (the
// loader drops vertices no face uses, and faces outside --face-range or the OBJ group).
#include <string>

#include "base/error.h"
#include "io/mesh_io.h"

namespace mcon::io {

int mesh_vertex_of_file_vertex(const LoadedMesh& loaded, long file_vertex, const std::string& what,
                               const std::string& mesh_name) {
  const std::string surface = mesh_name.empty() ? "the surface" : "the surface of '" + mesh_name + "'";
  const long n = static_cast<long>(loaded.file_to_mesh.size());
  require(n > 0, MCON_ERROR_INVALID_ARGUMENT, what + ": the mesh has no vertices");
  require(file_vertex >= 0 && file_vertex < n, MCON_ERROR_INVALID_ARGUMENT,
          what + " " + std::to_string(file_vertex) + " is not a vertex of " + surface + ": the file has vertices 0.." +
              std::to_string(n - 1) + " (numbers count from 0)");
  const int v = loaded.file_to_mesh[static_cast<std::size_t>(file_vertex)];
  require(v >= 0, MCON_ERROR_INVALID_ARGUMENT,
          what + " " + std::to_string(file_vertex) +
              " is not a vertex of " + surface + ": no kept face uses it (unreferenced, or outside the face range or "
              "group); pick a vertex of a kept face");
  return v;
}

int mesh_triangle_of_file_face(const LoadedMesh& loaded, long file_face, const std::string& what) {
  for (std::size_t t = 0; t < loaded.triangle_to_face.size(); ++t)
    if (loaded.triangle_to_face[t] == file_face) return static_cast<int>(t);
  const std::string range = loaded.triangle_to_face.empty()
                                ? std::string("the mesh has no faces")
                                : "the kept faces are numbered " + std::to_string(loaded.triangle_to_face.front()) +
                                      ".." + std::to_string(loaded.triangle_to_face.back());
  fail(MCON_ERROR_INVALID_ARGUMENT, what + " " + std::to_string(file_face) + " is not a face of the surface: " + range +
                                        " (numbers count from 0)");
}

}  // namespace mcon::io
