// `macrocon embed`: re-embed a source patch onto a target region and transfer its constraints
// (thesis ch. 4): the target patch with the transferred per-vertex fields (PLY), the guide
// polylines re-traced on the target (OBJ `l` lines), the target's guide-aligned cross field
// (QuadWild `.rosy`) and a JSON summary of the map.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <optional>
#include <string>
#include <vector>

#include "command/args.h"
#include "command/progress_bar.h"
#include "base/text.h"
#include "embed_constraints.h"
#include "library/library_file.h"
#include "json/json_file.h"
#include "transfer/cross_field.h"
#include "transfer/field_transfer.h"
#include "transfer/guide_cutting.h"
#include "patch/geodesic_disk_patch.h"
#include "operators/heat_geodesics.h"
#include "io/mesh_io.h"
#include "transfer/map_view.h"
#include "patch/patch_from_arrays.h"
#include "map/patch_map.h"
#include "transfer/polyline_transfer.h"

namespace mcon::cli {
namespace {

const char* kUsage =
    "usage: macrocon embed --source FILE --target FILE --center-vertex N --radius R\n"
    "                      [--source-center-vertex M --source-radius Q | --entry ID|NAME] [--face-range A:B]\n"
    "                      [--source-face-range A:B] [--seed S] [--samples K] [--iterations I]\n"
    "                      [--orientation auto|preserve|reverse] [--landmarks S:T,S:T,...]\n"
    "                      [--up X,Y,Z | --source-up X,Y,Z --target-up X,Y,Z] [--cut-guides]\n"
    "                      [--snap F] [--out DIR] [--json] [--quiet | --progress]\n"
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
    "--source-up and --target-up give them apart. The map's rigid start then turns the source's up onto\n"
    "the target's (within 60 degrees), so it is never upside down; a reflection stays --orientation's.\n"
    "An up direction (nearly) normal to a patch at its center is refused: omit it for such patches.\n"
    "--cut-guides also cuts the re-traced guides into the target patch, so every guide is a chain of\n"
    "mesh edges, and writes the cut patch for a quad mesher: target_cut.obj (QuadWild's input, exact\n"
    "doubles), target_cut.ply (with the transferred fields), target_cut.sharp (the guide edges as\n"
    "feature edges) and target_cut.rosy (a cross field that follows the guide edges exactly).\n"
    "Crossings closer than --snap F (default 0.25) edge lengths to a vertex snap to it and guides that\n"
    "close merge, so no sliver is made; the summary's 'cut' reports the smallest angle created.\n"
    "A progress bar for the map is drawn on stderr when it is a terminal; --quiet hides it, --progress\n"
    "draws it anyway (e.g. into a log).\n"
    MACROCON_HELP_NUMBERING;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

io::LoadedMesh load(const ArgParser& p, const std::string& file_key, const std::string& range_key,
                    OrientationRule orientation = OrientationRule::outward) {
  io::MeshFileOptions options;
  options.orientation = orientation;
  if (p.has(range_key)) parse_range(range_key, p.get(range_key), options.face_begin, options.face_end);
  return io::read_mesh(p.required(file_key), options);
}

Patch cut(const io::LoadedMesh& mesh, long file_vertex, double radius, const std::string& what) {
  const int center = io::mesh_vertex_of_file_vertex(mesh, file_vertex, what);
  require(std::isfinite(radius) && radius > 0, MCON_ERROR_INVALID_ARGUMENT, "radii must be > 0");
  PatchOptions options;
  options.center.vertex = center;
  options.radius = radius;
  return extract_geodesic_disk(mesh.mesh, options);
}

// The patch vertex at host vertex h (a patch vertex that is a host vertex links {h, h}; cut
// crossings lie strictly inside an edge), or -1 if the patch does not contain it.
int patch_vertex_at(const Patch& patch, int h) {
  for (std::size_t v = 0; v < patch.host_vertex.size(); ++v)
    if (patch.host_vertex[v].v0 == h && patch.host_vertex[v].v1 == h) return static_cast<int>(v);
  return -1;
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

// The patch vertex of file vertex `file_vertex` of `mesh`, or an error naming the landmark.
int landmark_vertex(const io::LoadedMesh& mesh, const Patch& patch, long file_vertex, const char* side) {
  const bool known = file_vertex >= 0 && file_vertex < static_cast<long>(mesh.file_to_mesh.size()) &&
                     mesh.file_to_mesh[static_cast<std::size_t>(file_vertex)] >= 0;
  const int v = known ? patch_vertex_at(patch, mesh.file_to_mesh[static_cast<std::size_t>(file_vertex)]) : -1;
  require(v >= 0, MCON_ERROR_INVALID_ARGUMENT,
          std::string("--landmarks: ") + side + " vertex " + std::to_string(file_vertex) + " is not a vertex of the " +
              side + " patch");
  return v;
}

// An already-cut, normalized patch: centered at the vertex nearest to its area-weighted centroid
// (the center of a geodesic disk is near its centroid unless the disk is very curved; the vertex,
// not the centroid itself, so the center is a point of the surface).
Patch as_entry(const TriMesh& mesh) {
  Vec3 centroid = Vec3::Zero();
  double area = 0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tri = mesh.triangles[t];
    const double a = triangle_area(mesh, t);
    centroid += a * (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0;
    area += a;
  }
  centroid /= area;
  int best = 0;
  for (int v = 1; v < mesh.num_vertices(); ++v)
    if ((mesh.positions[v] - centroid).squaredNorm() < (mesh.positions[best] - centroid).squaredNorm()) best = v;
  PatchFrame frame;
  for (int t = 0; t < mesh.num_triangles() && frame.center.triangle < 0; ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] == best) {
        frame.center.triangle = t;
        frame.center.barycentric = Vec3::Zero();
        frame.center.barycentric[k] = 1.0;
      }
  return patch_from_mesh(mesh, frame);
}

void write_polylines_obj(const std::string& path, const std::vector<std::vector<Vec3>>& lines,
                         const std::vector<bool>& closed) {
  std::ostringstream s;
  s.precision(9);
  s << "# macrocon embed: polylines as OBJ lines\n";
  for (const auto& line : lines)
    for (const Vec3& x : line) s << "v " << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
  std::size_t first = 1;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    s << 'l';
    for (std::size_t k = 0; k < lines[i].size(); ++k) s << ' ' << first + k;
    if (closed[i]) s << ' ' << first;
    s << '\n';
    first += lines[i].size();
  }
  io::write_file_maybe_gz(path, s.str());
}

// The checked options of embed that the stages read.
struct EmbedOptions {
  std::string out_dir;
  long samples = 0, iterations = 0, seed = 0;
  std::string orientation;
  std::optional<Vec3> source_up, target_up;
  bool cut_guides = false;
  GuideCutOptions cut;
};

// "X,Y,Z" as a vector of three finite numbers.
Vec3 parse_vec3(const std::string& key, const std::string& s) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (std::size_t comma; (comma = s.find(',', begin)) != std::string::npos; begin = comma + 1)
    parts.push_back(s.substr(begin, comma - begin));
  parts.push_back(s.substr(begin));
  require(parts.size() == 3, MCON_ERROR_INVALID_ARGUMENT, "--" + key + " expects X,Y,Z (three numbers), got '" + s + "'");
  Vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = ArgParser::parse_number(key, parts[static_cast<std::size_t>(k)]);
  return v;
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
  require(p.has("source-up") == p.has("target-up"), MCON_ERROR_INVALID_ARGUMENT,
          "--source-up and --target-up go together (or give --up for both)");
  if (p.has("up")) o.source_up = o.target_up = parse_vec3("up", p.get("up"));
  if (p.has("source-up")) {
    o.source_up = parse_vec3("source-up", p.get("source-up"));
    o.target_up = parse_vec3("target-up", p.get("target-up"));
  }
  o.cut_guides = p.flag("cut-guides");
  require(o.cut_guides || !p.has("snap"), MCON_ERROR_INVALID_ARGUMENT, "--snap needs --cut-guides");
  o.cut.snap_fraction = p.number("snap", o.cut.snap_fraction);
  require(o.cut.snap_fraction >= 0 && o.cut.snap_fraction <= 0.45, MCON_ERROR_INVALID_ARGUMENT,
          "--snap must be in [0, 0.45] (a fraction of an edge length)");
  return o;
}

