// g++ 12 reports -Wmaybe-uninitialized inside OpenMesh's PropertyT::push_back (docs/design.md §8) at
// a libstdc++ location that SYSTEM includes do not cover, so it is off for this file, before any
// standard header is seen.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "common/retessellate.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "common/bench_random.h"
#include "base/error.h"

namespace mcon::tools {

namespace {

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

// 4 sqrt(3) area / sum of squared edge lengths: 1 for an equilateral triangle, 0 when degenerate.
double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double sum = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  return sum > 0 ? 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / sum : 0.0;
}

bool is_degenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  // The test of validate_mesh (src/mesh.cpp), with a safety factor.
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return (b - a).cross(c - a).norm() <= 1e-10 * longest;
}

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

Vec3 to_vec3(const OpenMesh::Vec3d& p) { return Vec3(p[0], p[1], p[2]); }

}  // namespace

Retessellation rediagonalize(const TriMesh& mesh, const std::vector<int>& triangle_to_face, DiagonalPattern pattern,
                             std::uint64_t seed) {
  require(triangle_to_face.size() == mesh.triangles.size(), MCON_ERROR_INVALID_ARGUMENT,
          "rediagonalize: triangle_to_face has " + std::to_string(triangle_to_face.size()) + " entries for " +
              std::to_string(mesh.triangles.size()) + " triangles");
  validate_mesh(mesh);
  std::unordered_set<std::uint64_t> edges;
  edges.reserve(mesh.triangles.size() * 2);
  for (const Tri& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) edges.insert(edge_key(t[i], t[(i + 1) % 3]));

  const BenchRng rng(seed, 0);
  Retessellation out;
  out.mesh.positions = mesh.positions;
  out.mesh.triangles.reserve(mesh.triangles.size());
  const std::size_t nt = mesh.triangles.size();
  for (std::size_t t = 0; t < nt;) {
    const int face = triangle_to_face[t];
    std::size_t end = t + 1;
    while (end < nt && triangle_to_face[end] == face) ++end;
    const Tri& first = mesh.triangles[t];
    // A quad a,b,c,d read as a,b,c + a,c,d.
    const bool quad = end - t == 2 && mesh.triangles[t + 1][0] == first[0] && mesh.triangles[t + 1][1] == first[2];
    bool flip = false;
    if (quad) {
      switch (pattern) {
        case DiagonalPattern::All: flip = true; break;
        case DiagonalPattern::Alternate: flip = face % 2 != 0; break;
        case DiagonalPattern::Random: flip = rng.uniform(static_cast<std::uint64_t>(face)) < 0.5; break;
      }
    }
    if (flip) {
      const int a = first[0], b = first[1], c = first[2], d = mesh.triangles[t + 1][2];
      const Vec3 &pa = mesh.positions[a], &pb = mesh.positions[b], &pc = mesh.positions[c], &pd = mesh.positions[d];
      const Vec3 quad_normal = (pb - pa).cross(pc - pa) + (pc - pa).cross(pd - pa);
      // The new edge b-d must not exist already (it would be shared by four triangles), and both new
      // triangles must face the quad's way.
      flip = !edges.count(edge_key(b, d)) && !is_degenerate(pa, pb, pd) && !is_degenerate(pb, pc, pd) &&
             (pb - pa).cross(pd - pa).dot(quad_normal) > 0 && (pc - pb).cross(pd - pb).dot(quad_normal) > 0;
      if (flip) {
        edges.erase(edge_key(a, c));
        edges.insert(edge_key(b, d));
        out.mesh.triangles.push_back({a, b, d});
        out.mesh.triangles.push_back({b, c, d});
        ++out.changed;
      }
    }
    if (!flip)
      for (std::size_t k = t; k < end; ++k) out.mesh.triangles.push_back(mesh.triangles[k]);
    t = end;
  }
  out.to_original.resize(mesh.positions.size());
  for (std::size_t v = 0; v < out.to_original.size(); ++v) out.to_original[v] = static_cast<int>(v);
  validate_mesh(out.mesh);
  return out;
}

