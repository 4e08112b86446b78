// Heat-method geodesics at ~10k vertices (docs/design.md §2: 0.08 s factorization, 3 ms per
// source): constructor time (median of 5), per-source query time (median of 20 sources) and the
// mean relative error against the analytic distance (vertices within 2 mean edge lengths of the
// source excluded). The MakeHuman body (13380 vertices) has no analytic distance: its reference
// is a Steiner-point shortest path (checked against the sphere's great circles in the output). Wall-clock and process CPU seconds (all threads: the factorizations run in
// parallel) are both reported; on a shared machine the CPU time is the steadier number. Prints
// one JSON object.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <queue>
#include <string>
#include <vector>

#include "operators/heat_geodesics.h"
#include "io/mesh_io.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

struct Seconds {
  double wall = 0, cpu = 0;
};

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

Seconds time_once(const std::function<void()>& f) {
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  f();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(), process_cpu_seconds() - cpu0};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Seconds median(const std::vector<Seconds>& samples) {
  std::vector<double> wall, cpu;
  for (const Seconds& s : samples) {
    wall.push_back(s.wall);
    cpu.push_back(s.cpu);
  }
  return {median(wall), median(cpu)};
}

// Near-exact polyhedral geodesic distance from `source` to every vertex: Dijkstra on the graph
// of the vertices plus k points per edge, where all boundary points of each triangle are joined
// by straight segments (Lanthier, Maheshwari, Sack 2001). Edges are generated on the fly.
std::vector<double> steiner_distances(const TriMesh& mesh, const MeshTopology& topo, int source, int k) {
  const int n = mesh.num_vertices();
  auto position = [&](int node) -> Vec3 {
    if (node < n) return mesh.positions[node];
    const int e = (node - n) / k, i = (node - n) % k;
    const Vec3& a = mesh.positions[topo.edges[e][0]];
    const Vec3& b = mesh.positions[topo.edges[e][1]];
    return a + (b - a) * (i + 1.0) / (k + 1.0);
  };
  std::vector<double> dist(n + static_cast<std::size_t>(topo.num_edges()) * k, 1e300);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  dist[source] = 0;
  heap.emplace(0.0, source);
  std::vector<int> nodes;
  auto relax_triangle = [&](int t, int from, double d, const Vec3& p) {
    nodes.clear();
    for (int i = 0; i < 3; ++i) {
      nodes.push_back(mesh.triangles[t][i]);
      const int e = topo.triangle_edges[t][i];
      for (int j = 0; j < k; ++j) nodes.push_back(n + e * k + j);
    }
    for (int to : nodes) {
      if (to == from) continue;
      const double nd = d + (position(to) - p).norm();
      if (nd < dist[to]) {
        dist[to] = nd;
        heap.emplace(nd, to);
      }
    }
  };
  while (!heap.empty()) {
    const auto [d, node] = heap.top();
    heap.pop();
    if (d > dist[node]) continue;
    const Vec3 p = position(node);
    if (node < n) {
      for (int t : topo.vertex_triangles[node]) relax_triangle(t, node, d, p);
    } else {
      for (int t : topo.edge_triangles[(node - n) / k])
        if (t >= 0) relax_triangle(t, node, d, p);
    }
  }
  dist.resize(n);
  return dist;
}

using ExactDistance = std::function<double(int source, int vertex)>;

