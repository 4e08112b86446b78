// `macrocon embed`: re-embed a source patch onto a target region and transfer its constraints
// (thesis ch. 4): the target patch with the transferred per-vertex fields (PLY), the guide
// polylines re-traced on the target (OBJ `l` lines), the target's guide-aligned cross field
// (QuadWild `.rosy`) and a JSON summary of the map.
#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "base/text.h"
#include "command/args.h"
#include "command/command.h"
#include "command/progress_bar.h"
#include "embed_stages.h"
#include "io/mesh_io.h"
#include "json/json_file.h"
#include "macrocon/macrocon.hpp"
#include "sdk_arrays.h"

namespace mcon::cli {
namespace {

const char* kUsage =
    "usage: macrocon embed --source FILE --target FILE --center-vertex N --radius R\n"
    "                      [--source-center-vertex M --source-radius Q | --entry ID|NAME] [--face-range A:B]\n"
    "                      [--source-face-range A:B] [--seed S] [--samples K] [--iterations I]\n"
    "                      [--orientation auto|preserve|reverse] [--landmarks S:T,S:T,...]\n"
    "                      [--up X,Y,Z | --source-up X,Y,Z --target-up X,Y,Z] [--cut-guides]\n"
    "                      [--snap F] [--fair-passes N] [--out DIR] [--json] [--quiet | --progress]\n"
    "Maps a source patch onto the geodesic disk of radius R around vertex N of the target mesh and\n"
    "transfers the source's constraints. With --source-center-vertex the source patch is cut the same\n"
    "way from the source mesh (radius Q, default R); without it the source file must already be one\n"
    "normalized disk patch (a library entry), centered at its vertex nearest to its area centroid.\n"
    "With --entry, --source is a library file (.mclb) and the entry (an id, or a unique name; see\n"
    "macrocon library info) is the source patch: its own guides, features, singularities and fields\n"
    "are transferred (features to features.obj, singularities to singularities.csv, fields into\n"
    "target.ply under their names; --landmarks then numbers the entry's vertices from 0).\n"
    "A mesh source gets synthetic constraints that show the map: its uv, mean curvature, geodesic\n"
    "distance from the center and a ring label (distance in steps of 0.25) per vertex, and guide\n"
    "loops at geodesic distance 0.3 and 0.6.\n"
    "--out DIR (default embed-out) receives target.ply (target patch in target mesh units with the\n"
    "transferred fields and 'outside' = 1 where no source point maps), target.obj (the same triangles\n"
    "with exact doubles, for QuadWild), guides.obj (re-traced guides),\n"
    "source_guides.obj, target.rosy (cross field following the guides) and summary.json; --json\n"
    "also prints the summary. Vertex numbers and face ranges refer to the files.\n"
    "--orientation (default auto) forces an orientation-preserving or -reversing map, e.g. to flip a\n"
    "nearly mirror-symmetric patch; the summary's alignment_score_unreflected/_reflected (-1: not\n"
    "tried), orientation_compared and level0_energy_unreflected/_reflected (-1: not compared) show\n"
    "how close the automatic call was.\n"
    "--landmarks pairs source vertex S with target vertex T (file numbers, both inside their patches),\n"
    "e.g. points an artist clicked on both meshes; the map is guided by the geodesic distances from\n"
    "them (mcon_map_options guidance channels), which settles what the geometry cannot (orientation,\n"
    "which finger is which).\n"
    "--up gives both meshes' up direction in their file coordinates (e.g. 0,1,0 for Y-up hosts);\n"
    "--source-up and --target-up give them apart; an --entry that stores its up (library build --up)\n"
    "gives the source's, so --up or --target-up is the target's. The map's rigid start then turns the\n"
    "source's up onto the target's (within 60 degrees), so it is never upside down; a reflection stays\n"
    "--orientation's.\n"
    "An up direction (nearly) normal to a patch at its center is refused: omit it for such patches.\n"
    "--cut-guides also cuts the re-traced guides into the target patch, so every guide is a chain of\n"
    "mesh edges, and writes the cut patch for a quad mesher: target_cut.obj (QuadWild's input, exact\n"
    "doubles), target_cut.ply (with the transferred fields), target_cut.sharp (the guide edges as\n"
    "feature edges) and target_cut.rosy (a cross field that follows the guide edges exactly).\n"
    "Crossings closer than --snap F (default 0.25) edge lengths to a vertex snap to it and guides that\n"
    "close merge, so no sliver is made; --fair-passes N (default 3, 0 = off) passes of fairing then\n"
    "straighten the chains on the surface. The summary's 'cut' reports the smallest angle created.\n"
    "A progress bar for the map is drawn on stderr when it is a terminal; --quiet hides it, --progress\n"
    "draws it anyway (e.g. into a log).\n" MACROCON_HELP_NUMBERING;

io::LoadedMesh load(const ArgParser& p, const std::string& file_key, const std::string& range_key,
                    OrientationRule orientation = OrientationRule::outward) {
  io::MeshFileOptions options;
  options.orientation = orientation;
  if (p.has(range_key)) parse_range(range_key, p.get(range_key), options.face_begin, options.face_end);
  return io::read_mesh(p.required(file_key), options);
}

macrocon::Patch cut(const macrocon::Context& context, const io::LoadedMesh& mesh, long file_vertex, double radius,
                    const std::string& what) {
  const int center = io::mesh_vertex_of_file_vertex(mesh, file_vertex, what);
  require(std::isfinite(radius) && radius > 0, MCON_ERROR_INVALID_ARGUMENT, "radii must be > 0");
  return macrocon::Patch::extract(sdk_mesh(context, mesh.mesh),
                                  macrocon::PatchOptions::at_vertex(static_cast<std::uint32_t>(center), radius));
}

// "S:T,S:T,...": pairs of file vertex numbers (source, target).
std::vector<std::pair<long, long>> parse_landmarks(const std::string& s) {
  std::vector<std::pair<long, long>> out;
  std::size_t at = 0;
  while (at <= s.size()) {
    const std::size_t end = std::min(s.find(',', at), s.size());
    const std::string item = s.substr(at, end - at);
    const std::size_t colon = item.find(':');
    require(colon != std::string::npos, MCON_ERROR_INVALID_ARGUMENT,
            "--landmarks expects S:T pairs separated by commas, got '" + item + "'");
    out.emplace_back(static_cast<long>(ArgParser::parse_number("landmarks", item.substr(0, colon))),
                     static_cast<long>(ArgParser::parse_number("landmarks", item.substr(colon + 1))));
    at = end + 1;
  }
  require(out.size() <= 64, MCON_ERROR_INVALID_ARGUMENT, "--landmarks takes at most 64 pairs");
  return out;
}

// The patch vertex of file vertex `file_vertex` of `mesh` (a patch vertex that is a host vertex
// links {h, h}; cut crossings lie strictly inside an edge), or an error naming the landmark.
std::uint32_t landmark_vertex(const io::LoadedMesh& mesh, const macrocon::HostVertices& host, long file_vertex,
                              const char* side) {
  const bool known = file_vertex >= 0 && file_vertex < static_cast<long>(mesh.file_to_mesh.size()) &&
                     mesh.file_to_mesh[static_cast<std::size_t>(file_vertex)] >= 0;
  const std::uint32_t h =
      known ? static_cast<std::uint32_t>(mesh.file_to_mesh[static_cast<std::size_t>(file_vertex)]) : MCON_INVALID_INDEX;
  for (std::size_t v = 0; known && v < host.v0.size(); ++v)
    if (host.v0[v] == h && host.v1[v] == h) return static_cast<std::uint32_t>(v);
  fail(MCON_ERROR_INVALID_ARGUMENT, std::string("--landmarks: ") + side + " vertex " + std::to_string(file_vertex) +
                                        " is not a vertex of the " + side + " patch");
}

// An already-cut, normalized patch: centered at the vertex nearest to its area-weighted centroid
// (the center of a geodesic disk is near its centroid unless the disk is very curved; the vertex,
// not the centroid itself, so the center is a point of the surface).
macrocon::Patch as_entry(const macrocon::Context& context, const TriMesh& mesh) {
  Vec3 centroid = Vec3::Zero();
  double area = 0;
  for (const Tri& tri : mesh.triangles) {
    const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
    const double t_area = 0.5 * (b - a).cross(c - a).norm();
    centroid += t_area * (a + b + c) / 3.0;
    area += t_area;
  }
  centroid /= area;
  int best = 0;
  for (int v = 1; v < mesh.num_vertices(); ++v)
    if ((mesh.positions[v] - centroid).squaredNorm() < (mesh.positions[best] - centroid).squaredNorm()) best = v;
  std::uint32_t center_triangle = MCON_INVALID_INDEX;
  std::array<double, 3> center_barycentric{{0, 0, 0}};
  for (std::size_t t = 0; t < mesh.triangles.size() && center_triangle == MCON_INVALID_INDEX; ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] == best) {
        center_triangle = static_cast<std::uint32_t>(t);
        center_barycentric[static_cast<std::size_t>(k)] = 1.0;
      }
  return macrocon::patch_from_arrays(context, flat_positions(mesh), flat_triangles(mesh), center_triangle,
                                     center_barycentric);
}

EmbedOptions embed_options(const ArgParser& p) {
  require(p.has("center-vertex"), MCON_ERROR_INVALID_ARGUMENT, "missing required option --center-vertex");
  require(p.has("radius"), MCON_ERROR_INVALID_ARGUMENT, "missing required option --radius");
  EmbedOptions o;
  o.out_dir = p.get("out", "embed-out");
  o.samples = p.integer("samples", 10000);
  o.iterations = p.integer("iterations", 100);
  require(o.samples >= 1, MCON_ERROR_INVALID_ARGUMENT, "--samples must be >= 1");
  require(o.iterations >= 1, MCON_ERROR_INVALID_ARGUMENT, "--iterations must be >= 1");
  o.seed = p.integer("seed", 0);
  require(o.seed >= 0, MCON_ERROR_INVALID_ARGUMENT, "--seed must be >= 0");
  o.orientation = p.get("orientation", "auto");
  require(o.orientation == "auto" || o.orientation == "preserve" || o.orientation == "reverse",
          MCON_ERROR_INVALID_ARGUMENT, "--orientation must be auto, preserve or reverse, got '" + o.orientation + "'");
  require(!p.has("up") || (!p.has("source-up") && !p.has("target-up")), MCON_ERROR_INVALID_ARGUMENT,
          "give --up (both meshes) or --source-up and --target-up, not both");
  if (p.has("up")) o.source_up = o.target_up = parse_vec3("up", p.get("up"));
  if (p.has("source-up")) o.source_up = parse_vec3("source-up", p.get("source-up"));
  if (p.has("target-up")) o.target_up = parse_vec3("target-up", p.get("target-up"));
  o.cut_guides = p.flag("cut-guides");
  require(o.cut_guides || !p.has("snap"), MCON_ERROR_INVALID_ARGUMENT, "--snap needs --cut-guides");
  mcon_guide_cut_options defaults;
  macrocon::check(mcon_guide_cut_options_init(&defaults));
  o.snap = p.number("snap", defaults.snap_fraction);
  require(o.snap >= 0 && o.snap <= 0.45, MCON_ERROR_INVALID_ARGUMENT,
          "--snap must be in [0, 0.45] (a fraction of an edge length)");
  require(o.cut_guides || !p.has("fair-passes"), MCON_ERROR_INVALID_ARGUMENT, "--fair-passes needs --cut-guides");
  o.fair_passes = p.integer("fair-passes", defaults.fair_passes);
  require(o.fair_passes >= 0 && o.fair_passes <= 100, MCON_ERROR_INVALID_ARGUMENT,
          "--fair-passes must be 0 (no chain fairing) to 100");
  return o;
}

PatchGeometry geometry_of(const macrocon::Patch& patch) {
  const mcon_patch_info info = patch.info();
  PatchGeometry g;
  g.mesh = file_mesh(patch);
  g.center = Vec3(info.center[0], info.center[1], info.center[2]);
  g.radius = info.radius;
  g.center_point.face = info.center_patch_triangle;
  for (int k = 0; k < 3; ++k) g.center_point.barycentric[k] = info.center_barycentric[k];
  return g;
}

// The index of the entry --entry names: a number is an id, anything else a name (which must be unique).
std::size_t find_library_entry(const macrocon::Library& lib, const std::string& path, const std::string& which) {
  const bool numeric = !which.empty() && which.find_first_not_of("0123456789") == std::string::npos;
  errno = 0;
  const unsigned long long id = numeric ? std::strtoull(which.c_str(), nullptr, 10) : 0;
  std::optional<std::size_t> found;
  if (numeric && errno != ERANGE) {
    try {
      found = lib.find(id);
    } catch (const macrocon::Error& e) {
      if (e.status() != MCON_ERROR_NOT_FOUND) throw;
    }
  }
  std::size_t named = 0;
  for (std::size_t i = 0; !numeric && i < lib.size(); ++i)
    if (lib.entry_string(i, MCON_ENTRY_NAME, 0) == which) {
      found = i;
      ++named;
    }
  require(named <= 1, MCON_ERROR_INVALID_ARGUMENT,
          "--entry '" + printable_text(which) + "': " + std::to_string(named) + " entries of '" + path +
              "' have that name; give the id (macrocon library info lists them)");
  require(found.has_value(), MCON_ERROR_NOT_FOUND,
          "--entry '" + printable_text(which) + "': '" + path + "' has no entry with that " +
              (numeric ? "id" : "name") + " (macrocon library info lists them)");
  return *found;
}

// The entry as the source patch, in the units of the mesh it was cut from; its vertices are the
// source's "file" vertices (for --landmarks).
void entry_source(const ArgParser& p, EmbedPatches& e) {
  for (const char* key : {"source-center-vertex", "source-radius", "source-face-range"})
    require(!p.has(key), MCON_ERROR_INVALID_ARGUMENT,
            std::string("--") + key + " does not apply with --entry: the entry is already a patch");
  const std::string path = p.required("source");
  const macrocon::Library lib = macrocon::Library::open(e.context, path);
  const std::size_t index = find_library_entry(lib, path, p.get("entry"));
  const mcon_library_entry_info info = lib.entry_info(index);
  e.entry = lib.entry(index);
  const mcon_surface_point& c = info.center;
  e.source = macrocon::patch_from_arrays(e.context, lib.entry_positions(index), lib.entry_triangles(index), c.face,
                                         {{c.barycentric[0], c.barycentric[1], c.barycentric[2]}},
                                         {{info.source_origin[0], info.source_origin[1], info.source_origin[2]}},
                                         info.source_scale);
  for (std::size_t v = 0; v < info.vertex_count; ++v) {
    e.source_mesh.file_to_mesh.push_back(static_cast<int>(v));
    e.source_mesh.mesh_to_file.push_back(static_cast<long>(v));
  }
}

void cut_source(const ArgParser& p, EmbedPatches& e) {
  const bool cut_from_mesh = p.has("source-center-vertex");
  // A source that is already a patch is oriented like mcon_patch_create_from_arrays (majority).
  e.source_mesh =
      load(p, "source", "source-face-range", cut_from_mesh ? OrientationRule::outward : OrientationRule::majority);
  require(cut_from_mesh || !p.has("source-radius"), MCON_ERROR_INVALID_ARGUMENT,
          "--source-radius needs --source-center-vertex");
  if (cut_from_mesh) {
    e.source = cut(e.context, e.source_mesh, p.integer("source-center-vertex", -1),
                   p.number("source-radius", p.number("radius", 0)), "--source-center-vertex");
    return;
  }
  try {
    e.source = as_entry(e.context, e.source_mesh.mesh);
  } catch (const macrocon::Error& err) {
    // A whole mesh given as --source (a closed head, a body) is the usual slip: say what to add.
    if (err.status() != MCON_ERROR_NOT_A_DISK) throw;
    fail(MCON_ERROR_NOT_A_DISK, "--source '" + p.get("source", "") + "' is not a disk patch (" + err.what() +
                                    "): give --source-center-vertex M (and --source-radius Q) to cut one out of it");
  }
}

EmbedPatches cut_embed_patches(const ArgParser& p) {
  EmbedPatches e;
  e.target_mesh = load(p, "target", "face-range");
  e.target = cut(e.context, e.target_mesh, p.integer("center-vertex", -1), p.number("radius", 0), "--center-vertex");
  if (p.has("entry"))
    entry_source(p, e);
  else
    cut_source(p, e);
  e.target_geometry = geometry_of(e.target);
  e.source_geometry = geometry_of(e.source);
  return e;
}

// An --entry that stores its source's up direction supplies the source's hint: --up and --target-up
// then give the target's (an explicit --source-up still wins). Both hints or none reach the map.
void resolve_up_hints(const ArgParser& p, const EmbedPatches& e, EmbedOptions& o) {
  if (e.entry && e.entry->up && !p.has("source-up") && o.target_up) {
    o.source_up = e.entry->up;
    o.up_from_entry = true;
  }
  require(o.source_up.has_value() == o.target_up.has_value(), MCON_ERROR_INVALID_ARGUMENT,
          o.source_up ? "--source-up and --target-up go together (or give --up for both)"
                      : "--target-up needs --source-up (or an --entry that stores its up; see library info --json)");
}

// Landmarks: one guidance channel per pair, the geodesic distance from it on each patch.
void landmark_guidance(const std::vector<std::pair<long, long>>& landmarks, const EmbedPatches& e,
                       macrocon::MapOptions& options) {
  const std::size_t k_count = landmarks.size(), ns = e.source.vertex_count(), nt = e.target.vertex_count();
  const macrocon::HostVertices source_host = e.source.host_vertices(), target_host = e.target.host_vertices();
  options.guidance_dimension = static_cast<std::uint32_t>(k_count);
  options.source_guidance.assign(ns * k_count, 0.0);
  options.target_guidance.assign(nt * k_count, 0.0);
  for (std::size_t k = 0; k < k_count; ++k) {
    const std::vector<double> ds =
        e.source.distance_from_vertices({landmark_vertex(e.source_mesh, source_host, landmarks[k].first, "source")});
    const std::vector<double> dt =
        e.target.distance_from_vertices({landmark_vertex(e.target_mesh, target_host, landmarks[k].second, "target")});
    for (std::size_t v = 0; v < ns; ++v) options.source_guidance[v * k_count + k] = ds[v];
    for (std::size_t v = 0; v < nt; ++v) options.target_guidance[v * k_count + k] = dt[v];
  }
}

EmbedMap map_embed_patches(const ArgParser& p, const EmbedOptions& o, const EmbedPatches& e) {
  macrocon::MapOptions options;
  options.alignment_samples = static_cast<std::uint32_t>(o.samples);
  options.seed = static_cast<std::uint64_t>(o.seed);
  options.max_iterations = static_cast<std::uint32_t>(o.iterations);
  options.orientation = o.orientation == "preserve"  ? MCON_MAP_ORIENTATION_PRESERVE
                        : o.orientation == "reverse" ? MCON_MAP_ORIENTATION_REVERSE
                                                     : MCON_MAP_ORIENTATION_AUTOMATIC;
  options.source_up = o.source_up;
  options.target_up = o.target_up;
  const std::vector<std::pair<long, long>> landmarks =
      p.has("landmarks") ? parse_landmarks(p.get("landmarks")) : std::vector<std::pair<long, long>>{};
  if (!landmarks.empty()) landmark_guidance(landmarks, e, options);
  EmbedMap m;
  m.landmarks = landmarks.size();
  ProgressBar bar("map", progress_wanted(p));
  options.progress = bar.callback();
  const auto t_map = std::chrono::steady_clock::now();
  m.map = macrocon::Map::compute(e.source, e.target, options);
  bar.finish();
  m.map_seconds = seconds_since(t_map);
  m.info = m.map.info();
  return m;
}

// The points of `points` as the parallel arrays the map's transfers take.
void flatten(const std::vector<mcon_surface_point>& points, std::vector<std::uint32_t>& triangles,
             std::vector<double>& barycentric) {
  for (const mcon_surface_point& q : points) {
    triangles.push_back(q.face);
    barycentric.insert(barycentric.end(), {q.barycentric[0], q.barycentric[1], q.barycentric[2]});
  }
}

TracedLines trace_polylines(const macrocon::Map& map, const std::vector<macrocon::Polyline>& lines) {
  std::vector<std::uint32_t> triangles, sizes;
  std::vector<double> barycentric;
  std::vector<std::uint8_t> closed;
  for (const macrocon::Polyline& l : lines) {
    flatten(l.points, triangles, barycentric);
    sizes.push_back(static_cast<std::uint32_t>(l.points.size()));
    closed.push_back(l.closed ? 1 : 0);
  }
  TracedLines t;
  t.set = map.transfer_polylines(triangles, barycentric, sizes, closed);
  t.sizes = t.set.sizes();
  t.inputs = t.set.input_polylines();
  t.closed = t.set.closed();
  t.points = t.set.points();
  return t;
}

EmbedTransfer transfer_constraints(const macrocon::Map& map, const EmbedPatches& e) {
  EmbedTransfer x;
  // 3. Source constraints: the entry's own, or synthetic ones that show the map.
  const auto t_transfer = std::chrono::steady_clock::now();
  x.source = e.entry ? entry_constraints(*e.entry) : synthetic_constraints(e.source);
  x.source_field_seconds = seconds_since(t_transfer);
  const auto t_fields = std::chrono::steady_clock::now();
  x.fields = transfer_fields(map, x.source.fields);
  x.outside = map.outside_mask();
  x.field_seconds = seconds_since(t_fields);
  const auto t_polylines = std::chrono::steady_clock::now();
  x.traced = trace_polylines(map, x.source.polylines);
  const mcon_surface_point& c = e.source_geometry.center_point;
  x.center_on_target =
      map.transfer_points({c.face}, {c.barycentric[0], c.barycentric[1], c.barycentric[2]}).triangles[0] !=
      MCON_INVALID_INDEX;
  std::vector<mcon_surface_point> singularities;
  for (const mcon_singularity& s : x.source.singularities) singularities.push_back(s.location);
  std::vector<std::uint32_t> triangles;
  std::vector<double> barycentric;
  flatten(singularities, triangles, barycentric);
  if (!triangles.empty()) x.singularities = map.transfer_points(triangles, barycentric);
  x.polyline_seconds = seconds_since(t_polylines);
  // 4. Cross field of the target following the re-traced guides and features.
  const auto t_field = std::chrono::steady_clock::now();
  x.cross_field = macrocon::compute_cross_field(e.target, x.traced.set).directions;
  x.cross_field_seconds = seconds_since(t_field);
  x.transfer_seconds = seconds_since(t_transfer);
  return x;
}

int run_embed(const Args& args) {
  static const OptionHelp help{
      {"source", "the source: a mesh, a disk patch file, or a library (.mclb) with --entry"},
      {"target", "the target mesh"},
      {"face-range", "keep only the target file's faces [A, B)"},
      {"center-vertex", "center of the target region (target file vertex)"},
      {"radius", "geodesic radius of the target region in target mesh units"},
      {"source-center-vertex", "cut the source region around this source file vertex"},
      {"source-radius", "geodesic radius of the source region (default --radius)"},
      {"source-face-range", "keep only the source file's faces [A, B)"},
      {"entry", "with a library --source: the entry (id, or a unique name)"},
      {"samples", "rigid start candidates scored (default 10000)"},
      {"iterations", "Newton iterations per coarse-to-fine level (default 100)"},
      {"orientation", "auto (default), preserve or reverse"},
      {"landmarks", "source:target vertex pairs that must correspond"},
      {"up", "up direction of both meshes, in file coordinates"},
      {"source-up", "up direction of the source mesh (with --target-up)"},
      {"target-up", "up direction of the target mesh (with --source-up)"},
      {"out", "output folder (default embed-out)"},
      {"snap", "with --cut-guides: snap crossings this close to a vertex (edge fraction, default 0.25)"},
      {"fair-passes", "with --cut-guides: passes of chain fairing, 0 = off (default 3)"},
      {"cut-guides", "also cut the guides into the target patch and write QuadWild's inputs"},
  };
  const ArgParser p(args,
                    {"source", "target", "center-vertex", "radius", "source-center-vertex", "source-radius",
                     "face-range", "source-face-range", "seed", "samples", "iterations", "orientation", "landmarks",
                     "up", "source-up", "target-up", "out", "snap", "fair-passes", "entry"},
                    {"json", "cut-guides", "quiet", "progress"}, kUsage, help);
  const auto t_start = std::chrono::steady_clock::now();
  EmbedOptions o = embed_options(p);
  const EmbedPatches e = cut_embed_patches(p);
  resolve_up_hints(p, e, o);
  const double patch_seconds = seconds_since(t_start);
  const EmbedMap m = map_embed_patches(p, o, e);
  const EmbedTransfer x = transfer_constraints(m.map, e);
  const EmbedFiles f = write_embed_files(o.out_dir, e, x);
  std::optional<EmbedCut> cut;
  if (o.cut_guides) cut = cut_and_write(o, e, x);
  tools::Json summary = embed_summary(o, e, m, x, f, patch_seconds, t_start);
  summary.set("guide_turning", turning_summary(e, x, cut ? &*cut : nullptr));
  if (cut) add_cut_summary(*cut, summary);
  tools::write_json_file(f.summary_path, summary);
  if (p.flag("json"))
    std::printf("%s\n", tools::write_json(summary, false).c_str());
  else
    print_report(o, m, x, f, cut ? &*cut : nullptr);
  return m.info.flipped_triangles == 0 ? 0 : 1;
}

const Registration registration{"embed", "re-embed a source patch onto a target region and transfer its constraints",
                                run_embed};

}  // namespace
}  // namespace mcon::cli
