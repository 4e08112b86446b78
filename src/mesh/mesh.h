// The core's triangle mesh: plain positions and CCW triangles, validated on construction so
// every algorithm downstream can assume a finite, manifold, oriented mesh without isolated vertices
// (user meshes are oriented first: mesh/orientation.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace mcon {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Tri = std::array<int, 3>;

// The z component of the 2D cross product: twice the signed area of (0, a, b).
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Do the segments (a, b) and (p, q) cross properly, each strictly separating the other's ends? A
// point within eps of the other segment's line counts as on it, so collinear pieces (up to
// rounding) and touching ends never cross.
inline bool segments_cross_properly(const Vec2& a, const Vec2& b, const Vec2& p, const Vec2& q, double eps) {
  const auto side = [eps](const Vec2& u, const Vec2& v, const Vec2& x) {
    const double o = cross2(v - u, x - u), tol = eps * (v - u).norm();
    return o > tol ? 1 : o < -tol ? -1 : 0;
  };
  return side(a, b, p) * side(a, b, q) < 0 && side(p, q, a) * side(p, q, b) < 0;
}

struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<Tri> triangles;

  int num_vertices() const { return static_cast<int>(positions.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
};

// The element type of an index array (the C API's mcon_index_format).
enum class IndexType { uint32, int32, int64 };

inline std::size_t index_size(IndexType type) { return type == IndexType::int64 ? 8 : 4; }

// Strided input, as the C API receives it. A stride of 0 means tightly packed (3 positions or 3
// indices of their type per row).
struct MeshArrays {
  const void* positions = nullptr;
  bool positions_are_double = true;
  std::size_t position_stride = 0;
  std::size_t vertex_count = 0;
  const void* indices = nullptr;
  IndexType index_type = IndexType::uint32;
  std::size_t index_stride = 0;
  std::size_t triangle_count = 0;
};

// The supported coordinate range: every |coordinate| <= kMaxCoordinate and a bounding box whose
// diagonal is >= kMinExtent. Outside it, squared lengths and areas over- or underflow (a grid
// scaled by 1e200 or 1e-100 has "zero-area" triangles, at 1e100 the Laplacian cannot be
// factorized); validation reports MCON_ERROR_INVALID_ARGUMENT naming the range instead.
inline constexpr double kMaxCoordinate = 1e15;
inline constexpr double kMinExtent = 1e-15;

// Copies strided arrays into a TriMesh and validates it (throws mcon::Error).
TriMesh mesh_from_arrays(const MeshArrays& arrays);

// Copies strided arrays into a TriMesh, checking only the array sizes, pointers and index range
// (user meshes then go through orient_and_validate, mesh/orientation.h).
TriMesh copy_mesh_arrays(const MeshArrays& arrays);

// Throws mcon::Error with a distinct status and a message naming the first offending element:
// EMPTY_MESH, NON_FINITE, INDEX_OUT_OF_RANGE, REPEATED_INDEX, DEGENERATE_TRIANGLE,
// NON_MANIFOLD_EDGE, NON_MANIFOLD_VERTEX, ISOLATED_VERTEX.
void validate_mesh(const TriMesh& mesh);

// Same as validate_mesh but without the isolated-vertex rule (used by readers before compaction).
void validate_mesh_allow_isolated(const TriMesh& mesh);

// The per-element part of validate_mesh (EMPTY_MESH, NON_FINITE, INDEX_OUT_OF_RANGE,
// REPEATED_INDEX, DEGENERATE_TRIANGLE): what orient_mesh needs before it can look at edges.
void validate_mesh_elements(const TriMesh& mesh);

// EMPTY_MESH, NON_FINITE, INDEX_OUT_OF_RANGE, REPEATED_INDEX: what every mesh must pass before
// anything reads it, also one whose other defects are deferred (DefectPolicy::defer).
void validate_mesh_indices(const TriMesh& mesh);

// Local validation of a mesh whose defects were deferred: the triangles `part` (zero area; an edge
// used by more than two of them or twice in one direction) and the fans of `whole_vertices`
// (vertices all of whose triangles are in `part`; one with none is isolated). Given every triangle
// and vertex, it applies validate_mesh's rules beyond validate_mesh_indices, with their statuses.
// Messages name mesh indices, count the offenders as validate_mesh does and end with `where`
// (e.g. "within 3 radii of the center").
// With `accept_repairable`, zero-area triangles and pinched vertices are not errors but returned
// (for an opt-in repair that removes or splits them); the other rules still throw.
struct PartDefects {
  std::vector<int> zero_area_triangles;
  std::vector<int> pinched_vertices;
};
PartDefects validate_mesh_part(const TriMesh& mesh, const std::vector<int>& part, const std::vector<int>& whole_vertices,
                               const std::string& where, bool accept_repairable = false);

// Zero area relative to the longest edge (|cross| <= 1e-12 * longest^2): what validate_mesh refuses.
bool has_zero_area(const TriMesh& mesh, int t);
double triangle_area(const TriMesh& mesh, int t);
Vec3 triangle_normal(const TriMesh& mesh, int t);  // unit normal (zero for a degenerate triangle)
double total_area(const TriMesh& mesh);
double mean_edge_length(const TriMesh& mesh);

// Drops vertices used by no triangle. Returns for each old vertex its new index or -1.
std::vector<int> remove_unreferenced_vertices(TriMesh& mesh);

}  // namespace mcon
