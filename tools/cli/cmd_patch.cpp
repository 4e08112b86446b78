// `macrocon patch`: cut a geodesic disk out of a mesh file and report its topology.
#include <chrono>
#include <cstdio>
#include <string>

#include "command/args.h"
#include "descriptors/curvature_descriptors.h"
#include "patch/geodesic_disk_patch.h"
#include "io/mesh_io.h"
#include "mesh/mesh_topology.h"

namespace mcon::cli {
namespace {

const char* kUsage =
    "usage: macrocon patch --mesh FILE (--center-vertex N | --center-triangle T [--barycentric a,b,c])\n"
    "                      --radius R [--out FILE.ply] [--json] [--face-range BEGIN:END] [--group NAME]\n"
    "                      [--no-fill] [--snap F]\n"
    "Cuts the geodesic disk of radius R (mesh units) around the center, normalizes it to radius 1 and\n"
    "parametrizes it on the unit disk. Vertex and triangle numbers refer to the file (polygons before\n"
    "triangulation for --center-triangle and --face-range). --out writes the normalized patch as PLY\n"
    "with uv, mean curvature (sigma 0.1), host vertex and a per-face 'filled' flag.\n"
    MACROCON_HELP_NUMBERING;

void parse_range(const std::string& s, long& begin, long& end) {
  const auto colon = s.find(':');
  require(colon != std::string::npos, MCON_ERROR_INVALID_ARGUMENT, "--face-range expects BEGIN:END, got '" + s + "'");
  begin = static_cast<long>(ArgParser::parse_number("face-range", s.substr(0, colon)));
  end = static_cast<long>(ArgParser::parse_number("face-range", s.substr(colon + 1)));
  require(begin >= 0 && end > begin, MCON_ERROR_INVALID_ARGUMENT, "--face-range needs 0 <= BEGIN < END");
}

// The summary on stdout: one JSON object with --json, else two or three lines.
void print_summary(const Patch& patch, const MeshTopology& topo, const OrientationReport& o, double seconds,
                   bool json) {
  if (json) {
    std::printf(
        "{\"vertices\": %d, \"faces\": %d, \"filled_faces\": %d, \"boundary_loops\": %zu, "
        "\"euler_characteristic\": %d, \"max_geodesic_distance\": %.6g, \"param_flipped_triangles\": %d, "
        "\"radius\": %.9g, \"orientation\": {\"reoriented_triangles\": %d, \"components\": %d, "
        "\"closed_components\": %d, \"inconsistent_components\": %d, \"outward_turned_components\": %d}, "
        "\"seconds\": %.6g}\n",
        patch.mesh.num_vertices(), patch.mesh.num_triangles(), patch.filled_triangles(), topo.boundary_loops.size(),
        euler_characteristic(patch.mesh, topo), patch.max_geodesic_distance, patch.param_flipped_triangles,
        patch.radius, o.reoriented_triangles, o.components, o.closed_components, o.inconsistent_components,
        o.components_turned_outward, seconds);
  } else {
    if (o.reoriented_triangles > 0)
      std::printf("input orientation repaired: %d triangles reversed (%d inconsistent components, %d turned outward)\n",
                  o.reoriented_triangles, o.inconsistent_components, o.components_turned_outward);
    std::printf("patch: %d vertices, %d faces (%d filled), %zu boundary loop(s), Euler characteristic %d\n",
                patch.mesh.num_vertices(), patch.mesh.num_triangles(), patch.filled_triangles(),
                topo.boundary_loops.size(), euler_characteristic(patch.mesh, topo));
    std::printf("max geodesic distance %.4f (normalized), %d flipped triangles in the parametrization, %.3f s\n",
                patch.max_geodesic_distance, patch.param_flipped_triangles, seconds);
  }
}

int run_patch(const Args& args) {
  const ArgParser p(args, {"mesh", "center-vertex", "center-triangle", "barycentric", "radius", "out", "face-range",
                           "group", "snap"},
                    {"json", "no-fill"}, kUsage);
  io::MeshFileOptions file_options;
  if (p.has("face-range")) parse_range(p.get("face-range"), file_options.face_begin, file_options.face_end);
  file_options.obj_group = p.get("group");
  const io::LoadedMesh loaded = io::read_mesh(p.required("mesh"), file_options);

  PatchOptions options;
  options.radius = p.number("radius", 0.0);
  require(p.has("radius"), MCON_ERROR_INVALID_ARGUMENT, "missing required option --radius");
  options.fill_holes = !p.flag("no-fill");
  options.snap_fraction = p.number("snap", options.snap_fraction);
  if (p.has("center-vertex")) {
    options.center.vertex = io::mesh_vertex_of_file_vertex(loaded, p.integer("center-vertex", -1), "--center-vertex");
  } else {
    require(p.has("center-triangle"), MCON_ERROR_INVALID_ARGUMENT, "give --center-vertex or --center-triangle");
    const int triangle = io::mesh_triangle_of_file_face(loaded, p.integer("center-triangle", -1), "--center-triangle");
    options.center.triangle = triangle;
    if (p.has("barycentric")) {
      const std::string s = p.get("barycentric");
      const auto c1 = s.find(','), c2 = s.find(',', c1 + 1);
      require(c1 != std::string::npos && c2 != std::string::npos, MCON_ERROR_INVALID_ARGUMENT,
              "--barycentric expects a,b,c");
      options.center.barycentric = Vec3(ArgParser::parse_number("barycentric", s.substr(0, c1)),
                                        ArgParser::parse_number("barycentric", s.substr(c1 + 1, c2 - c1 - 1)),
                                        ArgParser::parse_number("barycentric", s.substr(c2 + 1)));
      // The weights follow the file's corner order; a reoriented triangle has corners 1 and 2 swapped.
      if (loaded.orientation.reoriented[static_cast<std::size_t>(triangle)])
        std::swap(options.center.barycentric[1], options.center.barycentric[2]);
    }
  }

  const auto t0 = std::chrono::steady_clock::now();
  const Patch patch = extract_geodesic_disk(loaded.mesh, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const MeshTopology topo = build_topology(patch.mesh);

  if (p.has("out")) {
    io::VertexAttribute uv{"uv", 2, {}}, host{"host_vertex", 1, {}}, mean{"mean_curvature", 1, {}};
    for (const Vec2& q : patch.uv) uv.values.insert(uv.values.end(), {q.x(), q.y()});
    for (const HostPoint& h : patch.host_vertex)
      host.values.push_back(h.v0 < 0 ? -1.0 : static_cast<double>(loaded.mesh_to_file[h.t < 0.5 ? h.v0 : h.v1]));
    const Eigen::VectorXd H = mean_curvature_descriptor(patch.mesh);
    mean.values.assign(H.data(), H.data() + H.size());
    io::FaceAttribute filled{"filled", {}};
    for (int ht : patch.host_triangle) filled.values.push_back(ht < 0 ? 1 : 0);
    io::write_ply(p.get("out"), patch.mesh, {uv, mean, host}, {filled});
  }

  print_summary(patch, topo, loaded.orientation, seconds, p.flag("json"));
  return 0;
}

const Registration registration{"patch", "cut a geodesic disk patch out of a mesh", run_patch};

}  // namespace
}  // namespace mcon::cli
