// Timing of the per-patch descriptor and parametrization work at ~10k vertices (the size of a
// large patch): CURV9 (edge tensors once, three heat smoothings), the sigma = 0.1 mean curvature,
// and the mean-value disk parametrization. Prints one JSON object; median of several runs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "curvature_descriptors.h"
#include "disk_parametrization.h"
#include "mesh_topology.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

double median_seconds(const std::function<void()>& run, int repeats) {
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    run();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds[seconds.size() / 2];
}

}  // namespace

int main() {
  const int repeats = 5;
  const TriMesh sphere = test_meshes::make_icosphere(5);
  const TriMesh patch = test_meshes::make_bumpy_grid(101);  // 10,201 vertices, open
  const std::vector<int> loop = build_topology(patch).boundary_loops.at(0);

  volatile double sink = 0;
  const double curv9_sphere = median_seconds([&] { sink = sink + curv9_descriptor(sphere)(0, 0); }, repeats);
  const double curv9_patch = median_seconds([&] { sink = sink + curv9_descriptor(patch)(0, 0); }, repeats);
  const double mean_patch = median_seconds([&] { sink = sink + mean_curvature_descriptor(patch)[0]; }, repeats);
  const double param_patch = median_seconds([&] { sink = sink + disk_parametrization(patch, loop)[0].x(); }, repeats);

  std::printf(
      "{\"bench\": \"curvature\", \"repeats\": %d,\n"
      " \"curv9_icosphere5\": {\"vertices\": %d, \"seconds\": %.4f},\n"
      " \"curv9_bumpy_grid\": {\"vertices\": %d, \"seconds\": %.4f, \"target_seconds\": 1.0},\n"
      " \"mean_curvature_bumpy_grid\": {\"vertices\": %d, \"seconds\": %.4f},\n"
      " \"disk_parametrization_bumpy_grid\": {\"vertices\": %d, \"seconds\": %.4f}}\n",
      repeats, sphere.num_vertices(), curv9_sphere, patch.num_vertices(), curv9_patch, patch.num_vertices(), mean_patch,
      patch.num_vertices(), param_patch);
  return curv9_patch < 1.0 ? 0 : 1;
}
