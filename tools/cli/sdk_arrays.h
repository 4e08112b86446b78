// Between the file layer's meshes (what io::read_mesh gives and io::write_* take) and the public
// API's flat arrays: the product commands do every computation through macrocon.hpp, and only
// read and write files through the io layer.
#pragma once

#include <cstdint>
#include <vector>

#include "io/mesh_io.h"
#include "macrocon/macrocon.hpp"

namespace mcon::cli {

// A mesh's positions (x0 y0 z0 x1 ...) and triangles (a0 b0 c0 a1 ...) as the API's flat arrays.
inline std::vector<double> flat_positions(const TriMesh& mesh) {
  std::vector<double> xyz;
  xyz.reserve(3 * mesh.positions.size());
  for (const Vec3& q : mesh.positions) xyz.insert(xyz.end(), {q.x(), q.y(), q.z()});
  return xyz;
}
inline std::vector<std::uint32_t> flat_triangles(const TriMesh& mesh) {
  std::vector<std::uint32_t> triangles;
  triangles.reserve(3 * mesh.triangles.size());
  for (const Tri& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) triangles.push_back(static_cast<std::uint32_t>(t[k]));
  return triangles;
}

// The loaded file as an SDK mesh (already oriented and validated by read_mesh; the SDK's own
// orientation step then changes nothing).
inline macrocon::Mesh sdk_mesh(const macrocon::Context& context, const TriMesh& mesh) {
  return macrocon::Mesh::from_arrays(context, flat_positions(mesh), flat_triangles(mesh));
}

// A patch's triangles at `scale * p + origin` (1 and 0: its normalized positions; radius and
// center: host units), for the file writers.
inline TriMesh file_mesh(const macrocon::Patch& patch, double scale = 1.0, const double* origin = nullptr) {
  const std::vector<double> p = patch.positions();
  const std::vector<std::uint32_t> t = patch.triangles();
  TriMesh mesh;
  mesh.positions.reserve(p.size() / 3);
  for (std::size_t v = 0; 3 * v < p.size(); ++v)
    mesh.positions.emplace_back(scale * p[3 * v] + (origin ? origin[0] : 0.0),
                                scale * p[3 * v + 1] + (origin ? origin[1] : 0.0),
                                scale * p[3 * v + 2] + (origin ? origin[2] : 0.0));
  for (std::size_t i = 0; 3 * i < t.size(); ++i)
    mesh.triangles.push_back({static_cast<int>(t[3 * i]), static_cast<int>(t[3 * i + 1]), static_cast<int>(t[3 * i + 2])});
  return mesh;
}

}  // namespace mcon::cli
