// Perturbations of a host mesh for the evaluations (issue "meshes from anywhere"): another density
// (decimated or subdivided), Gaussian noise, and every triangle's winding reversed, so the
// benchmarks can measure what a user's scan, sculpt or export does to retrieval and mapping.
// Everything is a pure function of (mesh, perturbation, seed).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace mcon::tools {

struct MeshPerturbation {
  // Standard deviation of an isotropic Gaussian displacement of every vertex (per coordinate), as a
  // multiple of the mean edge length of the mesh at its new density; 0 = none.
  double noise = 0;
  // Reverse every triangle (corners 1 and 2 swapped), as an exporter with the other convention.
  bool flip_winding = false;
  // Vertex count of the result / of the input: < 1 decimates (seeded halfedge collapses), > 1
  // subdivides (1-to-4 midpoint splits, the surface unchanged, then decimated to the exact ratio).
  double density = 1;

  bool active() const { return noise != 0 || flip_winding || density != 1; }
  // "clean" or e.g. "density 4, noise 0.5, flip-winding" (for logs and JSON).
  std::string describe() const;
};

// The one-line usage text of the three options, for a command's --help.
extern const char* const kMeshPerturbationUsage;

// INVALID_ARGUMENT unless noise is finite in [0, 10] and density in [0.05, 16].
void check_perturbation(const MeshPerturbation& perturbation);

struct PerturbedMesh {
  TriMesh mesh;
  // Per vertex: the input vertex it is (same position before the noise), or -1 for a vertex made
  // by subdivision.
  std::vector<int> to_original;
  int vertices_before = 0;
  int reoriented_triangles = 0;  // set by user_mesh: triangles orient_and_validate turned
};

// Density first, then noise, then the winding. `keep`: input vertices that must survive a
// decimation (a patch center). The input must be a valid mesh; the result is not re-validated
// (the caller's product path, orient_and_validate, does that).
PerturbedMesh perturb_mesh(const TriMesh& mesh, const MeshPerturbation& perturbation, std::uint64_t seed,
                           const std::vector<int>& keep = {});

// The mesh as a user hands it to the product: perturb_mesh, then oriented and validated as
// mcon_mesh_create does (mesh/orientation.h); to_original survives both steps.
PerturbedMesh user_mesh(const TriMesh& mesh, const MeshPerturbation& perturbation, std::uint64_t seed,
                        const std::vector<int>& keep = {});

// The result's vertex that is input vertex `original`, or -1 if it did not survive.
int perturbed_vertex(const PerturbedMesh& perturbed, int original);

}  // namespace mcon::tools
