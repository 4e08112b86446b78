// Random ICT-FaceKit faces for the benchmark: face = neutral + sum_k c_k (identity_k - neutral),
// k = 0..19, c_k ~ N(0, 1) clipped to +-2.5 (shared/bench/README.md "Making random instances"; the
// clip keeps the first components from distorting the face). Every face has the neutral mesh's
// vertices and triangles, so the ground truth between two faces is the identity on vertex indices.
// Face i of seed s is a pure function of (s, i) (bench_random.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "mesh/mesh.h"

namespace mcon::tools {

// The surface: faces 0..14033 of the OBJ (face, head and neck, eye and mouth socket linings) and
// their vertices 0..14061; one boundary loop at the neck.
constexpr int kIctSurfaceFaces = 14034;
constexpr int kIctSurfaceVertices = 14062;
constexpr int kIctIdentities = 20;
constexpr double kIctCoefficientClip = 2.5;

using IctCoefficients = std::array<double, kIctIdentities>;

class IctFaces {
 public:
  // Reads <shared_dir>/meshes/ict-facekit/generic_neutral_mesh.obj.gz and identity000..019 (surface
  // only; the identities must have the neutral mesh's triangles).
  explicit IctFaces(const std::string& shared_dir);

  const io::LoadedMesh& neutral() const { return neutral_; }

  static IctCoefficients coefficients(std::uint64_t seed, std::uint64_t index);
  // The neutral mesh's (validated) connectivity with the combined positions; not re-validated.
  TriMesh build(const IctCoefficients& c) const;
  TriMesh face(std::uint64_t seed, std::uint64_t index) const { return build(coefficients(seed, index)); }

 private:
  io::LoadedMesh neutral_;
  std::vector<std::vector<Vec3>> deltas_;  // identity_k - neutral, per vertex
};

}  // namespace mcon::tools
