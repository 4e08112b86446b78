// `macrocon patch`: cut a geodesic disk out of a mesh file and report its topology (through the
// public API, as every product command).
#include <chrono>
#include <cstdio>
#include <string>

#include "command/args.h"
#include "io/mesh_io.h"
#include "macrocon/macrocon.hpp"
#include "sdk_arrays.h"

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

// The summary on stdout: one JSON object with --json, else two or three lines.
void print_summary(const mcon_patch_info& patch, const OrientationReport& o, double seconds, bool json) {
  if (json) {
    std::printf(
        "{\"vertices\": %zu, \"faces\": %zu, \"filled_faces\": %zu, \"boundary_loops\": %u, "
        "\"euler_characteristic\": %d, \"max_geodesic_distance\": %.6g, \"param_flipped_triangles\": %u, "
        "\"radius\": %.9g, \"orientation\": {\"reoriented_triangles\": %d, \"components\": %d, "
        "\"closed_components\": %d, \"inconsistent_components\": %d, \"outward_turned_components\": %d}, "
        "\"seconds\": %.6g}\n",
        patch.vertex_count, patch.triangle_count, patch.filled_triangle_count, patch.boundary_loops,
        patch.euler_characteristic, patch.max_geodesic_distance, patch.param_flipped_triangles, patch.radius,
        o.reoriented_triangles, o.components, o.closed_components, o.inconsistent_components,
        o.components_turned_outward, seconds);
  } else {
    if (o.reoriented_triangles > 0)
      std::printf("input orientation repaired: %d triangles reversed (%d inconsistent components, %d turned outward)\n",
                  o.reoriented_triangles, o.inconsistent_components, o.components_turned_outward);
    std::printf("patch: %zu vertices, %zu faces (%zu filled), %u boundary loop(s), Euler characteristic %d\n",
                patch.vertex_count, patch.triangle_count, patch.filled_triangle_count, patch.boundary_loops,
                patch.euler_characteristic);
    std::printf("max geodesic distance %.4f (normalized), %u flipped triangles in the parametrization, %.3f s\n",
                patch.max_geodesic_distance, patch.param_flipped_triangles, seconds);
  }
}

// The center from --center-vertex, or --center-triangle [--barycentric a,b,c] (file numbering).
macrocon::PatchOptions center_options(const ArgParser& p, const io::LoadedMesh& loaded) {
  macrocon::PatchOptions options;
  if (p.has("center-vertex")) {
    options.center_vertex = static_cast<std::uint32_t>(
        io::mesh_vertex_of_file_vertex(loaded, p.integer("center-vertex", -1), "--center-vertex"));
    return options;
  }
  require(p.has("center-triangle"), MCON_ERROR_INVALID_ARGUMENT, "give --center-vertex or --center-triangle");
  const int triangle = io::mesh_triangle_of_file_face(loaded, p.integer("center-triangle", -1), "--center-triangle");
  options.center_triangle = static_cast<std::uint32_t>(triangle);
  if (p.has("barycentric")) {
    const std::string s = p.get("barycentric");
    const auto c1 = s.find(','), c2 = s.find(',', c1 + 1);
    require(c1 != std::string::npos && c2 != std::string::npos, MCON_ERROR_INVALID_ARGUMENT,
            "--barycentric expects a,b,c");
    options.center_barycentric = {ArgParser::parse_number("barycentric", s.substr(0, c1)),
                                  ArgParser::parse_number("barycentric", s.substr(c1 + 1, c2 - c1 - 1)),
                                  ArgParser::parse_number("barycentric", s.substr(c2 + 1))};
    // The weights follow the file's corner order; a reoriented triangle has corners 1 and 2 swapped.
    if (loaded.orientation.reoriented[static_cast<std::size_t>(triangle)])
      std::swap(options.center_barycentric[1], options.center_barycentric[2]);
  }
  return options;
}

// The normalized patch as PLY: uv, mean curvature, the nearer host vertex (file numbering, -1 for
// hole-fill vertices) and a per-face 'filled' flag.
void write_patch_ply(const std::string& path, const macrocon::Patch& patch, const io::LoadedMesh& loaded) {
  io::VertexAttribute uv{"uv", 2, patch.uv()}, host{"host_vertex", 1, {}},
      mean{"mean_curvature", 1, patch.compute_descriptors(MCON_DESCRIPTOR_MEAN_CURVATURE)};
  const macrocon::HostVertices h = patch.host_vertices();
  for (std::size_t v = 0; v < h.v0.size(); ++v)
    host.values.push_back(h.v0[v] == MCON_INVALID_INDEX
                              ? -1.0
                              : static_cast<double>(loaded.mesh_to_file[h.t[v] < 0.5 ? h.v0[v] : h.v1[v]]));
  io::FaceAttribute filled{"filled", {}};
  for (std::uint32_t ht : patch.host_triangles()) filled.values.push_back(ht == MCON_INVALID_INDEX ? 1 : 0);
  io::write_ply(path, file_mesh(patch), {uv, mean, host}, {filled});
}

int run_patch(const Args& args) {
  static const OptionHelp help{
      {"mesh", "the host mesh (OBJ, PLY, OFF; .gz too)"},
      {"center-vertex", "center at this file vertex"},
      {"center-triangle", "center inside this file face (with --barycentric)"},
      {"barycentric", "the center's weights in --center-triangle (default 1/3 each)"},
      {"radius", "geodesic radius in mesh units"},
      {"out", "write the normalized patch here (PLY)"},
      {"group", "keep only this OBJ group of the mesh"},
      {"snap", "boundary crossings this close to a vertex (fraction of an edge) snap to it"},
      {"no-fill", "leave holes inside the disk open (default: filled)"},
  };
  const ArgParser p(args, {"mesh", "center-vertex", "center-triangle", "barycentric", "radius", "out", "face-range",
                           "group", "snap"},
                    {"json", "no-fill"}, kUsage, help);
  io::MeshFileOptions file_options;
  if (p.has("face-range")) parse_range("face-range", p.get("face-range"), file_options.face_begin, file_options.face_end);
  file_options.obj_group = p.get("group");
  const io::LoadedMesh loaded = io::read_mesh(p.required("mesh"), file_options);

  macrocon::PatchOptions options = center_options(p, loaded);
  options.radius = p.number("radius", 0.0);
  require(p.has("radius"), MCON_ERROR_INVALID_ARGUMENT, "missing required option --radius");
  options.fill_holes = !p.flag("no-fill");
  options.snap_fraction = p.number("snap", options.snap_fraction);

  const macrocon::Context context;
  const macrocon::Mesh host = sdk_mesh(context, loaded.mesh);
  const auto t0 = std::chrono::steady_clock::now();
  const macrocon::Patch patch = macrocon::Patch::extract(host, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (p.has("out")) write_patch_ply(p.get("out"), patch, loaded);
  print_summary(patch.info(), loaded.orientation, seconds, p.flag("json"));
  return 0;
}

const Registration registration{"patch", "cut a geodesic disk patch out of a mesh", run_patch};

}  // namespace
}  // namespace mcon::cli
