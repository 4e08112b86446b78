// QuadWild `.sharp` feature-edge files, laid out as QuadWild's own SaveSharpFeatures writes them
// ("<count>\n" then "<kind>,<face>,<edge>\n"), with its convex/concave rule.
#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "base/error.h"
#include "mesh/edge_key.h"
#include "io/file_suffix.h"
#include "io/mesh_io.h"
#include "io/writer_input.h"

namespace mcon::io {
namespace {

// Both sides of an edge: (triangle, VCG edge index), the first from the lower triangle index.
struct EdgeSides {
  int face[2] = {-1, -1};
  int edge[2] = {-1, -1};
};

}  // namespace

void write_sharp(const std::string& path, const TriMesh& mesh, const std::vector<std::array<int, 2>>& feature_edges) {
  require(!is_gzip_path(path), MCON_ERROR_INVALID_ARGUMENT,
          "cannot write '" + path + "': QuadWild cannot read a compressed .sharp; give a path without .gz");
  check_writable(mesh, path);
  std::unordered_map<std::uint64_t, EdgeSides> sides;
  sides.reserve(2 * mesh.triangles.size());
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int j = 0; j < 3; ++j) {
      EdgeSides& s = sides[edge_key(mesh.triangles[t][j], mesh.triangles[t][(j + 1) % 3])];
      const int k = s.face[0] < 0 ? 0 : 1;
      s.face[k] = t;
      s.edge[k] = j;
    }

  std::string body;
  std::size_t count = 0;
  std::unordered_set<std::uint64_t> written;
  for (std::size_t i = 0; i < feature_edges.size(); ++i) {
    const int a = feature_edges[i][0], b = feature_edges[i][1];
    const auto it = a == b ? sides.end() : sides.find(edge_key(a, b));
    require(it != sides.end(), MCON_ERROR_INVALID_ARGUMENT,
            "cannot write '" + path + "': feature edge " + std::to_string(i) + " (" + std::to_string(a) + ", " +
                std::to_string(b) + ") is not an edge of the mesh");
    if (!written.insert(it->first).second) continue;
    const EdgeSides& s = it->second;
    bool convex = true;
    if (s.face[1] >= 0) {
      // QuadWild's IsConcaveEdge with LimitConcave = 0, on the side that is written.
      const Tri& tri = mesh.triangles[s.face[0]];
      const Vec3 dir = (mesh.positions[tri[(s.edge[0] + 1) % 3]] - mesh.positions[tri[s.edge[0]]]).normalized();
      const Vec3 cross = triangle_normal(mesh, s.face[0]).cross(triangle_normal(mesh, s.face[1]));
      convex = !(cross.dot(dir) < 0);
    }
    body += convex ? "1," : "0,";
    body += std::to_string(s.face[0]);
    body += ',';
    body += std::to_string(s.edge[0]);
    body += '\n';
    ++count;
  }
  write_file_maybe_gz(path, std::to_string(count) + "\n" + body);  // never .gz here
}

}  // namespace mcon::io
