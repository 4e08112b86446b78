// `macrocon-eval bench`: map and heat-geodesic timings on real patches (MakeHuman people), medians over
// a few runs inside a 2-thread arena. The ~10,000-vertex patches come from the body subdivided
// once (midpoint subdivision: every triangle into four), which keeps the shape and the vertex
// numbering of the original vertices, so the bench centers stay valid.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "command/args.h"
#include "common/bench_spec.h"
#include "json/json_file.h"
#include "common/makehuman_people.h"
#include "common/patch_instances.h"
#include "patch/geodesic_disk_patch.h"
#include "operators/heat_geodesics.h"
#include "map/patch_map.h"

namespace mcon::cli {
namespace {

const char* kUsage =
    "usage: macrocon-eval bench --shared DIR [--runs N] [--threads T] [--seed S] [--large] [--cases a,b]\n"
    "                            [--no-plain-newton] [--full-resolution] [--json]\n"
    "Times the re-embedding map (map_patches: descriptors, rigid initialization, optimization) and heat\n"
    "geodesics on MakeHuman patches between two random people: hand and face (about 1,700 and 2,800\n"
    "vertices) on the body, and the same classes on the body subdivided once (about 6,700 and 11,000);\n"
    "--large adds the face on the body subdivided twice (about 46,000). Each map runs with the default\n"
    "inexact Newton (factorizations reused) and, side by side, with plain Newton (one factorization per\n"
    "iteration; --no-plain-newton skips it). --cases restricts to the named cases (hand_r, face,\n"
    "hand_r_subdivided, face_subdivided, face_subdivided_twice). Sources of 5,000 vertices and more run their\n"
    "first stages on a coarsened copy; --full-resolution also maps them without it, side by side. Medians\n"
    "over --runs runs (default 3) in a --threads arena (default 2). --json prints\n"
    "{\"map\": [{\"case\", \"source_vertices\", \"target_vertices\", \"seconds_median\", \"init_seconds_median\",\n"
    "\"optimization_seconds_median\", \"cpu_seconds_median\", \"iterations\", \"factorizations\",\n"
    "\"inner_iterations\" (conjugate gradients), \"stop_reason\", \"orientation_compared\", \"level_iterations\"\n"
    "(per coarse-to-fine level), \"flips\", \"chordal_eps100\" (mean distance from each source vertex's image to\n"
    "the target vertex of the same host vertex, over sqrt(target area), x 100), \"coarse_vertices\",\n"
    "\"coarse_stages\", \"coarse_folds\" (untangled), \"coarse_fallback\", \"peak_rss_mib\" (the case's peak resident memory; \"peak_rss_scope\"\n"
    "\"case\", or \"process\" where the kernel cannot reset the peak), \"plain_newton_seconds_median\",\n"
    "\"plain_newton_iterations\", \"plain_newton_factorizations\", \"speedup_vs_plain_newton\",\n"
    "\"full_resolution_seconds_median\", \"full_resolution_iterations\", \"full_resolution_chordal_eps100\",\n"
    "\"full_resolution_flips\", \"speedup_vs_full_resolution\"}, ...],\n"
    "\"heat_geodesics\": [{\"vertices\", \"factor_seconds_median\", \"solve_seconds_median\"}, ...], \"threads\", \"load_average\"}.\n";

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Midpoint subdivision: each triangle into four; original vertices keep their indices.
TriMesh subdivide(const TriMesh& mesh) {
  TriMesh out;
  out.positions = mesh.positions;
  std::map<std::pair<int, int>, int> mid;
  auto midpoint = [&](int a, int b) {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    const auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    out.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
    const int id = static_cast<int>(out.positions.size()) - 1;
    mid.emplace(key, id);
    return id;
  };
  for (const Tri& t : mesh.triangles) {
    const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

// Peak resident memory (VmHWM) in MiB since the last reset_peak_rss(); -1 if unknown.
double peak_rss_mib() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return -1;
  char line[256];
  double kib = -1;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmHWM: %lf kB", &kib) == 1) break;
  std::fclose(f);
  return kib < 0 ? -1 : kib / 1024.0;
}

// Resets the peak to the current resident size (Linux >= 4.0: "5" to /proc/self/clear_refs).
bool reset_peak_rss() {
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

int count_flips(const TriMesh& mesh, const std::vector<Vec2>& phi, bool reflected) {
  int n = 0;
  for (const Tri& t : mesh.triangles) {
    const Vec2 e1 = phi[t[1]] - phi[t[0]], e2 = phi[t[2]] - phi[t[0]];
    const double a = e1.x() * e2.y() - e1.y() * e2.x();
    n += (reflected ? -a : a) <= 0;
  }
  return n;
}

// The map's error on the shared connectivity of the two people: for each source vertex on a host
// vertex that the target patch also has, the distance between where the map puts it and that
// target vertex, over sqrt(target patch area), x 100 (both in the normalized patch frame), and
// the mean over those vertices. Chordal, not geodesic like eval-mapping's eps: for the
// high-resolution cases eval-mapping does not reach.
double chordal_eps100(const Patch& src, const Patch& dst, const SurfaceMap& map) {
  std::map<int, int> target_of_host;
  for (std::size_t w = 0; w < dst.host_vertex.size(); ++w)
    if (dst.host_vertex[w].v0 >= 0 && dst.host_vertex[w].v0 == dst.host_vertex[w].v1)
      target_of_host[dst.host_vertex[w].v0] = static_cast<int>(w);
  double area = 0;
  for (int t = 0; t < dst.mesh.num_triangles(); ++t) area += triangle_area(dst.mesh, t);
  double sum = 0;
  int count = 0;
  for (std::size_t v = 0; v < src.host_vertex.size(); ++v) {
    const HostPoint& h = src.host_vertex[v];
    const auto it = target_of_host.find(h.v0);
    if (h.v0 < 0 || h.v0 != h.v1 || it == target_of_host.end() || !map.source_to_target[v].valid()) continue;
    const SurfacePoint& p = map.source_to_target[v];
    const Tri& tri = dst.mesh.triangles[p.triangle];
    Vec3 x = Vec3::Zero();
    for (int k = 0; k < 3; ++k) x += p.barycentric[k] * dst.mesh.positions[tri[k]];
    sum += (x - dst.mesh.positions[it->second]).norm();
    ++count;
  }
  return count > 0 ? 100 * sum / count / std::sqrt(area) : -1;
}

// Maps src onto dst `runs` times in the arena: wall times into `total` (and the rigid
// initialization's and the optimization's), the last map into `map`.
void timed_maps(const Patch& src, const Patch& dst, const PatchMapOptions& options, int runs, tbb::task_arena& arena,
                std::vector<double>& total, std::vector<double>* init, std::vector<double>* opt,
                std::vector<double>* cpu, SurfaceMap& map) {
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    arena.execute([&] { map = map_patches(src, dst, options); });
    if (cpu) cpu->push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    total.push_back(since(t0));
    if (init) init->push_back(map.alignment_seconds);
    if (opt) opt->push_back(map.optimization_seconds);
  }
}

// Medians of one map case: the default map, then (unless skipped) plain Newton side by side, and
// (if asked) the map without the coarse source stages.
tools::Json map_case_row(const std::string& case_name, const Patch& src, const Patch& dst, int runs,
                         bool plain_newton, bool full_resolution, tbb::task_arena& arena, bool quiet) {
  std::vector<double> total, init, opt, cpu;
  SurfaceMap map;
  PatchMapOptions map_options;
  const bool case_peak = reset_peak_rss();
  timed_maps(src, dst, map_options, runs, arena, total, &init, &opt, &cpu, map);
  const double peak = peak_rss_mib();
  PatchMapOptions plain_options = map_options;
  plain_options.map.newton.reuse_factorization = false;
  std::vector<double> plain_total;
  SurfaceMap plain;
  if (plain_newton) timed_maps(src, dst, plain_options, runs, arena, plain_total, nullptr, nullptr, nullptr, plain);
  PatchMapOptions full_options = map_options;
  full_options.map.coarse_stages = 0;
  std::vector<double> full_total;
  SurfaceMap full;
  if (full_resolution && map.coarse_vertices > 0)
    timed_maps(src, dst, full_options, runs, arena, full_total, nullptr, nullptr, nullptr, full);
  tools::Json row = tools::Json::object();
  row.set("case", case_name);
  row.set("source_vertices", src.mesh.num_vertices());
  row.set("target_vertices", dst.mesh.num_vertices());
  row.set("seconds_median", median(total));
  row.set("init_seconds_median", median(init));
  row.set("optimization_seconds_median", median(opt));
  row.set("cpu_seconds_median", median(cpu));
  row.set("iterations", map.iterations);
  row.set("factorizations", map.factorizations);
  row.set("inner_iterations", map.inner_iterations);
  row.set("stop_reason", stop_reason_name(map.stop_reason));
  row.set("orientation_compared", map.orientation_compared);
  tools::Json level_iterations = tools::Json::array();
  for (const LevelReport& lr : map.levels) level_iterations.push_back(lr.iterations);
  row.set("level_iterations", level_iterations);
  row.set("flips", count_flips(src.mesh, map.phi, map.reflected));
  row.set("chordal_eps100", chordal_eps100(src, dst, map));
  row.set("coarse_vertices", map.coarse_vertices);
  row.set("coarse_stages", map.coarse_stages);
  row.set("coarse_folds", map.coarse_folds);
  row.set("coarse_fallback", map.coarse_fallback);
  if (!full_total.empty()) {
    row.set("full_resolution_seconds_median", median(full_total));
    row.set("full_resolution_iterations", full.iterations);
    row.set("full_resolution_chordal_eps100", chordal_eps100(src, dst, full));
    row.set("full_resolution_flips", count_flips(src.mesh, full.phi, full.reflected));
    row.set("speedup_vs_full_resolution", median(full_total) / median(total));
  }
  row.set("peak_rss_mib", peak);
  row.set("peak_rss_scope", case_peak ? "case" : "process");
  if (!plain_total.empty()) {
    row.set("plain_newton_seconds_median", median(plain_total));
    row.set("plain_newton_iterations", plain.iterations);
    row.set("plain_newton_factorizations", plain.factorizations);
    row.set("speedup_vs_plain_newton", median(plain_total) / median(total));
  }
  if (!quiet) {
    std::fprintf(stderr, "map %s: %d -> %d vertices, %.3f s (init %.3f s), %d iterations, %d factorizations, peak %.0f MiB",
                 case_name.c_str(), src.mesh.num_vertices(), dst.mesh.num_vertices(), median(total), median(init),
                 map.iterations, map.factorizations, peak);
    if (!plain_total.empty())
      std::fprintf(stderr, "; plain Newton %.3f s, %d factorizations", median(plain_total), plain.factorizations);
    std::fprintf(stderr, "\n");
  }
  return row;
}

// Heat geodesics on the target patch: factorization and 5 solves per run.
tools::Json heat_row(const Patch& dst, int runs, tbb::task_arena& arena) {
  std::vector<double> factor, solve;
  for (int r = 0; r < runs; ++r) {
    arena.execute([&] {
      const auto t0 = std::chrono::steady_clock::now();
      const HeatGeodesics heat(dst.mesh);
      factor.push_back(since(t0));
      for (int k = 0; k < 5; ++k) {
        const auto t1 = std::chrono::steady_clock::now();
        const Eigen::VectorXd d = heat.from_vertices({(k * 7919) % dst.mesh.num_vertices()});
        solve.push_back(since(t1));
        require(d.allFinite(), MCON_ERROR_NUMERICAL, "bench: non-finite geodesic distance");
      }
    });
  }
  tools::Json h = tools::Json::object();
  h.set("vertices", dst.mesh.num_vertices());
  h.set("factor_seconds_median", median(factor));
  h.set("solve_seconds_median", median(solve));
  return h;
}

int run_bench(const Args& args) {
  static const OptionHelp help{
      {"runs", "runs per case; medians are reported (default 3)"},
      {"threads", "worker threads (TBB arena, default 2)"},
      {"seed", "seed of the two people (default 1)"},
      {"cases", "only these cases (hand_r, face, hand_r_subdivided, face_subdivided, face_subdivided_twice)"},
      {"large", "add the face on the body subdivided twice (about 46,000 vertices)"},
      {"no-plain-newton", "skip the side-by-side plain Newton runs"},
      {"full-resolution", "also map without the coarse source stages, side by side (where the default uses them)"},
  };
  const ArgParser p(args, {"shared", "runs", "threads", "seed", "cases"}, {"json", "large", "no-plain-newton", "full-resolution"}, kUsage,
                    help);
  const std::string shared = p.required("shared");
  const int runs = static_cast<int>(p.integer("runs", 3));
  const int threads = static_cast<int>(p.integer("threads", 2));
  const long seed = p.integer("seed", 1);
  require(runs >= 1 && runs <= 100 && threads >= 1 && threads <= 256 && seed >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "--runs must be in [1, 100], --threads in [1, 256], --seed >= 0");
  const tools::BenchModelData bench = tools::read_bench_model(shared, "makehuman");
  const tools::MakeHumanPeople people(shared);
  const TriMesh a = people.person(static_cast<std::uint64_t>(seed), 0);
  const TriMesh b = people.person(static_cast<std::uint64_t>(seed), 1);
  const TriMesh a2 = subdivide(a), b2 = subdivide(b);
  const std::vector<std::string> cases = p.has("cases") ? split_names(p.get("cases")) : std::vector<std::string>{};
  const bool large = p.flag("large") || std::find(cases.begin(), cases.end(), "face_subdivided_twice") != cases.end();
  const TriMesh a4 = large ? subdivide(a2) : TriMesh{}, b4 = large ? subdivide(b2) : TriMesh{};
  tbb::task_arena arena(threads);

  tools::Json map_rows = tools::Json::array(), heat_rows = tools::Json::array();
  for (const int fine : {0, 1, 2}) {
    if (fine == 2 && !large) break;
    for (const char* name : {"hand_r", "face"}) {
      if (fine == 2 && std::string(name) != "face") continue;
      const std::string case_name = std::string(name) + (fine == 1 ? "_subdivided" : fine == 2 ? "_subdivided_twice" : "");
      if (!cases.empty() && std::find(cases.begin(), cases.end(), case_name) == cases.end()) continue;
      const tools::BenchClass& cls = bench.spec.find(name);
      const std::vector<int>& verts = bench.patches.find(name).vertices;
      auto cut = [&](const TriMesh& coarse, const TriMesh& host) {
        const tools::InstancePatch ip = tools::instance_patch(cls, verts, people.base().mesh, coarse);
        PatchOptions po;
        po.center.vertex = cls.center_vertex;
        po.radius = ip.radius;
        po.fill_holes = cls.fill_holes;
        return extract_geodesic_disk(host, po);
      };
      const Patch src = cut(a, fine == 0 ? a : fine == 1 ? a2 : a4), dst = cut(b, fine == 0 ? b : fine == 1 ? b2 : b4);
      map_rows.push_back(map_case_row(case_name, src, dst, runs, !p.flag("no-plain-newton"), p.flag("full-resolution"),
                                      arena, p.flag("json")));
      heat_rows.push_back(heat_row(dst, runs, arena));
    }
  }
  tools::Json out = tools::Json::object();
  out.set("map", map_rows);
  out.set("heat_geodesics", heat_rows);
  out.set("threads", threads);
  out.set("runs", runs);
  double load[1] = {0};
  if (getloadavg(load, 1) == 1) out.set("load_average", load[0]);
  std::printf("%s\n", tools::write_json(out, p.flag("json")).c_str());
  return 0;
}

const Registration registration{"bench", "map and heat-geodesic timings on real patches (JSON)", run_bench};

}  // namespace
}  // namespace mcon::cli
