#include "mesh/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>
#include <unordered_map>

#include "base/error.h"
#include "base/text.h"
#include "mesh/edge_key.h"

namespace mcon {

bool has_zero_area(const TriMesh& mesh, int t) {
  const Tri& tri = mesh.triangles[t];
  const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  // Relative test: exact collinearity gives round-off of order 1e-16 * longest^2.
  return !((b - a).cross(c - a).norm() > 1e-12 * longest);
}

namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// One validation rule's offenders: the error names the first in full, then how many break the
// rule and the first few, so a vendor fixes them all in one pass rather than one per run (issue 17).
class Offenders {
 public:
  Offenders(mcon_status status, std::string plural, std::string where = "")
      : status_(status), plural_(std::move(plural)), where_(std::move(where)) {}
  void add(int index, const std::function<std::string()>& detail) {
    if (count_ == 0) first_detail_ = detail();
    if (count_ < kShown) first_.push_back(index);
    ++count_;
  }
  int first() const { return first_.empty() ? std::numeric_limits<int>::max() : first_[0]; }
  void fail_if_any() const {
    if (count_ == 0) return;
    std::string message = first_detail_;
    if (count_ > 1) {
      message += " (" + std::to_string(count_) + " " + plural_ + " in all" + (count_ > kShown ? ", the first " : ": ");
      if (count_ > kShown) message += std::to_string(kShown) + ": ";
      for (std::size_t i = 0; i < first_.size(); ++i) message += (i ? ", " : "") + std::to_string(first_[i]);
      message += ")";
    }
    if (!where_.empty()) message += " " + where_;
    fail(status_, message);
  }

 private:
  static constexpr long kShown = 8;
  mcon_status status_;
  std::string plural_;
  std::string where_;
  std::string first_detail_;
  std::vector<int> first_;
  long count_ = 0;
};

// Coordinates within the supported range (mesh.h), checked after finiteness.
void check_coordinate_range(const TriMesh& mesh) {
  if (mesh.positions.empty()) return;
  Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.positions[v];
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate)
      fail(MCON_ERROR_INVALID_ARGUMENT, "vertex " + std::to_string(v) + " has a coordinate of magnitude " +
                                            number_text(p.cwiseAbs().maxCoeff()) + ", outside the supported range (|x| <= " +
                                            number_text(kMaxCoordinate) + "); rescale the mesh (e.g. to metres)");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double extent = (hi - lo).norm();
  if (mesh.num_vertices() > 1 && extent < kMinExtent)
    fail(MCON_ERROR_INVALID_ARGUMENT, "the mesh's bounding box diagonal is " + number_text(extent) +
                                          ", below the supported minimum " + number_text(kMinExtent) +
                                          "; rescale the mesh (e.g. to metres)");
}

// Finite positions; triangle indices in range and distinct.
void check_positions_and_indices(const TriMesh& mesh) {
  const int nv = mesh.num_vertices();
  const int nt = mesh.num_triangles();
  Offenders non_finite(MCON_ERROR_NON_FINITE, "vertices have a non-finite coordinate");
  for (int v = 0; v < nv; ++v) {
    const Vec3& p = mesh.positions[v];
    if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())))
      non_finite.add(v, [&] { return "vertex " + std::to_string(v) + " has a non-finite coordinate"; });
  }
  non_finite.fail_if_any();
  check_coordinate_range(mesh);
  Offenders repeated(MCON_ERROR_REPEATED_INDEX, "triangles repeat a vertex");
  for (int t = 0; t < nt; ++t) {
    const Tri& tri = mesh.triangles[t];
    for (int i = 0; i < 3; ++i) {
      if (tri[i] < 0 || tri[i] >= nv)
        fail(MCON_ERROR_INDEX_OUT_OF_RANGE, "triangle " + std::to_string(t) + " uses vertex index " +
                                                std::to_string(static_cast<unsigned>(tri[i])) + " but the mesh has " +
                                                std::to_string(nv) + " vertices");
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      repeated.add(t, [&] {
        return "triangle " + std::to_string(t) + " repeats a vertex (" + std::to_string(tri[0]) + ", " +
               std::to_string(tri[1]) + ", " + std::to_string(tri[2]) + ")";
      });
  }
  repeated.fail_if_any();
}

void check_triangle_areas(const TriMesh& mesh) {
  Offenders zero_area(MCON_ERROR_DEGENERATE_TRIANGLE, "triangles have zero area");
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    if (has_zero_area(mesh, t))
      zero_area.add(t, [&] { return "triangle " + std::to_string(t) + " has zero area"; });
  }
  zero_area.fail_if_any();
}