// 1. Patches.
struct EmbedPatches {
  io::LoadedMesh target_mesh, source_mesh;
  Patch target, source;
  std::optional<MacroConstraint> entry;  // --entry: the library entry that is the source
};

// The entry --entry names: a number is an id, anything else a name (which must be unique).
MacroConstraint find_library_entry(const std::string& path, const std::string& which) {
  const ConstraintLibrary lib = load_library_from_file(path);
  const bool numeric = !which.empty() && which.find_first_not_of("0123456789") == std::string::npos;
  errno = 0;
  const unsigned long long id = numeric ? std::strtoull(which.c_str(), nullptr, 10) : 0;
  const MacroConstraint* found = numeric && errno != ERANGE ? lib.find_entry(id) : nullptr;
  std::size_t named = 0;
  if (!numeric)
    for (const MacroConstraint& e : lib.entries())
      if (e.name == which) {
        found = &e;
        ++named;
      }
  require(named <= 1, MCON_ERROR_INVALID_ARGUMENT,
          "--entry '" + printable_text(which) + "': " + std::to_string(named) + " entries of '" + path +
              "' have that name; give the id (macrocon library info lists them)");
  require(found != nullptr, MCON_ERROR_NOT_FOUND,
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
  e.entry = find_library_entry(p.required("source"), p.get("entry"));
  PatchFrame frame;
  frame.center = e.entry->center;
  frame.origin = Vec3(e.entry->source_origin[0], e.entry->source_origin[1], e.entry->source_origin[2]);
  frame.scale = e.entry->source_scale;
  e.source_mesh.mesh = entry_mesh(*e.entry);
  e.source = patch_from_mesh(e.source_mesh.mesh, frame);
  for (int v = 0; v < e.source_mesh.mesh.num_vertices(); ++v) {
    e.source_mesh.file_to_mesh.push_back(v);
    e.source_mesh.mesh_to_file.push_back(v);
  }
}

EmbedPatches cut_embed_patches(const ArgParser& p) {
  EmbedPatches e;
  e.target_mesh = load(p, "target", "face-range");
  e.target = cut(e.target_mesh, p.integer("center-vertex", -1), p.number("radius", 0), "--center-vertex");
  if (p.has("entry")) {
    entry_source(p, e);
    return e;
  }
  const bool cut_source = p.has("source-center-vertex");
  // A source that is already a patch is oriented like mcon_patch_create_from_arrays (majority).
  e.source_mesh =
      load(p, "source", "source-face-range", cut_source ? OrientationRule::outward : OrientationRule::majority);
  require(cut_source || !p.has("source-radius"), MCON_ERROR_INVALID_ARGUMENT,
          "--source-radius needs --source-center-vertex");
  if (cut_source) {
    e.source = cut(e.source_mesh, p.integer("source-center-vertex", -1), p.number("source-radius", p.number("radius", 0)),
                   "--source-center-vertex");
    return e;
  }
  try {
    e.source = as_entry(e.source_mesh.mesh);
  } catch (const Error& err) {
    // A whole mesh given as --source (a closed head, a body) is the usual slip: say what to add.
    if (err.status() != MCON_ERROR_NOT_A_DISK) throw;
    fail(MCON_ERROR_NOT_A_DISK, "--source '" + p.get("source", "") + "' is not a disk patch (" + err.what() +
                                    "): give --source-center-vertex M (and --source-radius Q) to cut one out of it");
  }
  return e;
}

// 2. The map.
struct EmbedMap {
  std::size_t landmarks = 0;
  SurfaceMap map;
  double map_seconds = 0;
  int flips = 0;
};

EmbedMap map_embed_patches(const ArgParser& p, const EmbedOptions& o, const EmbedPatches& e) {
  const Patch& source = e.source;
  const Patch& target = e.target;
  PatchMapOptions options;
  options.map.alignment.samples = static_cast<int>(o.samples);
  options.map.alignment.seed = static_cast<std::uint64_t>(o.seed);
  options.map.newton.max_iterations = static_cast<int>(o.iterations);
  options.map.orientation = o.orientation == "preserve"  ? MapOrientation::preserve
                            : o.orientation == "reverse" ? MapOrientation::reverse
                                                         : MapOrientation::automatic;
  options.source_up = o.source_up;
  options.target_up = o.target_up;
  // Landmarks: one guidance column per pair, the geodesic distance from it on each patch.
  const std::vector<std::pair<long, long>> landmarks =
      p.has("landmarks") ? parse_landmarks(p.get("landmarks")) : std::vector<std::pair<long, long>>{};
  Eigen::MatrixXd source_guidance(source.mesh.num_vertices(), static_cast<Eigen::Index>(landmarks.size()));
  Eigen::MatrixXd target_guidance(target.mesh.num_vertices(), static_cast<Eigen::Index>(landmarks.size()));
  if (!landmarks.empty()) {
    const HeatGeodesics source_heat(source.mesh), target_heat(target.mesh);
    for (std::size_t k = 0; k < landmarks.size(); ++k) {
      source_guidance.col(static_cast<Eigen::Index>(k)) =
          source_heat.from_vertices({landmark_vertex(e.source_mesh, source, landmarks[k].first, "source")});
      target_guidance.col(static_cast<Eigen::Index>(k)) =
          target_heat.from_vertices({landmark_vertex(e.target_mesh, target, landmarks[k].second, "target")});
    }
    options.source_guidance = &source_guidance;
    options.target_guidance = &target_guidance;
  }
  EmbedMap m;
  m.landmarks = landmarks.size();
  ProgressBar bar("map", progress_wanted(p));
  options.map.progress = bar.callback();
  const auto t_map = std::chrono::steady_clock::now();
  m.map = map_patches(source, target, options);
  bar.finish();
  m.map_seconds = seconds_since(t_map);
  m.flips = count_phi_flips(source.mesh, m.map.phi, m.map.reflected);
  return m;
}

// 3. and 4.: the source constraints, transferred, and the target's cross field.
struct EmbedTransfer {
  SourceConstraints source;
  std::vector<NamedField> fields;  // on the target's vertices
  std::vector<std::uint8_t> outside;
  std::vector<TracedPolyline> traced;
  std::vector<SurfacePoint> singularities;  // on the target (triangle -1: outside the map)
  SurfacePoint center_on_target;
  CrossField field;
  double source_field_seconds = 0, field_seconds = 0, polyline_seconds = 0, cross_field_seconds = 0,
         transfer_seconds = 0;
};

EmbedTransfer transfer_constraints(const MapView& view, const EmbedPatches& e) {
  const Patch& source = e.source;
  const Patch& target = e.target;
  EmbedTransfer x;
  // 3. Source constraints: the entry's own, or synthetic ones that show the map.
  const auto t_transfer = std::chrono::steady_clock::now();
  x.source = e.entry ? entry_constraints(*e.entry) : synthetic_constraints(source);
  x.source_field_seconds = seconds_since(t_transfer);
  const auto t_fields = std::chrono::steady_clock::now();
  x.fields = transfer_fields(view, x.source.fields);
  x.outside = outside_mask(view);
  x.field_seconds = seconds_since(t_fields);
  const auto t_polylines = std::chrono::steady_clock::now();
  const PolylineTransfer transfer(view);
  x.traced = transfer.map_polylines(x.source.polylines);
  x.center_on_target = transfer.map_point({source.center.triangle, source.center.barycentric});
  for (const Singularity& s : x.source.singularities) x.singularities.push_back(transfer.map_point(s.location));

  x.polyline_seconds = seconds_since(t_polylines);
  const auto t_field = std::chrono::steady_clock::now();
  // 4. Cross field of the target following the re-traced guides and features.
  std::vector<std::vector<SurfacePoint>> guide_points;
  for (const TracedPolyline& t : x.traced) {
    std::vector<SurfacePoint> line;
    for (const SurfacePoint& q : t.points) line.push_back({q.triangle, q.barycentric});
    if (t.closed) line.push_back(line.front());
    guide_points.push_back(std::move(line));
  }
  x.field = compute_cross_field(target.mesh, constraints_from_polylines(target.mesh, guide_points));
  x.cross_field_seconds = seconds_since(t_field);
  x.transfer_seconds = seconds_since(t_transfer);
  return x;
}

// 5. Files (target mesh units: host = center + radius * p).
struct EmbedFiles {
  std::string ply, obj, features_obj, src_obj, rosy, singularities_csv, summary_path;
  std::size_t traced_points = 0;
};

Vec3 to_host(const Patch& patch, const Vec3& x) { return Vec3(patch.center_position + patch.radius * x); }

// The target patch in host units with the transferred per-vertex fields.
void write_target_ply(const std::string& ply, const EmbedPatches& e, const EmbedTransfer& x) {
  const Patch& target = e.target;
  TriMesh target_host = target.mesh;
  for (Vec3& v : target_host.positions) v = to_host(target, v);
  std::vector<io::VertexAttribute> attributes = field_attributes(x.fields);
  io::VertexAttribute out_attr{"outside", 1, {}}, host_vertex{"host_vertex", 1, {}};
  for (int w = 0; w < target.mesh.num_vertices(); ++w) {
    out_attr.values.push_back(x.outside[w]);
    const HostPoint& hp = target.host_vertex[w];
    host_vertex.values.push_back(hp.v0 < 0 ? -1.0 : static_cast<double>(e.target_mesh.mesh_to_file[hp.t < 0.5 ? hp.v0 : hp.v1]));
  }
  attributes.push_back(std::move(out_attr));
  attributes.push_back(std::move(host_vertex));
  io::write_ply(ply, target_host, attributes);
  // The same triangles as OBJ with exact doubles (QuadWild reads OBJ), next to the PLY.
  io::write_obj(ply.substr(0, ply.size() - 4) + ".obj", target_host);
}

// The mapped singularities as the table `library build --singularities` reads (x, y, z, index in
// target mesh units); those the map sends outside the target are left out (the summary counts them).
void write_singularities_csv(const std::string& path, const EmbedPatches& e, const EmbedTransfer& x) {
  std::ostringstream s;
  s.precision(17);
  s << "x,y,z,index\n";
  for (std::size_t i = 0; i < x.singularities.size(); ++i) {
    if (!x.singularities[i].valid()) continue;
    const Vec3 p = to_host(e.target, position_on(e.target.mesh, x.singularities[i]));
    s << p.x() << ',' << p.y() << ',' << p.z() << ',' << x.source.singularities[i].index_quarters << '\n';
  }
  io::write_file_maybe_gz(path, s.str());
}

EmbedFiles write_embed_files(const std::string& out_dir, const EmbedPatches& e, const EmbedTransfer& x) {
  const Patch& target = e.target;
  const Patch& source = e.source;
  std::filesystem::create_directories(out_dir);
  EmbedFiles f;
  f.ply = out_dir + "/target.ply";
  f.obj = out_dir + "/guides.obj";
  f.src_obj = out_dir + "/source_guides.obj";
  f.rosy = out_dir + "/target.rosy";
  f.summary_path = out_dir + "/summary.json";
  write_target_ply(f.ply, e, x);
  // Traced guides and traced features go to their own files; the source's all to one.
  std::vector<std::vector<Vec3>> lines[2], source_lines;
  std::vector<bool> closed[2], source_closed;
  for (const TracedPolyline& t : x.traced) {
    const int feature = static_cast<std::size_t>(t.input) >= x.source.guide_count ? 1 : 0;
    std::vector<Vec3> line;
    for (const Vec3& v : t.positions) line.push_back(to_host(target, v));
    lines[feature].push_back(std::move(line));
    closed[feature].push_back(t.closed);
    f.traced_points += t.points.size();
  }
  for (const PolylineInput& in : x.source.polylines) {
    std::vector<Vec3> line;
    for (const SurfacePoint& q : in.points) line.push_back(to_host(source, position_on(source.mesh, q)));
    source_lines.push_back(std::move(line));
    source_closed.push_back(in.closed);
  }
  write_polylines_obj(f.obj, lines[0], closed[0]);
  if (x.source.polylines.size() > x.source.guide_count) {
    f.features_obj = out_dir + "/features.obj";
    write_polylines_obj(f.features_obj, lines[1], closed[1]);
  }
  write_polylines_obj(f.src_obj, source_lines, source_closed);
  if (!x.source.singularities.empty()) {
    f.singularities_csv = out_dir + "/singularities.csv";
    write_singularities_csv(f.singularities_csv, e, x);
  }
  io::write_rosy(f.rosy, target.mesh, x.field.directions);
  return f;
}

// 5b. With --cut-guides: the guides cut into the target patch, its fields, cross field and files.
struct EmbedCut {
  CutMesh cut;
  CrossField field;
  std::string obj, ply, sharp, rosy, guides;
  double seconds = 0;
};

EmbedCut cut_and_write(const EmbedOptions& o, const EmbedPatches& e, const EmbedTransfer& x) {
  const auto t0 = std::chrono::steady_clock::now();
  const Patch& target = e.target;
  std::vector<std::vector<SurfacePoint>> guides;
  std::vector<bool> closed;
  for (const TracedPolyline& t : x.traced) {
    guides.push_back(t.points);
    closed.push_back(t.closed);
  }
  EmbedCut c;
  c.cut = cut_guides_into_mesh(target.mesh, guides, closed, o.cut);
  const TriMesh& mesh = c.cut.mesh;
  c.field = compute_cross_field(mesh, constraints_from_edges(mesh, c.cut.guide_edges));
  align_field_to_edges(mesh, c.cut.guide_edges, c.field);
  c.seconds = seconds_since(t0);

  std::vector<io::VertexAttribute> attributes = field_attributes(carry_fields(c.cut, target.mesh, x.fields));
  const std::vector<std::uint8_t> outside = carry_labels(c.cut, target.mesh, x.outside);
  TriMesh host_units = mesh;
  for (Vec3& v : host_units.positions) v = to_host(target, v);
  io::VertexAttribute out_attr{"outside", 1, {}}, guide{"guide", 1, {}};
  std::vector<double> on_guide(mesh.positions.size(), 0.0);
  for (const auto& edge : c.cut.guide_edges) on_guide[edge[0]] = on_guide[edge[1]] = 1.0;
  for (int w = 0; w < mesh.num_vertices(); ++w) {
    out_attr.values.push_back(outside[w]);
    guide.values.push_back(on_guide[w]);
  }
  attributes.push_back(std::move(out_attr));
  attributes.push_back(std::move(guide));
  c.obj = o.out_dir + "/target_cut.obj";
  c.ply = o.out_dir + "/target_cut.ply";
  c.sharp = o.out_dir + "/target_cut.sharp";
  c.rosy = o.out_dir + "/target_cut.rosy";
  io::write_obj(c.obj, host_units);
  io::write_ply(c.ply, host_units, attributes);
  io::write_sharp(c.sharp, host_units, c.cut.guide_edges);
  io::write_rosy(c.rosy, host_units, c.field.directions);
  // The cut guides as OBJ lines through the cut mesh's own vertices (same numbering as target_cut.obj).
  c.guides = o.out_dir + "/target_cut_guides.obj";
  // 17 digits: the vertices read back as target_cut.obj's (std::to_string would keep 6 decimals).
  std::ostringstream lines;
  lines.precision(17);
  lines << "# macrocon embed: the guides as chains of target_cut.obj's edges\n";
  for (const Vec3& v : host_units.positions) lines << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const std::vector<int>& chain : c.cut.guides) {
    if (chain.size() < 2) continue;
    lines << 'l';
    for (int v : chain) lines << ' ' << v + 1;
    lines << '\n';
  }
  io::write_file_maybe_gz(c.guides, lines.str());
  return c;
}

