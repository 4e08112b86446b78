// Shared by the writers: a file must never reference a vertex it does not contain.
#pragma once

#include <string>

#include "base/error.h"
#include "mesh/mesh.h"

namespace mcon::io {

inline void check_writable(const TriMesh& mesh, const std::string& path) {
  const int nv = mesh.num_vertices();
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int v : mesh.triangles[t])
      if (v < 0 || v >= nv)
        fail(MCON_ERROR_INVALID_ARGUMENT, "cannot write '" + path + "': triangle " + std::to_string(t) +
                                              " uses vertex " + std::to_string(v) + " of " + std::to_string(nv));
}

}  // namespace mcon::io
