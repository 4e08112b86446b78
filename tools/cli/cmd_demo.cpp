// `macrocon demo`: the main job on the bundled sample data (no ../shared needed). Cuts every
// landmark patch of the bundled MakeHuman body, computes its descriptors and parametrization,
// and writes the patches as PLY files one can open in any viewer.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "args.h"
#include "curvature_descriptors.h"
#include "geodesic_disk_patch.h"
#include "io/mesh_io.h"

namespace mcon::cli {
namespace {

struct Landmark {
  std::string name;
  long center_vertex = -1;
  double radius = 0;
};

// The bundled landmarks file is our own, with a fixed simple layout: read each class's name,
// center_vertex and radius.
std::vector<Landmark> read_landmarks(const std::string& path) {
  const std::string text = io::read_file_maybe_gz(path);
  std::vector<Landmark> out;
  const auto classes = text.find("\"classes\"");
  require(classes != std::string::npos, MCON_ERROR_IO, "'" + path + "' has no \"classes\"");
  std::size_t pos = text.find('{', classes);
  for (;;) {
    const auto q0 = text.find('"', pos + 1);
    if (q0 == std::string::npos) break;
    const auto q1 = text.find('"', q0 + 1);
    const auto body_end = text.find('}', q1);
    if (q1 == std::string::npos || body_end == std::string::npos) break;
    const std::string body = text.substr(q1, body_end - q1);
    Landmark l;
    l.name = text.substr(q0 + 1, q1 - q0 - 1);
    const auto cv = body.find("\"center_vertex\":"), rd = body.find("\"radius\":");
    require(cv != std::string::npos && rd != std::string::npos, MCON_ERROR_IO, "malformed class '" + l.name + "'");
    l.center_vertex = std::strtol(body.c_str() + cv + 16, nullptr, 10);
    l.radius = std::strtod(body.c_str() + rd + 9, nullptr);
    out.push_back(l);
    pos = body_end;
    if (text.find('"', pos) > text.find("}", pos + 1)) break;  // end of "classes"
  }
  require(!out.empty(), MCON_ERROR_IO, "'" + path + "' lists no classes");
  return out;
}

int run_demo(const Args& args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::puts("usage: macrocon demo [--data DIR] [--out DIR]\n"
              "Runs the main job on the bundled sample data and writes PLY patches to --out (default demo-out).");
    return 0;
  }
  const ArgParser p(args, {"data", "out"}, {});
  const std::string data = p.get("data", MACROCON_SAMPLE_DATA_DIR);
  const std::string out_dir = p.get("out", "demo-out");
  std::filesystem::create_directories(out_dir);

  const auto t0 = std::chrono::steady_clock::now();
  const io::LoadedMesh body = io::read_mesh(data + "/makehuman-body.obj.gz");
  std::printf("mesh: %d vertices, %d triangles (MakeHuman body, CC0)\n", body.mesh.num_vertices(),
              body.mesh.num_triangles());
  int failures = 0;
  for (const Landmark& l : read_landmarks(data + "/makehuman-landmarks.json")) {
    PatchOptions options;
    options.center.vertex = body.file_to_mesh.at(static_cast<std::size_t>(l.center_vertex));
    options.radius = l.radius;
    const auto t1 = std::chrono::steady_clock::now();
    try {
      const Patch patch = extract_geodesic_disk(body.mesh, options);
      const Eigen::MatrixXd curv9 = curv9_descriptor(patch.mesh);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      io::VertexAttribute uv{"uv", 2, {}}, mean{"mean_curvature", 1, {}}, gauss{"gaussian_curvature", 1, {}};
      for (const Vec2& q : patch.uv) uv.values.insert(uv.values.end(), {q.x(), q.y()});
      for (int v = 0; v < patch.mesh.num_vertices(); ++v) {
        mean.values.push_back(curv9(v, 7));
        gauss.values.push_back(curv9(v, 6));
      }
      io::FaceAttribute filled{"filled", {}};
      for (int ht : patch.host_triangle) filled.values.push_back(ht < 0 ? 1 : 0);
      const std::string file = out_dir + "/" + l.name + ".ply";
      io::write_ply(file, patch.mesh, {uv, mean, gauss}, {filled});
      std::printf("  %-8s r=%.2f  %5d vertices %5d triangles (%d filled)  flips %d  max geodesic %.3f  %.3f s -> %s\n",
                  l.name.c_str(), l.radius, patch.mesh.num_vertices(), patch.mesh.num_triangles(),
                  patch.filled_triangles(), patch.param_flipped_triangles, patch.max_geodesic_distance, seconds,
                  file.c_str());
      failures += patch.param_flipped_triangles != 0;
    } catch (const Error& e) {
      std::printf("  %-8s failed: %s\n", l.name.c_str(), e.what());
      ++failures;
    }
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("demo finished in %.2f s with %d failure(s)\n", total, failures);
  return failures == 0 ? 0 : 1;
}

const Registration registration{"demo", "run the main job on the bundled sample data", run_demo};

}  // namespace
}  // namespace mcon::cli
