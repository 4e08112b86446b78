// Cross-field solve times (compute_cross_field) on ~10k-face meshes: guides along a line on a
// grid and a cylinder, a closed sphere with a few guides, the unconstrained smoothest field
// (inverse iteration), a boundary-aligned disk and a real face patch. Prints one JSON object.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "transfer/cross_field.h"
#include "io/mesh_io.h"
#include "test_meshes.h"

namespace {

// Median wall time and median process CPU time: the machine is often shared, and CPU time is
// the number that does not depend on how many other jobs run.
struct Timing {
  double wall_ms, cpu_ms;
};

template <typename F>
Timing median_ms(int runs, F&& f) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    f();
    cpu.push_back(1000.0 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[wall.size() / 2], cpu[cpu.size() / 2]};
}

mcon::Vec3 centroid(const mcon::TriMesh& m, int t) {
  const mcon::Tri& tri = m.triangles[t];
  return (m.positions[tri[0]] + m.positions[tri[1]] + m.positions[tri[2]]) / 3.0;
}

struct Case {
  std::string name;
  mcon::TriMesh mesh;
  std::vector<mcon::DirectionConstraint> constraints;
  mcon::CrossFieldOptions options;
};

}  // namespace

int main() {
  using mcon::Vec3;
  std::vector<Case> cases;
  {
    Case c{"grid_line", mcon::test_meshes::make_grid(72, 1.0, 0.3), {}, {}};
    for (int t = 0; t < c.mesh.num_triangles(); ++t)
      if (std::abs(centroid(c.mesh, t).y() - 0.5) < 0.01) c.constraints.push_back({t, Vec3(1, 0.2, 0), 1.0});
    cases.push_back(std::move(c));
  }
  {
    Case c{"cylinder_axis", mcon::test_meshes::make_cylinder(1.0, 3.0, 100, 51), {}, {}};
    for (int t = 0; t < c.mesh.num_triangles(); ++t) {
      const Vec3 p = centroid(c.mesh, t);
      if (std::abs(std::atan2(p.y(), p.x())) < 0.05) c.constraints.push_back({t, Vec3::UnitZ(), 1.0});
    }
    cases.push_back(std::move(c));
  }
  {
    Case c{"sphere_equator", mcon::test_meshes::make_icosphere(4), {}, {}};
    for (int t = 0; t < c.mesh.num_triangles(); ++t) {
      const Vec3 p = centroid(c.mesh, t);
      if (std::abs(p.z()) < 0.02) c.constraints.push_back({t, Vec3::UnitZ().cross(p), 1.0});
    }
    cases.push_back(std::move(c));
  }
  cases.push_back({"sphere_smoothest", mcon::test_meshes::make_icosphere(4), {}, {}});
  cases.push_back({"grid_smoothest", mcon::test_meshes::make_grid(72, 1.0, 0.3), {}, {}});
  {
    Case c{"disk_boundary", mcon::test_meshes::make_disk(41), {}, {}};
    c.options.align_to_boundary = true;
    cases.push_back(std::move(c));
  }
  {
    // A real target patch: the ICT face's narrow face area (quads split, ~13k triangles, holes at
    // the eyes and mouth), a vertical guide down the middle and boundary alignment.
    mcon::io::MeshFileOptions file_options;
    file_options.face_end = 6705;
    Case c{"ict_face_area", mcon::io::read_mesh(std::string(MACROCON_SHARED_DIR) +
                                                    "/meshes/ict-facekit/generic_neutral_mesh.obj.gz",
                                                file_options).mesh,
           {}, {}};
    c.options.align_to_boundary = true;
    for (int t = 0; t < c.mesh.num_triangles(); ++t)
      if (std::abs(centroid(c.mesh, t).x()) < 0.3) c.constraints.push_back({t, Vec3::UnitY(), 1.0});
    cases.push_back(std::move(c));
  }
  const int runs = 7;
  std::printf("{\n  \"benchmark\": \"cross_field\",\n  \"runs\": %d,\n  \"cases\": [\n", runs);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    mcon::CrossField field;
    const Timing ms = median_ms(runs, [&] { field = mcon::compute_cross_field(c.mesh, c.constraints, c.options); });
    double mean_confidence = 0;
    for (double v : field.confidence) mean_confidence += v;
    mean_confidence /= static_cast<double>(field.confidence.size());
    std::printf("%s    {\"case\": \"%s\", \"triangles\": %d, \"constraints\": %zu, \"wall_ms\": %.2f, \"cpu_ms\": %.2f, "
                "\"mean_confidence\": %.4f}",
                i ? ",\n" : "", c.name.c_str(), c.mesh.num_triangles(), c.constraints.size(), ms.wall_ms, ms.cpu_ms,
                mean_confidence);
  }
  std::printf("\n  ]\n}\n");
  return 0;
}