// Turning angle per unit length (normalized patch units), the mean over guides with >= 3 points.
double mean_turning(const std::vector<std::vector<Vec3>>& lines, const std::vector<bool>& closed) {
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].size() >= 3) {
      sum += turning_per_length(lines[i], closed[i]);
      ++count;
    }
  return count > 0 ? sum / count : 0.0;
}

tools::Json turning_summary(const EmbedPatches& e, const EmbedTransfer& x, const EmbedCut* c) {
  std::vector<std::vector<Vec3>> source, traced, cut;
  std::vector<bool> source_closed, traced_closed, cut_closed;
  for (const PolylineInput& in : x.source.polylines) {
    std::vector<Vec3> line;
    for (const SurfacePoint& q : in.points) line.push_back(position_on(e.source.mesh, q));
    source.push_back(std::move(line));
    source_closed.push_back(in.closed);
  }
  for (const TracedPolyline& t : x.traced) {
    traced.push_back(t.positions);
    traced_closed.push_back(t.closed);
  }
  tools::Json j = tools::Json::object();
  // In host units (per unit length of the mesh files), so patches of different radii compare.
  const double s = mean_turning(source, source_closed) / e.source.radius,
               t = mean_turning(traced, traced_closed) / e.target.radius;
  j.set("source", s);
  j.set("traced", t);
  j.set("traced_ratio", s > 0 ? t / s : 0.0);
  if (c) {
    for (const std::vector<int>& chain : c->cut.guides) {
      std::vector<Vec3> line;
      for (int v : chain) line.push_back(c->cut.mesh.positions[v]);
      // A closed chain repeats its first vertex: drop it and measure it closed.
      const bool is_closed = chain.size() > 2 && chain.front() == chain.back();
      if (is_closed) line.pop_back();
      cut.push_back(std::move(line));
      cut_closed.push_back(is_closed);
    }
    const double k = mean_turning(cut, cut_closed) / e.target.radius;
    j.set("cut", k);
    j.set("cut_ratio", s > 0 ? k / s : 0.0);
  }
  return j;
}

