// What every format parser produces: the file's vertices and polygons exactly as stored (file
// order, 0-based, indices already range-checked), before face selection, triangulation,
// compaction and validation, which read_mesh does once for all formats.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh.h"

namespace mcon::io {

struct PolygonSoup {
  std::vector<Vec3> positions;
  std::vector<int> corners;     // all polygons' vertex indices, concatenated
  std::vector<int> face_start;  // polygon f is corners[face_start[f], face_start[f + 1])
  // OBJ only: per polygon, the index of its `g`/`o` statement in `groups` (-1 before any).
  std::vector<int> face_group;
  std::vector<std::vector<std::string>> groups;  // the names of each `g`/`o` statement
  // OBJ only: the `l` statements, each the 0-based vertex indices of one polyline (>= 2), and the
  // line each was read from (for messages).
  std::vector<std::vector<int>> lines;
  std::vector<int> line_numbers;
  // PLY only, when parse_ply is asked for them: the vertex element's scalar properties other
  // than x, y, z, by name, vertex-major (vertex_property_names.size() values per vertex).
  std::vector<std::string> vertex_property_names;
  std::vector<double> vertex_property_values;

  PolygonSoup() : face_start{0} {}
  int num_faces() const { return static_cast<int>(face_start.size()) - 1; }
};

// Each throws mcon::Error(MCON_ERROR_IO, "<file_name>:<line>: ...") on malformed content.
PolygonSoup parse_obj(std::string_view text, const std::string& file_name);
PolygonSoup parse_off(std::string_view text, const std::string& file_name);
PolygonSoup parse_ply(std::string_view data, const std::string& file_name, bool keep_vertex_properties = false);

}  // namespace mcon::io