// Directed edges: each may appear once; its reverse at most once.
void check_directed_edges(const TriMesh& mesh) {
  const int nt = mesh.num_triangles();
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(static_cast<std::size_t>(nt) * 3);
  Offenders shared(MCON_ERROR_NON_MANIFOLD_EDGE, "triangles reuse a directed edge");
  for (int t = 0; t < nt; ++t) {
    const Tri& tri = mesh.triangles[t];
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      auto [it, inserted] = directed.emplace(directed_edge_key(a, b), t);
      if (!inserted) {
        const int other = it->second;
        shared.add(t, [&] {
          return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ") is used by triangles " +
                 std::to_string(other) + " and " + std::to_string(t) +
                 " in the same direction (more than two triangles, or inconsistent orientation: orient_mesh repairs "
                 "that)";
        });
      }
    }
  }
  shared.fail_if_any();
}

// The number of fans the triangles `ts` around vertex v form: connected through the edges
// incident to v (one for a manifold vertex). `link` is scratch: (link vertex, slot).
int fan_count(const TriMesh& mesh, int v, const std::vector<int>& ts, std::vector<int>& parent,
              std::vector<std::pair<int, int>>& link) {
  parent.resize(ts.size());
  std::iota(parent.begin(), parent.end(), 0);
  link.clear();
  for (int k = 0; k < static_cast<int>(ts.size()); ++k) {
    for (int w : mesh.triangles[ts[k]]) {
      if (w == v) continue;
      auto it = std::find_if(link.begin(), link.end(), [w](const auto& e) { return e.first == w; });
      if (it == link.end())
        link.emplace_back(w, k);
      else
        parent[find_root(parent, k)] = find_root(parent, it->second);
    }
  }
  int fans = 0;
  for (int k = 0; k < static_cast<int>(ts.size()); ++k) fans += (find_root(parent, k) == k);
  return fans;
}

std::string pinched_text(int v, int fans) {
  return "vertex " + std::to_string(v) + " joins " + std::to_string(fans) +
         " separate fans of triangles (non-manifold vertex)";
}

// Vertex fans: the triangles around a vertex must form one fan, i.e. be connected through the
// edges incident to that vertex.
void check_vertex_fans(const TriMesh& mesh, bool allow_isolated) {
  const int nv = mesh.num_vertices();
  const int nt = mesh.num_triangles();
  std::vector<std::vector<int>> vertex_triangles(nv);
  for (int t = 0; t < nt; ++t)
    for (int v : mesh.triangles[t]) vertex_triangles[v].push_back(t);
  std::vector<int> parent;
  std::vector<std::pair<int, int>> link;  // valences are small
  Offenders isolated(MCON_ERROR_ISOLATED_VERTEX, "vertices are used by no triangle");
  Offenders pinched(MCON_ERROR_NON_MANIFOLD_VERTEX, "vertices join separate fans");
  for (int v = 0; v < nv; ++v) {
    const auto& ts = vertex_triangles[v];
    if (ts.empty()) {
      if (!allow_isolated) isolated.add(v, [&] { return "vertex " + std::to_string(v) + " is not used by any triangle"; });
      continue;
    }
    const int fans = fan_count(mesh, v, ts, parent, link);
    if (fans != 1) pinched.add(v, [&] { return pinched_text(v, fans); });
  }
  // The rule broken first in vertex order is reported, as when the scan stopped at the first.
  if (isolated.first() < pinched.first()) isolated.fail_if_any();
  pinched.fail_if_any();
  isolated.fail_if_any();
}

// EMPTY_MESH, then check_positions_and_indices: validate_mesh_indices.
void check_indices(const TriMesh& mesh) {
  require(mesh.num_vertices() > 0 && mesh.num_triangles() > 0, MCON_ERROR_EMPTY_MESH,
          "mesh is empty (" + std::to_string(mesh.num_vertices()) + " vertices, " +
              std::to_string(mesh.num_triangles()) + " triangles)");
  check_positions_and_indices(mesh);
}

void check_elements(const TriMesh& mesh) {
  check_indices(mesh);
  check_triangle_areas(mesh);
}

void validate_impl(const TriMesh& mesh, bool allow_isolated) {
  check_elements(mesh);
  check_directed_edges(mesh);
  check_vertex_fans(mesh, allow_isolated);
}

template <typename Scalar>
Vec3 read_position(const unsigned char* base, std::size_t stride, std::size_t i) {
  Scalar xyz[3];
  std::memcpy(xyz, base + i * stride, sizeof(xyz));
  return Vec3(static_cast<double>(xyz[0]), static_cast<double>(xyz[1]), static_cast<double>(xyz[2]));
}

