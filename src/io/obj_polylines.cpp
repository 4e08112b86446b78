// OBJ `l` statements as polylines in file coordinates: what a DCC exports for curves drawn on a
// mesh (Blender's and Maya's OBJ exporters write edges and curves this way).
#include "base/error.h"
#include "io/mesh_io.h"
#include "io/polygon_soup.h"

namespace mcon::io {

std::vector<FilePolyline> read_obj_polylines(const std::string& path, std::size_t max_bytes) {
  const PolygonSoup soup = parse_obj(read_file_maybe_gz(path, max_bytes), path);
  require(!soup.lines.empty(), MCON_ERROR_IO,
          "'" + path + "' has no polyline (`l` statement): export the curves or edge loops as OBJ lines");
  std::vector<FilePolyline> out;
  for (std::size_t i = 0; i < soup.lines.size(); ++i) {
    const std::vector<int>& indices = soup.lines[i];
    FilePolyline line;
    line.line = soup.line_numbers[i];
    line.closed = indices.size() >= 4 && indices.front() == indices.back();
    const std::size_t n = line.closed ? indices.size() - 1 : indices.size();
    for (std::size_t k = 0; k < n; ++k) line.points.push_back(soup.positions[static_cast<std::size_t>(indices[k])]);
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace mcon::io
