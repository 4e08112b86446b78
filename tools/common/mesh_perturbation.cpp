#include "common/mesh_perturbation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "base/counter_rng.h"
#include "base/error.h"
#include "common/retessellate.h"
#include "mesh/edge_key.h"
#include "mesh/orientation.h"

namespace mcon::tools {
namespace {

// Streams of the perturbation's random draws (distinct per step).
constexpr std::uint64_t kDecimationStream = 0xDE5171u;
constexpr std::uint64_t kNoiseStream = 0x0015E0000u;

// One 1-to-4 midpoint split: the input vertices keep their numbers, edge midpoints follow.
TriMesh subdivide_midpoints(const TriMesh& mesh) {
  TriMesh out;
  out.positions = mesh.positions;
  std::unordered_map<std::uint64_t, int> midpoint;
  midpoint.reserve(mesh.triangles.size() * 2);
  const auto mid = [&](int a, int b) {
    const auto [it, inserted] = midpoint.emplace(edge_key(a, b), out.num_vertices());
    if (inserted) out.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
    return it->second;
  };
  out.triangles.reserve(mesh.triangles.size() * 4);
  for (const Tri& t : mesh.triangles) {
    const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

// Decimates `p` to `target` vertices (if that removes at least 0.5 %), keeping `keep` (numbers of
// the input) and composing to_original.
void decimate_to(PerturbedMesh& p, int target, std::uint64_t seed, const std::vector<int>& keep) {
  const double fraction = 1.0 - static_cast<double>(target) / p.mesh.num_vertices();
  if (fraction < 0.005) return;
  DecimationOptions dec;
  dec.min_fraction = dec.max_fraction = std::min(fraction, 0.99);
  for (const int k : keep) {
    const int v = perturbed_vertex(p, k);
    if (v >= 0) dec.keep.push_back(v);
  }
  Retessellation r = decimate(p.mesh, seed, dec);
  std::vector<int> to_original(r.to_original.size());
  for (std::size_t v = 0; v < r.to_original.size(); ++v) to_original[v] = p.to_original[r.to_original[v]];
  p.mesh = std::move(r.mesh);
  p.to_original = std::move(to_original);
}

void resample(PerturbedMesh& p, double density, std::uint64_t seed, const std::vector<int>& keep) {
  const int target = static_cast<int>(std::lround(density * p.vertices_before));
  // Within 1 % is close enough: a 1-to-4 split of a closed mesh gives 4 V - 6, not 4 V.
  while (p.mesh.num_vertices() < 0.99 * target) {
    p.mesh = subdivide_midpoints(p.mesh);
    p.to_original.resize(p.mesh.positions.size(), -1);
  }
  decimate_to(p, target, counter_hash(seed, kDecimationStream, 0), keep);
}

void add_noise(TriMesh& mesh, double noise, std::uint64_t seed) {
  const double sigma = noise * mean_edge_length(mesh);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    CounterRng rng(counter_hash(seed, kNoiseStream, 0), static_cast<std::uint64_t>(v));
    const double dx = rng.normal(), dy = rng.normal(), dz = rng.normal();
    mesh.positions[v] += sigma * Vec3(dx, dy, dz);
  }
}

}  // namespace

const char* const kMeshPerturbationUsage =
    "--noise F (Gaussian, std F x mean edge length), --flip-winding, --density S (S x the vertex count)";

std::string MeshPerturbation::describe() const {
  if (!active()) return "clean";
  std::string s;
  char buf[64];
  if (density != 1) {
    std::snprintf(buf, sizeof buf, "density %g", density);
    s += buf;
  }
  if (noise != 0) {
    std::snprintf(buf, sizeof buf, "%snoise %g", s.empty() ? "" : ", ", noise);
    s += buf;
  }
  if (flip_winding) s += s.empty() ? "flip-winding" : ", flip-winding";
  return s;
}

void check_perturbation(const MeshPerturbation& p) {
  require(std::isfinite(p.noise) && p.noise >= 0 && p.noise <= 10, MCON_ERROR_INVALID_ARGUMENT,
          "--noise must be in [0, 10] (a multiple of the mean edge length)");
  require(std::isfinite(p.density) && p.density >= 0.05 && p.density <= 16, MCON_ERROR_INVALID_ARGUMENT,
          "--density must be in [0.05, 16] (a multiple of the vertex count)");
}

PerturbedMesh perturb_mesh(const TriMesh& mesh, const MeshPerturbation& perturbation, std::uint64_t seed,
                           const std::vector<int>& keep) {
  check_perturbation(perturbation);
  PerturbedMesh p;
  p.mesh = mesh;
  p.vertices_before = mesh.num_vertices();
  p.to_original.resize(mesh.positions.size());
  for (int v = 0; v < mesh.num_vertices(); ++v) p.to_original[v] = v;
  if (perturbation.density != 1) resample(p, perturbation.density, seed, keep);
  if (perturbation.noise != 0) add_noise(p.mesh, perturbation.noise, seed);
  if (perturbation.flip_winding)
    for (Tri& t : p.mesh.triangles) std::swap(t[1], t[2]);
  return p;
}

PerturbedMesh user_mesh(const TriMesh& mesh, const MeshPerturbation& perturbation, std::uint64_t seed,
                        const std::vector<int>& keep) {
  PerturbedMesh p = perturb_mesh(mesh, perturbation, seed, keep);
  p.reoriented_triangles = orient_and_validate(p.mesh).reoriented_triangles;
  return p;
}

int perturbed_vertex(const PerturbedMesh& perturbed, int original) {
  const auto it = std::find(perturbed.to_original.begin(), perturbed.to_original.end(), original);
  return it == perturbed.to_original.end() ? -1 : static_cast<int>(it - perturbed.to_original.begin());
}

}  // namespace mcon::tools