// Reads 3 indices of type Index per row (memcpy: rows need no alignment) and checks each against
// [0, vertex_count): a negative signed index and one too large are INDEX_OUT_OF_RANGE alike.
template <typename Index>
void read_triangles(const unsigned char* base, std::size_t stride, std::size_t vertex_count,
                    std::vector<Tri>& triangles) {
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    Index idx[3];
    std::memcpy(idx, base + t * stride, sizeof(idx));
    for (int k = 0; k < 3; ++k) {
      bool in_range = true;
      if constexpr (std::is_signed_v<Index>) in_range = idx[k] >= 0;
      in_range = in_range && static_cast<std::uint64_t>(idx[k]) < vertex_count;
      require(in_range, MCON_ERROR_INDEX_OUT_OF_RANGE,
              "triangle " + std::to_string(t) + " uses vertex index " + std::to_string(idx[k]) +
                  ", outside the valid range [0, " + std::to_string(vertex_count) + "): the mesh has " +
                  std::to_string(vertex_count) + " vertices");
      triangles[t][k] = static_cast<int>(idx[k]);
    }
  }
}

}  // namespace

void validate_mesh(const TriMesh& mesh) { validate_impl(mesh, false); }
void validate_mesh_allow_isolated(const TriMesh& mesh) { validate_impl(mesh, true); }
void validate_mesh_elements(const TriMesh& mesh) { check_elements(mesh); }

void validate_mesh_indices(const TriMesh& mesh) { check_indices(mesh); }

PartDefects validate_mesh_part(const TriMesh& mesh, const std::vector<int>& part, const std::vector<int>& whole_vertices,
                               const std::string& where, bool accept_repairable) {
  PartDefects defects;
  Offenders zero_area(MCON_ERROR_DEGENERATE_TRIANGLE, "triangles have zero area", where);
  for (int t : part)
    if (has_zero_area(mesh, t)) {
      zero_area.add(t, [&] { return "triangle " + std::to_string(t) + " has zero area"; });
      defects.zero_area_triangles.push_back(t);
    }
  if (!accept_repairable) zero_area.fail_if_any();

  // Edges: the undirected edge's triangles in the part, and each direction's count.
  std::unordered_map<std::uint64_t, std::array<int, 3>> edges;  // key -> {triangles, forward, first triangle}
  edges.reserve(3 * part.size());
  for (int t : part)
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.triangles[t][i], b = mesh.triangles[t][(i + 1) % 3];
      auto [it, inserted] = edges.emplace(edge_key(a, b), std::array<int, 3>{0, 0, t});
      ++it->second[0];
      it->second[1] += a < b;
    }
  // Listed by the first triangle of each bad edge (a surface edge has at most two, run opposite ways).
  Offenders shared(MCON_ERROR_NON_MANIFOLD_EDGE, "triangles start an edge used by more than two or twice in one direction",
                   where);
  for (int t : part)
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.triangles[t][i], b = mesh.triangles[t][(i + 1) % 3];
      const std::array<int, 3>& e = edges.at(edge_key(a, b));
      if (e[2] != t || !(e[0] > 2 || (e[0] == 2 && e[1] != 1))) continue;
      shared.add(t, [&] {
        return "edge (" + std::to_string(std::min(a, b)) + ", " + std::to_string(std::max(a, b)) + ") of triangle " +
               std::to_string(t) + " is used by " + std::to_string(e[0]) + " triangles" +
               (e[0] == 2 ? " in the same direction" : "") + ": remove the extra or duplicate triangles";
      });
      break;
    }
  shared.fail_if_any();

  std::unordered_map<int, std::vector<int>> fans_of;
  std::vector<char> wanted(mesh.positions.size(), 0);
  for (int v : whole_vertices) wanted[static_cast<std::size_t>(v)] = 1;
  for (int t : part)
    for (int v : mesh.triangles[t])
      if (wanted[static_cast<std::size_t>(v)]) fans_of[v].push_back(t);
  std::vector<int> parent;
  std::vector<std::pair<int, int>> link;
  Offenders pinched(MCON_ERROR_NON_MANIFOLD_VERTEX, "vertices join separate fans", where);
  Offenders isolated(MCON_ERROR_ISOLATED_VERTEX, "vertices are used by no triangle", where);
  for (int v : whole_vertices) {
    const auto it = fans_of.find(v);
    if (it == fans_of.end()) {  // all of its triangles are in the part, and it has none
      isolated.add(v, [&] { return "vertex " + std::to_string(v) + " is not used by any triangle"; });
      continue;
    }
    const int fans = fan_count(mesh, v, it->second, parent, link);
    if (fans != 1) {
      pinched.add(v, [&] { return pinched_text(v, fans); });
      defects.pinched_vertices.push_back(v);
    }
  }
  if (accept_repairable) {
    isolated.fail_if_any();
    return defects;
  }
  if (isolated.first() < pinched.first()) isolated.fail_if_any();  // in vertex order, as validate_mesh
  pinched.fail_if_any();
  isolated.fail_if_any();
  return defects;
}

