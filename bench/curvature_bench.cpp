// Timing of the per-patch descriptor and parametrization work at ~10k vertices (the size of a
// large patch): CURV9 (edge tensors once, three heat smoothings), the sigma = 0.1 mean curvature,
// and the mean-value disk parametrization. Prints one JSON object (median wall and CPU seconds of
// several runs); exits 1 if CURV9 on the open 10k patch misses its 1 s target.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "descriptors/curvature_descriptors.h"
#include "patch/disk_parametrization.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

struct Timing {
  double wall = 0;  // median wall-clock seconds
  double cpu = 0;   // median process CPU seconds (less sensitive to a busy machine)
};

Timing median_seconds(const std::function<void()>& run, int repeats) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    run();
    cpu.push_back(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[wall.size() / 2], cpu[cpu.size() / 2]};
}

std::string entry(const char* name, int vertices, const Timing& t, const char* extra = "") {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "\"%s\": {\"vertices\": %d, \"seconds\": %.4f, \"cpu_seconds\": %.4f%s}", name,
                vertices, t.wall, t.cpu, extra);
  return buffer;
}

}  // namespace

int main() {
  const int repeats = 5;
  const TriMesh sphere = test_meshes::make_icosphere(5);
  const TriMesh patch = test_meshes::make_bumpy_grid(101);  // 10,201 vertices, open
  const std::vector<int> loop = build_topology(patch).boundary_loops.at(0);

  volatile double sink = 0;
  const Timing curv9_sphere = median_seconds([&] { sink = sink + curv9_descriptor(sphere)(0, 0); }, repeats);
  const Timing curv9_patch = median_seconds([&] { sink = sink + curv9_descriptor(patch)(0, 0); }, repeats);
  const Timing mean_patch = median_seconds([&] { sink = sink + mean_curvature_descriptor(patch)[0]; }, repeats);
  const Timing param_patch = median_seconds([&] { sink = sink + disk_parametrization(patch, loop)[0].x(); }, repeats);

  std::printf("{\"bench\": \"curvature\", \"repeats\": %d,\n %s,\n %s,\n %s,\n %s}\n", repeats,
              entry("curv9_icosphere5", sphere.num_vertices(), curv9_sphere).c_str(),
              entry("curv9_bumpy_grid", patch.num_vertices(), curv9_patch, ", \"target_seconds\": 1.0").c_str(),
              entry("mean_curvature_bumpy_grid", patch.num_vertices(), mean_patch).c_str(),
              entry("disk_parametrization_bumpy_grid", patch.num_vertices(), param_patch).c_str());
  return curv9_patch.wall < 1.0 ? 0 : 1;
}