tools::Json cut_summary(const EmbedCut& c) {
  tools::Json j = tools::Json::object();
  j.set("vertices", c.cut.mesh.num_vertices());
  j.set("triangles", c.cut.mesh.num_triangles());
  j.set("guide_edges", c.cut.guide_edges.size());
  j.set("input_triangles_cut", c.cut.input_triangles_cut);
  j.set("min_angle_created_degrees", c.cut.min_angle_created);
  j.set("min_angle_of_cut_input_degrees", c.cut.min_angle_of_cut_input);
  j.set("snapped_to_vertices", c.cut.snapped_to_vertices);
  j.set("merged_crossings", c.cut.merged_crossings);
  j.set("dropped_points", c.cut.dropped_points);
  j.set("shortcuts", c.cut.shortcuts);
  j.set("moved_vertices", c.cut.moved_vertices);
  j.set("seconds", c.seconds);
  return j;
}

// Where the constraints came from, the fields transferred and where each singularity landed.
tools::Json source_summary(const EmbedPatches& e, const EmbedTransfer& x) {
  using tools::Json;
  Json j = Json::object();
  j.set("kind", e.entry ? "library_entry" : "mesh (synthetic constraints)");
  if (e.entry) {
    j.set("entry_id", std::to_string(e.entry->id));
    j.set("entry_name", e.entry->name);
    j.set("entry_class", e.entry->class_label);
  }
  Json fields = Json::array();
  for (const NamedField& f : x.fields) fields.push_back(f.name);
  j.set("fields", fields);
  Json singularities = Json::array();
  for (std::size_t i = 0; i < x.singularities.size(); ++i) {
    Json s = Json::object();
    s.set("index_quarters", x.source.singularities[i].index_quarters);
    s.set("on_target", x.singularities[i].valid());
    if (x.singularities[i].valid()) {
      const Vec3 p = to_host(e.target, position_on(e.target.mesh, x.singularities[i]));
      Json xyz = Json::array();
      for (int k = 0; k < 3; ++k) xyz.push_back(p[k]);
      s.set("position", xyz);
    }
    singularities.push_back(s);
  }
  j.set("singularities", singularities);
  return j;
}

