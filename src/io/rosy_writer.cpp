// QuadWild `.rosy` cross-field files. Lines are formatted like vcglib's own writer (ExporterFIELD:
// fprintf("%d\n", n); fprintf("4\n"); fprintf("%f %f %f \n", (float)x, ...)), and n is the face
// count, which the reader QuadWild uses (ImporterFIELD::Load4ROSY) requires; some vcglib versions'
// writer print the vertex count there. std::to_chars keeps the output independent of the C locale
// (QuadWild itself switches LC_NUMERIC to get '.' decimals).
#include <charconv>
#include <string>

#include "base/error.h"
#include "io/file_suffix.h"
#include "io/mesh_io.h"

namespace mcon::io {
namespace {

// printf("%f", (float)value): the float rounded to 6 fixed decimals.
void append_fixed6(std::string& out, double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), static_cast<double>(static_cast<float>(value)),
                                    std::chars_format::fixed, 6);
  out.append(buffer, result.ptr);
}

}  // namespace

void write_rosy(const std::string& path, const TriMesh& mesh, const std::vector<Vec3>& directions) {
  // QuadWild reads a gzip-compressed .rosy as all zeros and exits 0 (docs/design.md §7).
  require(!is_gzip_path(path), MCON_ERROR_INVALID_ARGUMENT,
          "cannot write '" + path + "': QuadWild reads a compressed .rosy as zeros; give a path without .gz");
  require(directions.size() == mesh.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
          "cannot write '" + path + "': " + std::to_string(directions.size()) + " directions for " +
              std::to_string(mesh.triangles.size()) + " triangles");
  std::string out = std::to_string(directions.size()) + "\n4\n";
  out.reserve(out.size() + 32 * directions.size());
  for (std::size_t f = 0; f < directions.size(); ++f) {
    const Vec3& d = directions[f];
    require(d.allFinite(), MCON_ERROR_INVALID_ARGUMENT,
            "cannot write '" + path + "': direction of face " + std::to_string(f) + " is not finite");
    for (int i = 0; i < 3; ++i) {
      append_fixed6(out, d[i]);
      out += ' ';
    }
    out += '\n';
  }
  write_file_maybe_gz(path, out);  // never .gz here
}

}  // namespace mcon::io