TriMesh mesh_from_arrays(const MeshArrays& in) {
  TriMesh mesh = copy_mesh_arrays(in);
  validate_mesh(mesh);
  return mesh;
}

TriMesh copy_mesh_arrays(const MeshArrays& in) {
  require(in.vertex_count > 0 && in.triangle_count > 0, MCON_ERROR_EMPTY_MESH,
          "mesh is empty (" + std::to_string(in.vertex_count) + " vertices, " + std::to_string(in.triangle_count) +
              " triangles)");
  require(in.positions != nullptr, MCON_ERROR_NULL_POINTER, "positions pointer is NULL");
  require(in.indices != nullptr, MCON_ERROR_NULL_POINTER, "indices pointer is NULL");
  require(in.vertex_count < (1u << 31) && in.triangle_count < (1u << 31), MCON_ERROR_INVALID_ARGUMENT,
          "meshes are limited to 2^31 - 1 vertices and triangles");
  const std::size_t scalar = in.positions_are_double ? sizeof(double) : sizeof(float);
  const std::size_t pstride = in.position_stride ? in.position_stride : 3 * scalar;
  const std::size_t isize = index_size(in.index_type);
  const std::size_t istride = in.index_stride ? in.index_stride : 3 * isize;
  require(pstride >= 3 * scalar, MCON_ERROR_INVALID_ARGUMENT,
          "position_stride " + std::to_string(pstride) + " is smaller than one position (" +
              std::to_string(3 * scalar) + " bytes)");
  require(istride >= 3 * isize, MCON_ERROR_INVALID_ARGUMENT,
          "index_stride " + std::to_string(istride) + " is smaller than one triangle (" + std::to_string(3 * isize) +
              " bytes)");

  TriMesh mesh;
  mesh.positions.resize(in.vertex_count);
  const auto* pbase = static_cast<const unsigned char*>(in.positions);
  for (std::size_t i = 0; i < in.vertex_count; ++i)
    mesh.positions[i] = in.positions_are_double ? read_position<double>(pbase, pstride, i)
                                                : read_position<float>(pbase, pstride, i);
  mesh.triangles.resize(in.triangle_count);
  const auto* ibase = static_cast<const unsigned char*>(in.indices);
  switch (in.index_type) {
    case IndexType::uint32: read_triangles<std::uint32_t>(ibase, istride, in.vertex_count, mesh.triangles); break;
    case IndexType::int32: read_triangles<std::int32_t>(ibase, istride, in.vertex_count, mesh.triangles); break;
    case IndexType::int64: read_triangles<std::int64_t>(ibase, istride, in.vertex_count, mesh.triangles); break;
  }
  return mesh;
}

double triangle_area(const TriMesh& mesh, int t) {
  const Tri& tri = mesh.triangles[t];
  const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
  return 0.5 * (b - a).cross(c - a).norm();
}

Vec3 triangle_normal(const TriMesh& mesh, int t) {
  const Tri& tri = mesh.triangles[t];
  const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
  const Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

double total_area(const TriMesh& mesh) {
  double area = 0;
  for (int t = 0; t < mesh.num_triangles(); ++t) area += triangle_area(mesh, t);
  return area;
}

double mean_edge_length(const TriMesh& mesh) {
  double sum = 0;
  for (const Tri& tri : mesh.triangles)
    for (int i = 0; i < 3; ++i) sum += (mesh.positions[tri[i]] - mesh.positions[tri[(i + 1) % 3]]).norm();
  return mesh.triangles.empty() ? 0.0 : sum / (3.0 * static_cast<double>(mesh.triangles.size()));
}

std::vector<int> remove_unreferenced_vertices(TriMesh& mesh) {
  std::vector<int> remap(mesh.positions.size(), -1);
  for (const Tri& tri : mesh.triangles)
    for (int v : tri) remap[v] = 0;
  int next = 0;
  for (std::size_t v = 0; v < remap.size(); ++v)
    if (remap[v] == 0) {
      mesh.positions[next] = mesh.positions[v];
      remap[v] = next++;
    }
  mesh.positions.resize(next);
  for (Tri& tri : mesh.triangles)
    for (int& v : tri) v = remap[v];
  return remap;
}

}  // namespace mcon