// 6. Summary.
tools::Json embed_summary(const EmbedOptions& o, const EmbedPatches& e, const EmbedMap& m, const EmbedTransfer& x,
                          const EmbedFiles& f, double patch_seconds, std::chrono::steady_clock::time_point t_start) {
  using tools::Json;
  const SurfaceMap& map = m.map;
  std::size_t source_inside = 0, target_inside = 0;
  for (const SurfacePoint& q : map.source_to_target) source_inside += q.triangle >= 0;
  for (std::uint8_t out : x.outside) target_inside += out == 0;
  Json energies = Json::object();
  energies.set("total", map.energy.total);
  for (std::size_t i = 0; i < map_energy_terms().size(); ++i)
    energies.set(map_energy_terms()[i].name, map.energy.values[i]);
  Json timings = Json::object();
  timings.set("patches", patch_seconds);
  timings.set("map", m.map_seconds);
  timings.set("alignment", map.alignment_seconds);
  timings.set("optimization", map.optimization_seconds);
  timings.set("transfer", x.transfer_seconds);  // the next four together
  timings.set("source_constraints", x.source_field_seconds);
  timings.set("fields", x.field_seconds);
  timings.set("polylines", x.polyline_seconds);
  timings.set("cross_field", x.cross_field_seconds);
  timings.set("total", seconds_since(t_start));
  Json files = Json::object();
  files.set("target_ply", f.ply);
  files.set("target_obj", f.ply.substr(0, f.ply.size() - 4) + ".obj");
  files.set("guides_obj", f.obj);
  files.set("source_guides_obj", f.src_obj);
  if (!f.features_obj.empty()) files.set("features_obj", f.features_obj);
  if (!f.singularities_csv.empty()) files.set("singularities_csv", f.singularities_csv);
  files.set("rosy", f.rosy);
  Json summary = Json::object();
  summary.set("source_vertices", e.source.mesh.num_vertices());
  summary.set("target_vertices", e.target.mesh.num_vertices());
  summary.set("source_vertices_inside", source_inside);
  summary.set("target_vertices_inside", target_inside);
  summary.set("overlap", map.overlap_ratio);
  summary.set("matching_score", map.matching_score);
  summary.set("alignment_score", map.alignment.score);
  summary.set("energies", energies);
  summary.set("iterations", map.iterations);
  summary.set("levels", static_cast<int>(map.levels.size()));
  summary.set("stop_reason", stop_reason_name(map.stop_reason));
  summary.set("reflected", map.reflected);
  // The evidence of the orientation call, for a host that offers a "flip" (--orientation).
  summary.set("orientation", o.orientation);
  summary.set("landmarks", static_cast<double>(m.landmarks));
  summary.set("up_hints", o.source_up.has_value());
  summary.set("alignment_score_unreflected", map.alignment.score_unreflected);
  summary.set("alignment_score_reflected", map.alignment.score_reflected);
  summary.set("orientation_compared", map.orientation_compared);
  summary.set("level0_energy_unreflected", map.level0_energy_unreflected);
  summary.set("level0_energy_reflected", map.level0_energy_reflected);
  summary.set("flips", m.flips);
  std::size_t features_out = 0;
  for (const TracedPolyline& t : x.traced) features_out += static_cast<std::size_t>(t.input) >= x.source.guide_count;
  summary.set("guides_in", x.source.guide_count);
  summary.set("guides_out", x.traced.size() - features_out);
  summary.set("features_in", x.source.polylines.size() - x.source.guide_count);
  summary.set("features_out", features_out);
  summary.set("source_constraints", source_summary(e, x));
  summary.set("guide_points_out", f.traced_points);
  summary.set("center_on_target", x.center_on_target.triangle >= 0);
  summary.set("timings", timings);
  summary.set("files", files);
  return summary;
}