Retessellation decimate(const TriMesh& mesh, std::uint64_t seed, const DecimationOptions& options) {
  require(options.min_fraction >= 0 && options.min_fraction <= options.max_fraction && options.max_fraction < 1,
          MCON_ERROR_INVALID_ARGUMENT, "decimate: need 0 <= min_fraction <= max_fraction < 1");
  require(options.max_normal_change_degrees > 0 && options.max_normal_change_degrees <= 180 &&
              options.min_quality >= 0 && options.min_quality < 1,
          MCON_ERROR_INVALID_ARGUMENT, "decimate: need 0 < max_normal_change_degrees <= 180 and 0 <= min_quality < 1");
  validate_mesh(mesh);
  const int nv = mesh.num_vertices();
  std::vector<char> keep(static_cast<std::size_t>(nv), 0);
  for (const int v : options.keep) {
    require(v >= 0 && v < nv, MCON_ERROR_INDEX_OUT_OF_RANGE,
            "decimate: keep vertex " + std::to_string(v) + " is outside the mesh's " + std::to_string(nv) + " vertices");
    keep[static_cast<std::size_t>(v)] = 1;
  }

  OMesh om;
  om.request_vertex_status();
  om.request_edge_status();
  om.request_halfedge_status();
  om.request_face_status();
  om.reserve(static_cast<std::size_t>(nv), mesh.triangles.size() * 3 / 2 + 3, mesh.triangles.size());
  for (const Vec3& p : mesh.positions) om.add_vertex(OMesh::Point(p.x(), p.y(), p.z()));
  for (const Tri& t : mesh.triangles) {
    const OMesh::FaceHandle f =
        om.add_face(OMesh::VertexHandle(t[0]), OMesh::VertexHandle(t[1]), OMesh::VertexHandle(t[2]));
    // validate_mesh passed, so OpenMesh must accept every face.
    require(f.is_valid(), MCON_ERROR_NON_MANIFOLD_VERTEX, "decimate: OpenMesh rejected a triangle");
  }

  const BenchRng rng(seed, 0);
  const double fraction = rng.uniform(0, options.min_fraction, options.max_fraction);
  const int target = static_cast<int>(std::lround(fraction * nv));
  const double min_cos = std::cos(options.max_normal_change_degrees * M_PI / 180.0);

  // Would collapsing v0 into v1 keep every remaining triangle around v0 valid?
  const auto geometry_ok = [&](OMesh::VertexHandle v0, OMesh::VertexHandle v1) {
    const Vec3 p1 = to_vec3(om.point(v1));
    for (const OMesh::FaceHandle f : om.vf_range(v0)) {
      Vec3 p[3], q[3];
      bool has_v1 = false;
      int k = 0;
      for (const OMesh::VertexHandle v : om.fv_range(f)) {
        p[k] = to_vec3(om.point(v));
        q[k] = v == v0 ? p1 : p[k];
        has_v1 = has_v1 || v == v1;
        ++k;
      }
      if (has_v1) continue;  // one of the two triangles that disappear
      const Vec3 n_old = (p[1] - p[0]).cross(p[2] - p[0]), n_new = (q[1] - q[0]).cross(q[2] - q[0]);
      if (is_degenerate(q[0], q[1], q[2])) return false;
      if (n_old.dot(n_new) < min_cos * n_old.norm() * n_new.norm()) return false;
      const double quality = triangle_quality(q[0], q[1], q[2]);
      if (quality < std::min(options.min_quality, triangle_quality(p[0], p[1], p[2]))) return false;
    }
    return true;
  };

  // A seeded random order of halfedges; later passes retry what an earlier one rejected.
  std::vector<std::pair<std::uint64_t, int>> order;
  order.reserve(om.n_halfedges());
  for (const OMesh::HalfedgeHandle h : om.halfedges())
    order.emplace_back(rng.key(static_cast<std::uint64_t>(h.idx())), h.idx());
  std::sort(order.begin(), order.end());

  int removed = 0;
  for (bool progress = true; removed < target && progress;) {
    progress = false;
    for (const auto& entry : order) {
      if (removed >= target) break;
      const OMesh::HalfedgeHandle h(entry.second);
      if (om.status(om.edge_handle(h)).deleted()) continue;
      const OMesh::VertexHandle v0 = om.from_vertex_handle(h), v1 = om.to_vertex_handle(h);
      if (keep[static_cast<std::size_t>(v0.idx())] || om.is_boundary(v0) || om.is_boundary(v1)) continue;
      if (!om.is_collapse_ok(h) || !geometry_ok(v0, v1)) continue;
      om.collapse(h);
      ++removed;
      progress = true;
    }
  }

  // Surviving vertices in input order, with their exact input positions.
  Retessellation out;
  std::vector<int> new_index(static_cast<std::size_t>(nv), -1);
  for (int v = 0; v < nv; ++v) {
    if (om.status(OMesh::VertexHandle(v)).deleted()) continue;
    new_index[static_cast<std::size_t>(v)] = static_cast<int>(out.to_original.size());
    out.to_original.push_back(v);
    out.mesh.positions.push_back(mesh.positions[static_cast<std::size_t>(v)]);
  }
  for (const OMesh::FaceHandle f : om.faces()) {  // skips deleted faces
    Tri t{};
    int k = 0;
    for (const OMesh::VertexHandle v : om.fv_range(f)) t[k++] = new_index[static_cast<std::size_t>(v.idx())];
    out.mesh.triangles.push_back(t);
  }
  out.changed = removed;
  validate_mesh(out.mesh);
  return out;
}

}  // namespace mcon::tools
