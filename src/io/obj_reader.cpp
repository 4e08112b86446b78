// Wavefront OBJ: `v` positions, `f` polygons (v, v/vt, v//vn, v/vt/vn; negative indices count back
// from the last vertex read), `l` polylines (same index forms), `g`/`o` group names. Texture
// coordinates, normals, materials and everything else are skipped: only the surface and the
// polylines drawn on it are needed.
#include <climits>
#include <utility>

#include "io/polygon_soup.h"
#include "io/text_cursor.h"

namespace mcon::io {
namespace {

void read_vertex(TextCursor& in, PolygonSoup& soup) {
  double xyz[3];
  for (double& value : xyz)
    if (!in.read_double(value)) in.error("expected a vertex coordinate, found " + in.quote_here());
  soup.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
}

// Reads one face corner's vertex index (0-based) and skips its /vt/vn part.
int read_corner(TextCursor& in, int vertices_so_far) {
  long long index = 0;
  if (!in.read_integer(index, '/')) in.error("expected a face vertex index, found " + in.quote_here());
  for (int slashes = 0; in.peek() == '/'; ++slashes) {
    if (slashes == 2) in.error("too many '/' in a face corner");
    in.advance();
    long long ignored = 0;
    if (in.peek() != '/' && !TextCursor::is_delimiter(in.peek()) && !in.at_end() && !in.read_integer(ignored, '/'))
      in.error("expected a texture or normal index, found " + in.quote_here());
  }
  if (index == 0) in.error("face vertex index 0 (OBJ indices start at 1)");
  if (index > INT_MAX || index < -static_cast<long long>(INT_MAX))
    in.error("face vertex index " + std::to_string(index) + " is out of range");
  if (index < 0) {
    index += vertices_so_far;
    if (index < 0) in.error("relative face vertex index reaches before the first vertex");
    return static_cast<int>(index);
  }
  return static_cast<int>(index - 1);
}

}  // namespace

PolygonSoup parse_obj(std::string_view text, const std::string& file_name) {
  PolygonSoup soup;
  TextCursor in(text, file_name);
  // Positive indices may name vertices defined further down; those are checked at the end.
  std::vector<std::pair<int, int>> forward_references;  // (index, line)
  int current_group = -1;
  while (!in.at_end()) {
    const std::string_view keyword = in.word();
    if (keyword == "v") {
      read_vertex(in, soup);
    } else if (keyword == "f") {
      const int nv = static_cast<int>(soup.positions.size());
      std::size_t count = 0;
      while (!in.at_line_end()) {
        const int v = read_corner(in, nv);
        if (v >= nv) forward_references.emplace_back(v, in.line());
        soup.corners.push_back(v);
        ++count;
      }
      if (count < 3) in.error("face has " + std::to_string(count) + " vertices (at least 3 needed)");
      if (soup.corners.size() > static_cast<std::size_t>(INT_MAX)) in.error("too many face corners");
      soup.face_start.push_back(static_cast<int>(soup.corners.size()));
      soup.face_group.push_back(current_group);
    } else if (keyword == "l") {
      const int nv = static_cast<int>(soup.positions.size());
      std::vector<int> line;
      while (!in.at_line_end()) {
        const int v = read_corner(in, nv);
        if (v >= nv) forward_references.emplace_back(v, in.line());
        line.push_back(v);
      }
      if (line.size() < 2) in.error("line has " + std::to_string(line.size()) + " vertices (at least 2 needed)");
      soup.lines.push_back(std::move(line));
      soup.line_numbers.push_back(in.line());
    } else if (keyword == "g" || keyword == "o") {
      std::vector<std::string> names;
      while (!in.at_line_end()) names.emplace_back(in.word());
      if (names.empty()) names.emplace_back("default");
      soup.groups.push_back(std::move(names));
      current_group = static_cast<int>(soup.groups.size()) - 1;
    }
    if (soup.positions.size() > static_cast<std::size_t>(INT_MAX) - 1) in.error("too many vertices");
    in.next_line();
  }
  const int nv = static_cast<int>(soup.positions.size());
  for (const auto& [index, line] : forward_references)
    if (index >= nv)
      fail(MCON_ERROR_IO, file_name + ":" + std::to_string(line) + ": face vertex index " +
                              std::to_string(index + 1) + " but the file has " + std::to_string(nv) + " vertices");
  return soup;
}

}  // namespace mcon::io