int run_embed(const Args& args) {
  const ArgParser p(args,
                    {"source", "target", "center-vertex", "radius", "source-center-vertex", "source-radius",
                     "face-range", "source-face-range", "seed", "samples", "iterations", "orientation", "landmarks",
                     "up", "source-up", "target-up", "out", "snap", "entry"},
                    {"json", "cut-guides", "quiet", "progress"}, kUsage);
  const auto t_start = std::chrono::steady_clock::now();
  const EmbedOptions o = embed_options(p);
  const EmbedPatches e = cut_embed_patches(p);
  const double patch_seconds = seconds_since(t_start);
  const EmbedMap m = map_embed_patches(p, o, e);
  const SurfaceMap& map = m.map;
  const MapView view{e.source.mesh, e.source.uv, e.target.mesh, e.target.uv, map.phi, map.source_to_target, map.target_to_source};
  const EmbedTransfer x = transfer_constraints(view, e);
  const EmbedFiles f = write_embed_files(o.out_dir, e, x);
  std::optional<EmbedCut> cut;
  if (o.cut_guides) cut = cut_and_write(o, e, x);
  tools::Json summary = embed_summary(o, e, m, x, f, patch_seconds, t_start);
  summary.set("guide_turning", turning_summary(e, x, cut ? &*cut : nullptr));
  if (cut) {
    summary.set("cut", cut_summary(*cut));
    tools::Json files = summary.at("files");
    files.set("cut_obj", cut->obj);
    files.set("cut_ply", cut->ply);
    files.set("cut_sharp", cut->sharp);
    files.set("cut_rosy", cut->rosy);
    files.set("cut_guides_obj", cut->guides);
    summary.set("files", files);
    // QuadWild's command lines for the cut patch (run in the output folder; <quadwild> is its build).
    tools::Json commands = tools::Json::array();
    commands.push_back(std::string("quadwild target_cut.obj 2 target_cut.rosy target_cut.sharp "
                                   "<quadwild>/config/prep_config/basic_setup.txt"));
    commands.push_back(std::string("quad_from_patches target_cut_rem_p0.obj 123 "
                                   "<quadwild>/config/main_config/flow_noalign_lemon.txt"));
    summary.set("quadwild_commands", commands);
  }
  tools::write_json_file(f.summary_path, summary);
  if (p.flag("json")) {
    std::printf("%s\n", tools::write_json(summary, false).c_str());
  } else {
    std::printf("map: %d -> %d vertices, overlap %.3f, %d iterations (%s), %s, %d flips, %.2f s\n",
                e.source.mesh.num_vertices(), e.target.mesh.num_vertices(), map.overlap_ratio, map.iterations,
                stop_reason_name(map.stop_reason), map.reflected ? "reflected" : "not reflected", m.flips,
                m.map_seconds);
    std::printf("constraints: %zu guides and features in, %zu out (%zu points), %zu singularities, %zu fields; files in %s\n",
                x.source.polylines.size(), x.traced.size(), f.traced_points, x.singularities.size(), x.fields.size(),
                o.out_dir.c_str());
    if (cut)
      std::printf("cut: %d vertices, %d triangles, %zu guide edges, smallest angle made %.1f degrees\n",
                  cut->cut.mesh.num_vertices(), cut->cut.mesh.num_triangles(), cut->cut.guide_edges.size(),
                  cut->cut.min_angle_created);
  }
  return m.flips == 0 ? 0 : 1;
}

const Registration registration{"embed", "re-embed a source patch onto a target region and transfer its constraints",
                                run_embed};

}  // namespace
}  // namespace mcon::cli
