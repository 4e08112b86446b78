// Re-embedding speed on synthetic disks (tests/synthetic_maps.h): median seconds of the whole map
// and of its rigid initialization, iterations, and the error against the known answer, at about
// 2,000 and 10,000 source vertices, inside a 2-thread arena. Prints one JSON object; besides wall
// seconds it reports the process CPU seconds (all threads), which stay meaningful on a shared,
// overloaded machine where wall time does not.
// Usage: map_bench [runs_2k=5] [runs_10k=3] [threads=2]
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "map/injective_step.h"
#include "map/surface_map.h"
#include "synthetic_maps.h"

using namespace mcon;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

std::string run_case(const char* name, int source_rings, int target_rings, int runs, tbb::task_arena& arena) {
  synthetic::GroundTruth truth;
  truth.angle = 70.0 * 3.141592653589793 / 180.0;
  truth.warp = 0.05;
  truth.translation = Vec2(0.05, -0.03);
  const synthetic::Problem pr = synthetic::make_problem(source_rings, target_rings, truth, 2);
  std::vector<double> total, init, opt, cpu;
  SurfaceMap map;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    arena.execute([&] {
      map = compute_surface_map({pr.source, pr.source_uv, pr.source_levels}, {pr.target, pr.target_uv, pr.target_levels});
    });
    cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    total.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    init.push_back(map.alignment_seconds);
    opt.push_back(map.optimization_seconds);
  }
  std::string levels;
  for (std::size_t l = 0; l < map.levels.size(); ++l) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s{\"iterations\": %d, \"stop\": \"%s\"}", l ? ", " : "", map.levels[l].iterations,
                  stop_reason_name(map.levels[l].stop_reason));
    levels += buf;
  }
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "\"%s\": {\"source_vertices\": %d, \"target_vertices\": %d, \"runs\": %d, \"seconds_median\": %.4f, \"cpu_seconds_median\": %.4f, "
                "\"init_seconds_median\": %.4f, \"optimization_seconds_median\": %.4f, \"iterations\": %d, "
                "\"levels\": [%s], \"mean_error\": %.5f, \"overlap_ratio\": %.4f, \"matching_score\": %.4f, "
                "\"initial_score\": %.4f, \"flips\": %d}",
                name, pr.source.num_vertices(), pr.target.num_vertices(), runs, median(total), median(cpu), median(init), median(opt),
                map.iterations, levels.c_str(), synthetic::mean_error(pr, map.phi), map.overlap_ratio,
                map.matching_score, map.alignment.score,
                [&] {
                  Eigen::VectorXd x(2 * map.phi.size());
                  for (std::size_t v = 0; v < map.phi.size(); ++v) x.segment<2>(2 * v) = map.phi[v];
                  return count_inverted(pr.source.triangles, x);
                }());
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs_2k = argc > 1 ? std::atoi(argv[1]) : 5;
  const int runs_10k = argc > 2 ? std::atoi(argv[2]) : 3;
  const int threads = argc > 3 ? std::atoi(argv[3]) : 2;
  tbb::task_arena arena(threads);
  std::string out = "{\"threads\": " + std::to_string(threads);
  if (runs_2k > 0) out += ", " + run_case("disk_2k", 26, 24, runs_2k, arena);
  if (runs_10k > 0) out += ", " + run_case("disk_10k", 57, 53, runs_10k, arena);
  double load[1] = {0};
  if (getloadavg(load, 1) == 1) out += ", \"load_average\": " + std::to_string(load[0]);
  out += "}";
  std::printf("%s\n", out.c_str());
  return 0;
}
