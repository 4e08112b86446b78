// Builds the starter constraint library from its text source (samples/starter-library/entries.json)
// and the bundled MakeHuman body, through the SDK's public C API only (macrocon.h): the same calls
// a vendor makes to build their own library. Run by CMake at build time; nothing binary is
// committed.
//
//   build_starter_library ENTRIES.json MODEL_DIR OUT.mclb
//
// For each entry: cut the geodesic disk (mcon_patch_extract), compute procedural example
// constraints and fields on the patch's arrays (procedural.h), add it (mcon_library_add_entry).
// Then build the retrieval vocabulary (mcon_library_build_retrieval) and save atomically.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>


#include "json/json.h"
#include "macrocon/macrocon.h"
#include "procedural.h"
#include "sample_mesh.h"

namespace {

const double kPi = 3.14159265358979323846;

// Throws with the SDK's message for anything but MCON_OK.
void check(mcon_status status, const std::string& what) {
  if (status == MCON_OK) return;
  const char* message = nullptr;
  const char* name = nullptr;
  mcon_get_last_error(nullptr, &message);
  mcon_get_status_name(status, &name);
  throw std::runtime_error(what + ": " + (name ? name : "?") + ": " + (message ? message : ""));
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Field {
  std::string name;
  mcon_field_kind kind;
  std::uint32_t dimension;
  std::vector<double> values;
  std::vector<std::int32_t> labels;
};

double smoothstep(double e0, double e1, double x) {
  const double t = std::min(1.0, std::max(0.0, (x - e0) / (e1 - e0)));
  return t * t * (3 - 2 * t);
}

// HSV (h in turns) -> RGB in [0, 1].
std::array<double, 3> hsv(double h, double s, double v) {
  h = h - std::floor(h);
  const double i = std::floor(h * 6), f = h * 6 - i;
  const double p = v * (1 - s), q = v * (1 - f * s), t = v * (1 - (1 - f) * s);
  switch (static_cast<int>(i) % 6) {
    case 0: return {v, t, p};
    case 1: return {q, v, p};
    case 2: return {p, v, t};
    case 3: return {p, q, v};
    case 4: return {t, p, v};
    default: return {v, p, q};
  }
}

// The per-vertex example fields: uv, geodesic distance, skin weights (a partition of unity), a
// colour and a region label. The angle is measured in the uv disk around the center's image.
std::vector<Field> example_fields(const starter::Geometry& g, const std::vector<double>& d) {
  const std::size_t n = g.nv();
  std::array<double, 2> cuv{{0, 0}};
  for (int k = 0; k < 3; ++k) {
    const std::size_t v = g.t[3 * g.center_face + static_cast<std::size_t>(k)];
    cuv[0] += g.center_bary[k] * g.uv[2 * v];
    cuv[1] += g.center_bary[k] * g.uv[2 * v + 1];
  }
  Field uv{"uv", MCON_FIELD_UV, 2, g.uv, {}};
  Field geo{"geodesic_distance", MCON_FIELD_SCALAR, 1, d, {}};
  Field wc{"skin_weight_center", MCON_FIELD_SCALAR, 1, {}, {}};
  Field w[3] = {{"skin_weight_0", MCON_FIELD_SCALAR, 1, {}, {}},
                {"skin_weight_1", MCON_FIELD_SCALAR, 1, {}, {}},
                {"skin_weight_2", MCON_FIELD_SCALAR, 1, {}, {}}};
  Field color{"color", MCON_FIELD_VECTOR3, 3, {}, {}};
  Field region{"region", MCON_FIELD_INTEGER_LABEL, 1, {}, {}};
  for (std::size_t v = 0; v < n; ++v) {
    const double angle = std::atan2(g.uv[2 * v + 1] - cuv[1], g.uv[2 * v] - cuv[0]);
    // A bump of 1 at the center falling to 0 at distance 0.6; the rest is shared by three
    // sectors with softmax-like weights exp(2 cos(angle - phi_k)), so the four sum to 1.
    const double c = 1 - smoothstep(0.0, 0.6, d[v]);
    double s[3], total = 0;
    for (int k = 0; k < 3; ++k) total += s[k] = std::exp(2 * std::cos(angle - 2 * kPi * k / 3));
    wc.values.push_back(c);
    for (int k = 0; k < 3; ++k) w[k].values.push_back((1 - c) * s[k] / total);
    const auto rgb = hsv(angle / (2 * kPi), 0.8, 1 - 0.6 * std::min(1.0, d[v]));
    color.values.insert(color.values.end(), rgb.begin(), rgb.end());
    int sector = static_cast<int>(std::floor((angle + kPi) / (2 * kPi / 3)));
    sector = std::min(2, std::max(0, sector));
    region.labels.push_back(sector + (d[v] > 0.5 ? 3 : 0));
  }
  return {uv, geo, wc, w[0], w[1], w[2], color, region};
}

struct Constraints {
  std::vector<starter::Polyline> guides, features;
  std::vector<mcon_singularity> singularities;
};

mcon_singularity singularity(const starter::SurfacePoint& p, int index) {
  mcon_singularity s{};
  s.location.face = p.face;
  for (int k = 0; k < 3; ++k) s.location.barycentric[k] = p.bary[k];
  s.index_quarters = index;
  return s;
}

Constraints example_constraints(const starter::Geometry& g, const std::vector<double>& d,
                                const mcon::tools::Json& spec, const std::string& name) {
  Constraints c;
  if (const auto* loops = spec.find("edge_loops")) {
    std::vector<starter::Polyline> rings;
    // "edge_loop_front": "+z" picks, per level, the closed loop lying furthest along +z (on the
    // face rather than inside the eye socket or the mouth cavity the patch also contains);
    // otherwise the longest closed loop (small loops are noise).
    const std::string front = spec.find("edge_loop_front") ? spec.at("edge_loop_front").as_string() : "";
    const int axis = front == "+x" ? 0 : front == "+y" ? 1 : front == "+z" ? 2 : -1;
    auto score = [&](const starter::Polyline& l) {
      if (axis < 0) return starter::length(g, l);
      double s = 0;
      for (const auto& sp : l.points) s += starter::point_position(g, sp)[static_cast<std::size_t>(axis)];
      return s / static_cast<double>(l.points.size());
    };
    for (const auto& level : loops->elements()) {
      const auto lines = starter::iso_lines(g, d, level.as_number());
      const starter::Polyline* best = nullptr;
      for (const auto& l : lines)
        if (l.closed && l.points.size() >= 6 && (best == nullptr || score(l) > score(*best))) best = &l;
      if (best == nullptr) throw std::runtime_error(name + ": no closed edge loop at level " + std::to_string(level.as_number()));
      rings.push_back(*best);
    }
    if (spec.find("corner_singularities") != nullptr && !rings.empty()) {
      const starter::Polyline& mid = rings[rings.size() / 2];
      std::size_t lo = 0, hi = 0;
      for (std::size_t i = 0; i < mid.points.size(); ++i) {
        const double x = starter::point_position(g, mid.points[i])[0];
        if (x < starter::point_position(g, mid.points[lo])[0]) lo = i;
        if (x > starter::point_position(g, mid.points[hi])[0]) hi = i;
      }
      c.singularities.push_back(singularity(mid.points[lo], -1));
      c.singularities.push_back(singularity(mid.points[hi], -1));
    }
    c.guides.insert(c.guides.end(), rings.begin(), rings.end());
  }
  if (const auto* fingers = spec.find("finger_flow_lines")) {
    const auto tips = starter::distance_maxima(g, d, fingers->at("min_distance").as_number(),
                                               fingers->at("separation").as_number(),
                                               static_cast<std::size_t>(fingers->at("count").as_number()));
    if (tips.empty()) throw std::runtime_error(name + ": no finger tips found");
    const auto vf = starter::vertex_faces(g);
    for (std::uint32_t tip : tips) {
      const auto path = starter::descend(g, d, tip, fingers->at("stop").as_number());
      if (path.size() < 2) continue;
      starter::Polyline pl;
      for (std::uint32_t v : path) pl.points.push_back(starter::vertex_point(g, vf, v));
      c.guides.push_back(pl);
      c.singularities.push_back(singularity(pl.points.front(), +1));
    }
  }
  if (const auto* section = spec.find("feature_section")) {
    const int axis = section->as_string() == "sagittal" ? 0 : section->as_string() == "transverse" ? 1 : -1;
    if (axis < 0) throw std::runtime_error(name + ": feature_section must be 'sagittal' or 'transverse'");
    std::vector<double> f(g.nv());
    for (std::size_t v = 0; v < g.nv(); ++v) f[v] = g.p[3 * v + static_cast<std::size_t>(axis)];
    for (auto& l : starter::iso_lines(g, f, g.center()[static_cast<std::size_t>(axis)]))
      if (l.points.size() >= 4 && starter::length(g, l) > 0.3) c.features.push_back(l);
    if (c.features.empty()) throw std::runtime_error(name + ": the section plane gives no feature line");
  }
  return c;
}

// The MakeHuman body as an SDK mesh.
void create_body_mesh(mcon_context ctx, const sample_mesh& body, const std::string& model, mcon_mesh* mesh) {
  mcon_mesh_desc desc;
  check(mcon_mesh_desc_init(&desc), "mcon_mesh_desc_init");
  desc.positions = body.positions;
  desc.position_type = MCON_SCALAR_FLOAT32;
  desc.vertex_count = body.vertex_count;
  desc.indices = body.indices;
  desc.triangle_count = body.triangle_count;
  check(mcon_mesh_create(ctx, &desc, mesh), "mcon_mesh_create(" + model + ")");
}

// The patch's arrays (positions, triangles, uv, center) read back through the C API.
starter::Geometry patch_geometry(mcon_patch patch, mcon_patch_info& info) {
  check(mcon_patch_info_init(&info), "mcon_patch_info_init");
  check(mcon_patch_get_info(patch, &info), "mcon_patch_get_info");
  starter::Geometry g;
  g.p.resize(3 * info.vertex_count);
  g.t.resize(3 * info.triangle_count);
  g.uv.resize(2 * info.vertex_count);
  check(mcon_patch_get_positions(patch, g.p.data(), g.p.size()), "mcon_patch_get_positions");
  check(mcon_patch_get_triangles(patch, g.t.data(), g.t.size()), "mcon_patch_get_triangles");
  check(mcon_patch_get_uv(patch, g.uv.data(), g.uv.size()), "mcon_patch_get_uv");
  g.center_face = info.center_patch_triangle;
  for (int k = 0; k < 3; ++k) g.center_bary[static_cast<std::size_t>(k)] = info.center_barycentric[k];
  return g;
}

// C views of the guides and features (points[i] holds polylines[i]'s points).
struct PolylineViews {
  std::vector<std::vector<mcon_surface_point>> points;
  std::vector<mcon_polyline> polylines;
};

PolylineViews polyline_views(const Constraints& c) {
  PolylineViews v;
  std::vector<std::vector<mcon_surface_point>>& points = v.points;
  std::vector<mcon_polyline>& polylines = v.polylines;
  auto add_polylines = [&](const std::vector<starter::Polyline>& list, mcon_polyline_kind kind) {
    for (const auto& pl : list) {
      std::vector<mcon_surface_point> pts;
      for (const auto& sp : pl.points) {
        mcon_surface_point q{};
        q.face = sp.face;
        for (int k = 0; k < 3; ++k) q.barycentric[k] = sp.bary[static_cast<std::size_t>(k)];
        pts.push_back(q);
      }
      points.push_back(std::move(pts));
      mcon_polyline l{};
      l.kind = kind;
      l.closed = pl.closed ? 1u : 0u;
      polylines.push_back(l);
    }
  };
  add_polylines(c.guides, MCON_POLYLINE_GUIDE);
  add_polylines(c.features, MCON_POLYLINE_FEATURE);
  for (std::size_t i = 0; i < polylines.size(); ++i) {
    polylines[i].points = points[i].data();
    polylines[i].point_count = points[i].size();
  }
  return v;
}

std::vector<mcon_vertex_field> field_views(const std::vector<Field>& fields) {
  std::vector<mcon_vertex_field> cfields;
  for (const Field& f : fields) {
    mcon_vertex_field cf{};
    cf.name = f.name.c_str();
    cf.kind = f.kind;
    cf.dimension = f.dimension;
    cf.values = f.values.empty() ? nullptr : f.values.data();
    cf.labels = f.labels.empty() ? nullptr : f.labels.data();
    cfields.push_back(cf);
  }
  return cfields;
}

// One entry of entries.json on an extracted patch: its procedural fields and constraints, added
// to the library (which copies everything), and its line of the build log.
void add_patch_entry(mcon_library library, mcon_patch patch, const mcon::tools::Json& e, const std::string& name,
                     const std::string& klass, const std::string& author, const std::string& licence,
                     const std::array<double, 3>* up) {
  mcon_patch_info info;
  const starter::Geometry g = patch_geometry(patch, info);

  const std::vector<double> d = starter::geodesic_distance(g);
  const std::vector<Field> fields = example_fields(g, d);
  const Constraints c = example_constraints(g, d, e.at("constraints"), name);

  // C views of everything (the library copies on add).
  PolylineViews views = polyline_views(c);
  std::vector<mcon_vertex_field> cfields = field_views(fields);
  std::vector<std::string> tags{"example", "makehuman", klass};
  if (const auto* extra = e.find("tags"))
    for (const auto& t : extra->elements()) tags.push_back(t.as_string());
  std::vector<const char*> ctags;
  for (const auto& t : tags) ctags.push_back(t.c_str());
  const std::string entry_name = name + " (MakeHuman body, procedural example constraints)";

  mcon_library_entry_desc ed;
  check(mcon_library_entry_desc_init(&ed), "mcon_library_entry_desc_init");
  ed.patch = patch;
  ed.id = static_cast<std::uint64_t>(e.at("id").as_number());
  ed.name = entry_name.c_str();
  ed.class_label = klass.c_str();
  ed.tags = ctags.data();
  ed.tag_count = ctags.size();
  ed.author = author.c_str();
  ed.licence = licence.c_str();
  ed.polylines = views.polylines.data();
  ed.polyline_count = views.polylines.size();
  ed.singularities = c.singularities.data();
  ed.singularity_count = c.singularities.size();
  ed.fields = cfields.data();
  ed.field_count = cfields.size();
  if (up != nullptr) {  // the body's up, for hosts that pass their own (mcon_map_options.target_up)
    ed.has_up = 1;
    for (int k = 0; k < 3; ++k) ed.up[k] = (*up)[k];
  }
  std::uint64_t id = 0;
  check(mcon_library_add_entry(library, &ed, &id), name + ": mcon_library_add_entry");
  std::printf("  %-7s id %2llu  class %-6s  %5zu vertices  %2zu guides  %zu features  %zu singularities  %zu fields\n",
              name.c_str(), static_cast<unsigned long long>(id), klass.c_str(), info.vertex_count,
              c.guides.size(), c.features.size(), c.singularities.size(), fields.size());
}

// An optional "up": [x, y, z] of entries.json (the SDK checks it is finite and not zero).
bool read_up(const mcon::tools::Json& object, std::array<double, 3>* up) {
  const mcon::tools::Json* value = object.find("up");
  if (value == nullptr) return false;
  const auto& xyz = value->elements();
  if (xyz.size() != 3) throw std::runtime_error("\"up\" must be [x, y, z]");
  for (int k = 0; k < 3; ++k) (*up)[k] = xyz[static_cast<std::size_t>(k)].as_number();
  return true;
}

// Cuts the entry's geodesic disk from the body and adds it; the patch is released either way.
// An entry's own "up" overrides the file's.
void add_entry(mcon_library library, mcon_mesh mesh, const mcon::tools::Json& e, const std::string& author,
               const std::string& licence, const std::array<double, 3>* file_up) {
  const std::string name = e.at("name").as_string(), klass = e.at("class").as_string();
  mcon_patch_options po;
  check(mcon_patch_options_init(&po), "mcon_patch_options_init");
  po.center_vertex = static_cast<std::uint32_t>(e.at("center_vertex").as_number());
  po.radius = e.at("radius").as_number();
  std::array<double, 3> own_up{};
  const std::array<double, 3>* up = read_up(e, &own_up) ? &own_up : file_up;
  mcon_patch patch = nullptr;
  check(mcon_patch_extract(mesh, &po, &patch), name + ": mcon_patch_extract");
  try {
    add_patch_entry(library, patch, e, name, klass, author, licence, up);
  } catch (...) {
    mcon_patch_release(patch);
    throw;
  }
  mcon_patch_release(patch);
}

int run(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: build_starter_library ENTRIES.json MODEL_DIR OUT.mclb\n");
    return 2;
  }
  const std::string entries_path = argv[1], model_dir = argv[2], out_path = argv[3];
  const mcon::tools::Json root = mcon::tools::parse_json(read_text(entries_path));
  const std::string model = model_dir + "/" + root.at("model").as_string();

  sample_mesh body;
  char error[512];
  if (sample_mesh_read_obj(model.c_str(), &body, error, sizeof(error)) != 0) throw std::runtime_error(error);

  mcon_context ctx = nullptr;
  mcon_mesh mesh = nullptr;
  mcon_library library = nullptr;
  int status = 0;
  try {
    check(mcon_context_create(nullptr, &ctx), "mcon_context_create");
    create_body_mesh(ctx, body, model, &mesh);
    check(mcon_library_create(ctx, &library), "mcon_library_create");

    const std::string author = root.at("author").as_string(), licence = root.at("licence").as_string();
    std::array<double, 3> file_up{};
    const bool has_up = read_up(root, &file_up);
    for (const auto& e : root.at("entries").elements())
      add_entry(library, mesh, e, author, licence, has_up ? &file_up : nullptr);

    mcon_retrieval_options ro;
    check(mcon_retrieval_options_init(&ro), "mcon_retrieval_options_init");
    check(mcon_library_build_retrieval(library, &ro), "mcon_library_build_retrieval");
    check(mcon_library_save(library, out_path.c_str()), "mcon_library_save(" + out_path + ")");
    size_t count = 0;
    check(mcon_library_get_count(library, &count), "mcon_library_get_count");
    std::printf("starter library: %zu entries -> %s\n", count, out_path.c_str());
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "build_starter_library: %s\n", ex.what());
    status = 1;
  }
  mcon_library_release(library);
  mcon_mesh_release(mesh);
  mcon_context_release(ctx);
  mcon_shutdown();
  sample_mesh_free(&body);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "build_starter_library: %s\n", ex.what());
    return 1;
  }
}
