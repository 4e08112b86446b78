// Mesh files for the CLI, tools, tests and samples (not part of the core's data flow): OBJ (quads
// and polygons fan-triangulated as a,b,c / a,c,d, so quad diagonals match the benchmark), OFF and
// PLY (ASCII and binary), each optionally gzip-compressed (`.gz`). PLY output carries per-vertex
// scalar and vector attributes so results can be inspected in any viewer.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/orientation.h"

namespace mcon::io {

// Largest input the readers accept, in bytes after decompression: a `.gz` file can inflate a
// thousandfold, so without a limit a small hostile file exhausts memory. 1 GiB of OBJ text is
// some 20 million vertices.
inline constexpr std::size_t kDefaultMaxInputBytes = std::size_t{1} << 30;

// The limit to apply: `requested` if not 0, else the environment variable
// MACROCON_MAX_INPUT_BYTES (a plain byte count; the CLI and tools read no option for it), else
// kDefaultMaxInputBytes. A malformed variable throws MCON_ERROR_INVALID_ARGUMENT.
std::size_t max_input_bytes(std::size_t requested = 0);

struct MeshFileOptions {
  // Keep only faces [face_begin, face_end) in file order (polygons counted before
  // triangulation); face_end < 0 means all.
  long face_begin = 0;
  long face_end = -1;
  // OBJ only: keep only faces in this group (`g` name); empty = all.
  std::string obj_group;
  // Refuse files larger than this after decompression (MCON_ERROR_IO); 0 = max_input_bytes().
  std::size_t max_bytes = 0;
  // How the mesh is oriented after reading (mesh/orientation.h): outward for hosts, majority for
  // an already-cut patch (a disk has no inside; a concave one must not be turned).
  OrientationRule orientation = OrientationRule::outward;
};

struct LoadedMesh {
  TriMesh mesh;                       // unreferenced vertices removed, oriented, validated
  std::vector<int> file_to_mesh;      // file vertex index -> mesh vertex index or -1
  std::vector<int> mesh_to_file;      // mesh vertex index -> file vertex index
  std::vector<int> triangle_to_face;  // mesh triangle -> file face index
  OrientationReport orientation;      // what orient_mesh changed (per mesh triangle)
};

// Throws mcon::Error(MCON_ERROR_IO) on unreadable or malformed files, and the errors of
// orient_and_validate on bad geometry.
LoadedMesh read_mesh(const std::string& path, const MeshFileOptions& options = {});

// The mesh vertex of a vertex number as written in the file; throws MCON_ERROR_INVALID_ARGUMENT
// naming `what` (e.g. "--center-vertex") and the valid range when the file has no such vertex or
// no kept face uses it (naming mesh_name, the file, when given).
int mesh_vertex_of_file_vertex(const LoadedMesh& loaded, long file_vertex, const std::string& what,
                               const std::string& mesh_name = {});

// The first mesh triangle of a face number as written in the file (a polygon is fanned into
// several); throws MCON_ERROR_INVALID_ARGUMENT naming `what` and the kept range otherwise.
int mesh_triangle_of_file_face(const LoadedMesh& loaded, long file_face, const std::string& what);

// Reads a whole file, transparently gunzipping `.gz` (any case); a truncated archive is an error.
// A file larger than max_input_bytes(max_bytes) (after decompression) is refused with
// MCON_ERROR_IO before more than that is held in memory.
std::string read_file_maybe_gz(const std::string& path, std::size_t max_bytes = 0);
// Writes a whole file, gzip-compressing when the path ends in `.gz` (any case).
void write_file_maybe_gz(const std::string& path, std::string_view bytes);

// Polylines drawn in a DCC and exported as OBJ `l` statements (guides, feature lines), in file
// coordinates and file order; a line whose last vertex repeats its first is closed (the repeat
// dropped). Faces and everything else in the file are ignored. MCON_ERROR_IO when malformed or
// when the file has no `l` statement (the message says what to export).
struct FilePolyline {
  std::vector<Vec3> points;  // >= 2 (>= 3 when closed)
  bool closed = false;
  int line = 0;              // the `l` statement's line in the file
};
std::vector<FilePolyline> read_obj_polylines(const std::string& path, std::size_t max_bytes = 0);

// Named columns of numbers with one row per item: per-vertex fields exported by a DCC, or a list
// of points. `.ply`: x, y, z and the vertex element's other scalar properties, one row per file
// vertex. `.csv` / `.txt`: a header line of column names, then one row per item, values separated
// by commas and/or blanks; `#` starts a comment. MCON_ERROR_IO when malformed (a row of the wrong
// length, a value that is not a finite number, repeated or missing column names).
struct ValueTable {
  std::vector<std::string> columns;
  std::vector<double> values;  // row-major, columns.size() per row
  std::size_t rows() const { return columns.empty() ? 0 : values.size() / columns.size(); }
  // The column's index, or -1.
  int column(const std::string& name) const;
  double at(std::size_t row, int column) const { return values[row * columns.size() + static_cast<std::size_t>(column)]; }
};
ValueTable read_value_table(const std::string& path, std::size_t max_bytes = 0);

struct VertexAttribute {
  std::string name;                   // e.g. "distance" or "uv" (components get _x/_y/... suffixes)
  int components = 1;                 // 1 (scalar), 2, 3
  std::vector<double> values;         // vertex-major, components per vertex
};

struct FaceAttribute {
  std::string name;
  std::vector<int> values;            // one integer per triangle
};

// Writers throw mcon::Error(MCON_ERROR_INVALID_ARGUMENT) on inconsistent input (index out of
// range, attribute of the wrong size) and MCON_ERROR_IO when the file cannot be written; a `.gz`
// path is gzip-compressed.
// Binary little-endian PLY with float positions and attributes: a scalar attribute becomes the
// property `name`, a 2- or 3-component one `name_x`, `name_y` (, `name_z`); names are reduced to
// [A-Za-z0-9_] and made unique. Face attributes become int properties after vertex_indices.
void write_ply(const std::string& path, const TriMesh& mesh, const std::vector<VertexAttribute>& vertex_attributes = {},
               const std::vector<FaceAttribute>& face_attributes = {});
// ASCII with shortest round-trip coordinates (reading them back gives the same doubles).
void write_obj(const std::string& path, const TriMesh& mesh);
void write_off(const std::string& path, const TriMesh& mesh);

// QuadWild's guide files (docs/design.md §7), in the layout QuadWild's readers expect, so the mesh
// file plus these two can be passed to `quadwild mesh.obj field.rosy mesh.sharp` (its main picks
// the files by their suffix). Face indices refer to the triangles in mesh order: write the mesh
// itself with write_obj/write_ply so QuadWild sees the same triangles in the same order.
//
// `.rosy` (read by vcglib ImporterFIELD::Load4ROSY, which requires count == face count and
// symmetry 4): "<face count>\n4\n", then per face one direction of the cross formatted like
// vcglib's writer, "%f %f %f \n" of the float values (6 decimals, trailing space). QuadWild takes
// the second direction as PD1 x N. Throws INVALID_ARGUMENT if directions.size() differs from the
// triangle count or a direction is not finite.
void write_rosy(const std::string& path, const TriMesh& mesh, const std::vector<Vec3>& directions);
// The directions of a `.rosy` file; MCON_ERROR_IO if malformed, MCON_ERROR_UNSUPPORTED if the
// symmetry is not 4.
std::vector<Vec3> read_rosy(const std::string& path);

// `.sharp` (read by QuadWild's LoadSharpFeatures): "<count>\n", then per feature edge
// "<kind>,<face>,<edge>\n" with kind 0 = concave, 1 = convex (QuadWild's test with its default
// LimitConcave = 0: concave iff (n_face x n_other) . edge direction < 0; boundary edges are
// convex) and `edge` the VCG edge index: the edge from corner `edge` to corner (edge + 1) % 3 of
// `face`. QuadWild marks the twin half-edge itself, so each edge is written once, from its
// lowest-index triangle.
struct SharpEdge {
  bool convex = true;
  int face = -1;
  int edge = -1;
};
// Feature edges as vertex pairs (either order). Throws INVALID_ARGUMENT if a pair is not an edge
// of the mesh; repeated edges are written once.
void write_sharp(const std::string& path, const TriMesh& mesh, const std::vector<std::array<int, 2>>& feature_edges);
// MCON_ERROR_IO if malformed.
std::vector<SharpEdge> read_sharp(const std::string& path);

}  // namespace mcon::io