std::string run_case(const std::string& name, const TriMesh& mesh, const ExactDistance& exact, int num_sources,
                     const HeatGeodesicsOptions& options = {}) {
  std::vector<Seconds> factor;
  for (int k = 0; k < 5; ++k) factor.push_back(time_once([&] { HeatGeodesics g(mesh, options); }));
  const HeatGeodesics geodesics(mesh, options);

  const double h = mean_edge_length(mesh);
  std::vector<Seconds> query;
  double error_sum = 0, error_max = 0;
  const int n = mesh.num_vertices();
  for (int k = 0; k < 20; ++k) {
    const int source = static_cast<int>((static_cast<long long>(k) * 7919 + 101) % n);
    Eigen::VectorXd d;
    query.push_back(time_once([&] { d = geodesics.from_vertices({source}); }));
    if (k >= num_sources) continue;
    double sum = 0;
    int count = 0;
    for (int v = 0; v < n; ++v) {
      const double e = exact(source, v);
      if (e <= 2 * h) continue;
      const double rel = std::abs(d[v] - e) / e;
      sum += rel;
      error_max = std::max(error_max, rel);
      ++count;
    }
    error_sum += sum / count;
  }
  const Seconds f = median(factor), q = median(query);
  char buffer[768];
  std::snprintf(buffer, sizeof(buffer),
                "{\"mesh\": \"%s\", \"vertices\": %d, \"triangles\": %d, \"factorization_seconds\": %.4f, "
                "\"factorization_cpu_seconds\": %.4f, \"query_seconds\": %.5f, \"query_cpu_seconds\": %.5f, "
                "\"timed_sources\": 20, \"error_sources\": %d, \"mean_relative_error\": %.5f, "
                "\"max_relative_error\": %.4f}",
                name.c_str(), n, mesh.num_triangles(), f.wall, f.cpu, q.wall, q.cpu, num_sources,
                error_sum / num_sources, error_max);
  return buffer;
}

// Mean relative error of the Steiner reference itself on the unit icosphere (one source).
double steiner_error_on_sphere(const TriMesh& sphere, int k) {
  const MeshTopology topo = build_topology(sphere);
  const std::vector<double> d = steiner_distances(sphere, topo, 0, k);
  const double h = mean_edge_length(sphere);
  double sum = 0;
  int count = 0;
  for (int v = 0; v < sphere.num_vertices(); ++v) {
    const double e = std::acos(std::clamp(sphere.positions[0].dot(sphere.positions[v]), -1.0, 1.0));
    if (e <= 2 * h) continue;
    sum += std::abs(d[v] - e) / e;
    ++count;
  }
  return sum / count;
}

}  // namespace

int main() {
  const TriMesh sphere = test_meshes::make_icosphere(5);
  const TriMesh grid = test_meshes::make_grid(100, 1.0, 0.3);
  const std::string sphere_json = run_case(
      "icosphere5", sphere,
      [&](int s, int v) {  // great circle on the unit sphere
        return std::acos(std::clamp(sphere.positions[s].dot(sphere.positions[v]), -1.0, 1.0));
      },
      20);
  const std::string grid_json = run_case(
      "jittered_grid_100", grid,
      [&](int s, int v) { return (grid.positions[s] - grid.positions[v]).norm(); },  // convex: straight
      20);

  // MakeHuman body: the first 13378 faces (quads split a,b,c / a,c,d), shared/bench/README.md.
  constexpr int kSteinerPoints = 5;
  io::MeshFileOptions body_options;
  body_options.face_end = 13378;
  const TriMesh body = io::read_mesh(std::string(MACROCON_SHARED_DIR) + "/meshes/makehuman/base.obj.gz", body_options).mesh;
  const MeshTopology body_topology = build_topology(body);
  std::vector<std::vector<double>> reference(body.num_vertices());
  const ExactDistance body_reference = [&](int s, int v) {
    if (reference[s].empty()) reference[s] = steiner_distances(body, body_topology, s, kSteinerPoints);
    return reference[s][v];
  };
  const std::string body_json = run_case("makehuman_body", body, body_reference, 5);
  // The same with the mesh's own (extrinsic) cotan operators: its quad-split triangles are far
  // from Delaunay, which is why intrinsic Delaunay operators are the default.
  HeatGeodesicsOptions extrinsic;
  extrinsic.intrinsic_delaunay = false;
  const std::string body_extrinsic_json = run_case("makehuman_body_extrinsic_cotan", body, body_reference, 5, extrinsic);
  std::printf(
      "{\"benchmark\": \"heat_geodesics\", \"time_factor\": 1.0, \"boundary_average\": true, "
      "\"intrinsic_delaunay\": true, \"cases\": [%s, %s, %s, %s], \"body_reference\": {\"method\": "
      "\"steiner_dijkstra\", \"points_per_edge\": %d, \"its_mean_relative_error_on_icosphere5\": %.5f}}\n",
      sphere_json.c_str(), grid_json.c_str(), body_json.c_str(), body_extrinsic_json.c_str(), kSteinerPoints,
      steiner_error_on_sphere(sphere, kSteinerPoints));
  return 0;
}
