#include "common/ict_faces.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>

#include "common/bench_random.h"
#include "base/error.h"

namespace mcon::tools {

namespace {

io::LoadedMesh read_surface(const std::string& path) {
  io::MeshFileOptions options;
  options.face_end = kIctSurfaceFaces;
  io::LoadedMesh m = io::read_mesh(path, options);
  bool identity = m.mesh.num_vertices() == kIctSurfaceVertices;
  for (int v = 0; identity && v < m.mesh.num_vertices(); ++v) identity = m.mesh_to_file[v] == v;
  require(identity, MCON_ERROR_INVALID_ARGUMENT,
          "'" + path + "': the surface is not vertices 0.." + std::to_string(kIctSurfaceVertices - 1));
  return m;
}

}  // namespace

IctFaces::IctFaces(const std::string& shared_dir) {
  const std::string dir = shared_dir + "/meshes/ict-facekit/";
  neutral_ = read_surface(dir + "generic_neutral_mesh.obj.gz");
  deltas_.resize(kIctIdentities);
  // The 20 files are independent: read them in parallel (the result does not depend on the order).
  tbb::parallel_for(0, kIctIdentities, [&](int k) {
    char name[32];
    std::snprintf(name, sizeof(name), "identity%03d.obj.gz", k);
    const io::LoadedMesh identity = read_surface(dir + name);
    require(identity.mesh.triangles == neutral_.mesh.triangles, MCON_ERROR_INVALID_ARGUMENT,
            std::string("'") + dir + name + "' has other triangles than the neutral mesh");
    std::vector<Vec3>& delta = deltas_[k];
    delta.resize(identity.mesh.positions.size());
    for (std::size_t v = 0; v < delta.size(); ++v) delta[v] = identity.mesh.positions[v] - neutral_.mesh.positions[v];
  });
}

IctCoefficients IctFaces::coefficients(std::uint64_t seed, std::uint64_t index) {
  const BenchRng rng(seed, index);
  IctCoefficients c{};
  for (int k = 0; k < kIctIdentities; ++k)
    c[k] = std::clamp(rng.normal(static_cast<std::uint64_t>(k)), -kIctCoefficientClip, kIctCoefficientClip);
  return c;
}

TriMesh IctFaces::build(const IctCoefficients& c) const {
  for (int k = 0; k < kIctIdentities; ++k)
    require(std::isfinite(c[k]), MCON_ERROR_NON_FINITE, "ICT coefficient " + std::to_string(k) + " is not finite");
  TriMesh mesh = neutral_.mesh;
  for (int k = 0; k < kIctIdentities; ++k) {
    if (c[k] == 0.0) continue;
    const std::vector<Vec3>& delta = deltas_[k];
    for (std::size_t v = 0; v < delta.size(); ++v) mesh.positions[v] += c[k] * delta[v];
  }
  return mesh;
}

}  // namespace mcon::tools
