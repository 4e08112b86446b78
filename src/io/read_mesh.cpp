// One pipeline for all formats: parse the polygons as stored, keep the requested faces (range,
// OBJ group), fan-triangulate each polygon as (a,b,c), (a,c,d), ... — for quads this is the
// benchmark's diagonal — then drop unreferenced vertices and validate.
#include <string>

#include "base/error.h"
#include "io/file_suffix.h"
#include "io/mesh_io.h"
#include "io/polygon_soup.h"

namespace mcon::io {
namespace {

enum class MeshFormat { Obj, Off, Ply };

MeshFormat format_of(const std::string& path) {
  std::string_view name = path;
  if (is_gzip_path(name)) name.remove_suffix(3);
  if (ends_with_ignoring_case(name, ".obj")) return MeshFormat::Obj;
  if (ends_with_ignoring_case(name, ".off")) return MeshFormat::Off;
  if (ends_with_ignoring_case(name, ".ply")) return MeshFormat::Ply;
  fail(MCON_ERROR_IO, "'" + path + "': unknown mesh format (expected .obj, .off or .ply, optionally .gz)");
}

PolygonSoup parse(MeshFormat format, std::string_view data, const std::string& path) {
  switch (format) {
    case MeshFormat::Obj: return parse_obj(data, path);
    case MeshFormat::Off: return parse_off(data, path);
    case MeshFormat::Ply: return parse_ply(data, path);
  }
  fail(MCON_ERROR_UNKNOWN, "unhandled mesh format");
}

// Per `g`/`o` statement: does it name the wanted group?
std::vector<char> groups_matching(const PolygonSoup& soup, const std::string& wanted, const std::string& path) {
  std::vector<char> match(soup.groups.size(), 0);
  bool any = false;
  for (std::size_t g = 0; g < soup.groups.size(); ++g)
    for (const std::string& name : soup.groups[g])
      if (name == wanted) match[g] = 1, any = true;
  require(any, MCON_ERROR_NOT_FOUND, "'" + path + "' has no group named '" + wanted + "'");
  return match;
}

}  // namespace

LoadedMesh read_mesh(const std::string& path, const MeshFileOptions& options) {
  const MeshFormat format = format_of(path);
  require(options.obj_group.empty() || format == MeshFormat::Obj, MCON_ERROR_INVALID_ARGUMENT,
          "'" + path + "': obj_group applies to OBJ files only");
  const std::string data = read_file_maybe_gz(path, options.max_bytes);
  const PolygonSoup soup = parse(format, data, path);

  const long num_faces = soup.num_faces();
  const long face_end = options.face_end < 0 ? num_faces : options.face_end;
  require(options.face_begin >= 0 && options.face_begin <= face_end && face_end <= num_faces,
          MCON_ERROR_INVALID_ARGUMENT,
          "'" + path + "': face range [" + std::to_string(options.face_begin) + ", " + std::to_string(options.face_end) +
              ") does not fit the file's " + std::to_string(num_faces) + " faces");
  std::vector<char> group_match;
  if (!options.obj_group.empty()) group_match = groups_matching(soup, options.obj_group, path);

  LoadedMesh loaded;
  TriMesh& mesh = loaded.mesh;
  mesh.positions = soup.positions;
  const int nv = mesh.num_vertices();
  for (int f = static_cast<int>(options.face_begin); f < face_end; ++f) {
    if (!group_match.empty() && (soup.face_group[f] < 0 || !group_match[soup.face_group[f]])) continue;
    const int begin = soup.face_start[f], end = soup.face_start[f + 1];
    for (int k = begin; k < end; ++k)  // the parsers check this; a bad index must never reach the core
      if (soup.corners[k] < 0 || soup.corners[k] >= nv)
        fail(MCON_ERROR_IO, "'" + path + "': face " + std::to_string(f) + " has an invalid vertex index");
    for (int k = begin + 1; k + 1 < end; ++k) {
      mesh.triangles.push_back({soup.corners[begin], soup.corners[k], soup.corners[k + 1]});
      loaded.triangle_to_face.push_back(f);
    }
  }

  loaded.file_to_mesh = remove_unreferenced_vertices(mesh);
  loaded.mesh_to_file.assign(mesh.positions.size(), -1);
  for (int v = 0; v < static_cast<int>(loaded.file_to_mesh.size()); ++v)
    if (loaded.file_to_mesh[v] >= 0) loaded.mesh_to_file[loaded.file_to_mesh[v]] = v;
  try {
    loaded.orientation = orient_and_validate(mesh, options.orientation);
  } catch (const Error& e) {
    // Same status; the message says which file, in mesh (not file) numbering.
    throw Error(e.status(), "'" + path + "' (after reading, in mesh numbering): " + e.what());
  }
  return loaded;
}

}  // namespace mcon::io
