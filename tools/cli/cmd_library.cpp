// `macrocon library build | add | info`: make a constraint library file from patches of mesh
// files, add one entry to a library file, and describe a library file.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <string>

#include "base/parallel_blocks.h"
#include "base/text.h"
#include "command/progress_bar.h"
#include "library_cli.h"

namespace mcon::cli {
namespace {

const char* kUsage =
    "usage: macrocon library build --out LIB.mclb [--mesh FILE] [--face-range A:B] [--up X,Y,Z]\n"
    "                              (--center-vertex N --radius R --class C [--name S] [--author A]\n"
    "                               [--licence L] [--tag T]...)...  [--spec FILE.json]\n"
    "                              [--descriptor curv9|hks|wks] [--rings K] [--vocabulary K] [--seed S]\n"
    "                              [--sigma X] [--json] [--quiet | --progress]\n"
    "       macrocon library add --library LIB.mclb [--mesh FILE] [--face-range A:B] [--up X,Y,Z]\n"
    "                            --center-vertex N --radius R --class C [--name S] [--author A]\n"
    "                            [--licence L] [--tag T]...\n"
    "                            [CONSTRAINTS] [--id ID] [--json]\n"
    "       macrocon library info --library LIB.mclb [--json]\n"
    "build: every --center-vertex starts an entry: a geodesic disk of radius R (mesh units) around\n"
    "  that vertex (file numbering) of the latest --mesh (and --face-range: file faces [A, B)); the\n"
    "  options after it describe that entry. --spec reads entries from JSON instead or as well:\n"
    "  {\"mesh\": \"body.obj.gz\", \"face_range\": \"0:13378\", \"entries\": [{\"center_vertex\": 297,\n"
    "  \"radius\": 0.5, \"class\": \"nose\", \"name\": \"nose\", \"author\": \"..\", \"licence\": \"..\",\n"
    "  \"tags\": [\"..\"], \"mesh\": \"(optional, per entry)\"}]} (paths relative to the spec file).\n"
    "  --up X,Y,Z (like --mesh: for the entries that follow; \"up\": [x, y, z] in a spec, top level or\n"
    "  per entry) stores the mesh's up direction with them, in its file coordinates (e.g. 0,1,0 for a\n"
    "  Y-up character); embed --entry then needs only the target's up.\n"
    "  Then the vocabulary (k-means++, k = --vocabulary, default 128), sigma and every histogram\n"
    "  are computed; rings default to the measured best. The file is written atomically.\n"
    "add: the entry's histogram is computed with the library's vocabulary (no rebuild), and the\n"
    "  file is rewritten atomically.\n"
    "info: counts, retrieval config and per-entry id/name/class/vertices/constraints/fields (--json:\n"
    "  also each field's kind and dimension, as --field names them).\n"
    "CONSTRAINTS of an entry, from files a DCC exports, in the mesh file's coordinates:\n"
    "  --guides FILE.obj / --features FILE.obj (each repeatable): polylines as OBJ 'l' statements on or\n"
    "    near the surface; each point snaps to the closest point of the patch. Points outside the\n"
    "    patch are left out (a line leaving the disk is cut into its pieces on it), so one file can\n"
    "    serve many entries; a point farther than --max-snap-distance D (mesh units, default 0.1 x\n"
    "    the radius) from the mesh is an error.\n"
    "  --singularities FILE.csv|FILE.ply: a table with columns x, y, z, index (index in quarter turns: +1 for a\n"
    "    valence-3 vertex, -1 for valence 5); points outside the patch are left out.\n"
    "  --fields FILE.ply|FILE.csv: per-vertex values, one row per mesh file vertex in file order (PLY:\n"
    "    vertex properties; CSV: a header line of column names). Every column but x, y, z becomes\n"
    "    a scalar field of its name, unless --field NAME[=COL,COL...][:KIND] (repeatable)\n"
    "    picks them: KIND scalar (default), vector3 or tangent (3 columns), uv (2), label (whole\n"
    "    numbers, not blended). Patch vertices on a host edge blend its two ends.\n"
    "  In --spec, an entry takes the same as \"guides\": [..], \"features\": [..], \"singularities\",\n"
    "  \"fields\", \"field\": [..] and \"max_snap_distance\". --json reports what each entry got\n"
    "  (\"authoring\": kept and left-out points, snap distances, fields).\n"
    "build draws progress bars (patches, then retrieval) on stderr when it is a terminal; --quiet\n"
    "hides them, --progress draws them anyway.\n"
    MACROCON_HELP_NUMBERING;

// Options that describe one entry, and options that hold for the whole command.
// The options that describe the latest --center-vertex's entry.
const std::set<std::string>& entry_options() {
  static const std::set<std::string> keys{"radius", "class", "name", "author", "licence", "tag", "guides",
                                          "features", "singularities", "fields", "field", "max-snap-distance"};
  return keys;
}

bool is_entry_option(const std::string& key) { return entry_options().count(key) > 0; }

// An authoring option of one entry (entry_authoring.h); `once` options given twice are refused.
void set_authoring_option(AuthoringSpec& a, const std::string& key, const std::string& value) {
  auto once = [&](std::string& slot) {
    require(slot.empty(), MCON_ERROR_INVALID_ARGUMENT, "--" + key + " given twice for one entry");
    slot = value;
  };
  if (key == "guides") a.guide_files.push_back(value);
  if (key == "features") a.feature_files.push_back(value);
  if (key == "singularities") once(a.singularity_file);
  if (key == "fields") once(a.field_file);
  if (key == "field") a.field_specs.push_back(value);
  if (key == "max-snap-distance") {
    a.max_snap_distance = parse_real(key, value);
    require(a.max_snap_distance >= 0, MCON_ERROR_INVALID_ARGUMENT, "--max-snap-distance must be >= 0");
  }
}

struct Parsed {
  std::vector<EntrySpec> entries;
  std::map<std::string, std::string> global;  // --out, --library, --descriptor, ...
  bool json = false;
  bool quiet = false, progress = false;  // the progress bar: off, forced on
};

// One line of --help per option of build, add and info.
const OptionHelp& library_help() {
  static const OptionHelp help{
      {"out", "build: the library file to write (.mclb)"},
      {"library", "add, info: the library file (.mclb)"},
      {"spec", "build: read entries from this JSON file too"},
      {"descriptor", "build: curv9 (default), hks or wks"},
      {"rings", "build: histogram rings (default: the measured best)"},
      {"vocabulary", "build: visual words k of the k-means++ vocabulary (default 128)"},
      {"seed", "build: seed of the vocabulary's k-means++"},
      {"sigma", "build: soft-assignment width (default: the median rule)"},
      {"id", "add: the new entry's id (default: the next free one)"},
      {"mesh", "the mesh the entries that follow are cut from"},
      {"face-range", "keep only that mesh file's faces [A, B)"},
      {"up", "X,Y,Z: that mesh's up direction, stored with the entries that follow"},
      {"center-vertex", "starts an entry: its center (file vertex)"},
      {"radius", "the entry's geodesic radius in mesh units"},
      {"class", "the entry's class label (e.g. nose)"},
      {"name", "the entry's name"},
      {"author", "the entry's author"},
      {"licence", "the entry's licence"},
      {"tag", "a tag of the entry (repeatable)"},
      {"guides", "guide polylines of the entry (OBJ 'l' lines; repeatable)"},
      {"features", "feature polylines of the entry (OBJ 'l' lines; repeatable)"},
      {"singularities", "the entry's singularities (CSV or PLY table of x, y, z, index)"},
      {"fields", "per-vertex fields of the entry (PLY vertex properties or CSV)"},
      {"field", "NAME[=COL,...][:KIND]: a field to take from --fields (repeatable)"},
      {"max-snap-distance", "farthest a constraint point may lie from the mesh (default 0.1 x radius)"},
  };
  return help;
}

// Reads the arguments in order: --mesh / --face-range / --up set the source of the entries that
// follow; --center-vertex starts an entry; entry options apply to the latest entry.
Parsed parse(const Args& args, const std::set<std::string>& globals) {
  std::set<std::string> keys(globals);
  keys.insert({"mesh", "face-range", "up", "center-vertex"});
  keys.insert(entry_options().begin(), entry_options().end());
  Parsed p;
  std::string mesh, face_range;
  std::optional<std::array<double, 3>> up;
  for (const ArgOccurrence& o : parse_in_order(args, keys, {"json", "quiet", "progress"}, kUsage, library_help())) {
    const std::string& key = o.key;
    const std::string& value = o.value;
    if (o.flag) {
      (key == "json" ? p.json : key == "quiet" ? p.quiet : p.progress) = true;
    } else if (key == "mesh") {
      mesh = value;
    } else if (key == "face-range") {
      long b = 0, e = 0;
      parse_range("face-range", value, b, e);
      face_range = value;
    } else if (key == "up") {
      up = parse_vec3("up", value);
    } else if (key == "center-vertex") {
      EntrySpec s;
      s.mesh = mesh;
      s.face_range = face_range;
      s.up = up;
      s.center_vertex = parse_integer(key, value);
      p.entries.push_back(s);
    } else if (is_entry_option(key)) {
      require(!p.entries.empty(), MCON_ERROR_INVALID_ARGUMENT, "'--" + key + "' before any --center-vertex");
      EntrySpec& s = p.entries.back();
      if (key == "radius") s.radius = parse_real(key, value);
      if (key == "class") s.class_label = value;
      if (key == "name") s.name = value;
      if (key == "author") s.author = value;
      if (key == "licence") s.licence = value;
      if (key == "tag") s.tags.push_back(value);
      set_authoring_option(s.authoring, key, value);
    } else {
      require(p.global.count(key) == 0, MCON_ERROR_INVALID_ARGUMENT, "option '--" + key + "' given twice");
      p.global[key] = value;
    }
  }
  return p;
}

void check_entry(const EntrySpec& s, std::size_t i) {
  const std::string what = "entry " + std::to_string(i) + " (center vertex " + std::to_string(s.center_vertex) + ")";
  require(s.radius > 0, MCON_ERROR_INVALID_ARGUMENT, what + ": needs --radius R > 0");
  require(!s.class_label.empty(), MCON_ERROR_INVALID_ARGUMENT, what + ": needs --class");
}

// A spec entry's constraint files ("guides"/"features": a path or a list; "singularities",
// "fields": a path; "field": a list of NAME[=COL,...][:KIND]; "max_snap_distance": mesh units).
template <typename Resolve>
void read_spec_authoring(const tools::Json& e, const Resolve& resolve, AuthoringSpec& a) {
  auto paths = [&](const char* key, std::vector<std::string>& out) {
    const tools::Json* v = e.find(key);
    if (!v) return;
    if (v->is_string()) {
      out.push_back(resolve(v->as_string()));
      return;
    }
    for (std::size_t i = 0; i < v->size(); ++i) out.push_back(resolve((*v)[i].as_string()));
  };
  paths("guides", a.guide_files);
  paths("features", a.feature_files);
  if (const tools::Json* v = e.find("singularities")) a.singularity_file = resolve(v->as_string());
  if (const tools::Json* v = e.find("fields")) a.field_file = resolve(v->as_string());
  if (const tools::Json* v = e.find("field"))
    for (std::size_t i = 0; i < v->size(); ++i) a.field_specs.push_back((*v)[i].as_string());
  if (const tools::Json* v = e.find("max_snap_distance")) {
    a.max_snap_distance = v->as_number();
    require(a.max_snap_distance >= 0, MCON_ERROR_INVALID_ARGUMENT, "max_snap_distance must be >= 0");
  }
}

std::vector<EntrySpec> read_spec(const std::string& path) {
  const tools::Json spec = tools::read_json_file(path);
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  auto resolve = [&](const std::string& p) {
    const std::filesystem::path fp(p);
    return fp.is_absolute() ? p : (dir / fp).string();
  };
  auto text = [](const tools::Json& j, const char* key, const std::string& fallback) {
    const tools::Json* v = j.find(key);
    return v ? v->as_string() : fallback;
  };
  const std::string mesh = text(spec, "mesh", "");
  const std::string face_range = text(spec, "face_range", "");
  // "up": [x, y, z], for every entry or per entry.
  auto up_of = [&](const tools::Json& j, const std::optional<std::array<double, 3>>& fallback) {
    const tools::Json* v = j.find("up");
    if (!v) return fallback;
    require(v->is_array() && v->size() == 3, MCON_ERROR_INVALID_ARGUMENT, path + ": \"up\" must be [x, y, z]");
    return std::optional<std::array<double, 3>>(std::array<double, 3>{{(*v)[0].as_number(), (*v)[1].as_number(),
                                                                       (*v)[2].as_number()}});
  };
  const std::optional<std::array<double, 3>> up = up_of(spec, std::nullopt);
  std::vector<EntrySpec> out;
  const tools::Json& entries = spec.at("entries");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const tools::Json& e = entries[i];
    EntrySpec s;
    const std::string m = text(e, "mesh", mesh);
    require(!m.empty(), MCON_ERROR_INVALID_ARGUMENT, path + ": entry " + std::to_string(i) + " has no mesh");
    s.mesh = resolve(m);
    s.face_range = text(e, "face_range", face_range);
    s.up = up_of(e, up);
    s.center_vertex = static_cast<long>(e.at("center_vertex").as_int());
    s.radius = e.at("radius").as_number();
    s.class_label = e.at("class").as_string();
    s.name = text(e, "name", "");
    s.author = text(e, "author", "");
    s.licence = text(e, "licence", "");
    if (const tools::Json* tags = e.find("tags"))
      for (std::size_t t = 0; t < tags->size(); ++t) s.tags.push_back((*tags)[t].as_string());
    read_spec_authoring(e, resolve, s.authoring);
    out.push_back(s);
  }
  return out;
}

std::string get(const Parsed& p, const std::string& key, const std::string& fallback = "") {
  auto it = p.global.find(key);
  return it == p.global.end() ? fallback : it->second;
}

std::string required(const Parsed& p, const std::string& key) {
  require(p.global.count(key) > 0, MCON_ERROR_INVALID_ARGUMENT, "missing required option --" + key);
  return p.global.at(key);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A failure of one entry, from either error type (the CLI's own checks and the SDK's).
struct EntryFailure {
  mcon_status status;
  std::string message;
};

// Cuts the entries' patches in parallel, a chunk at a time (each entry on its own; meshes are
// loaded first, then only read), and adds them in the given order, so the file does not depend
// on the thread count and at most one chunk of patches is held at once. A failing entry is named.
// Returns what each entry's constraint files gave (entry_authoring.h).
std::vector<AuthoringReport> add_entries(macrocon::Library& lib, MeshCache& meshes, const std::vector<EntrySpec>& entries,
                                         ProgressBar& bar) {
  auto entry_error = [&](std::size_t i, const EntryFailure& e) {
    const EntrySpec& s = entries[i];
    fail(e.status, "entry " + std::to_string(i) + (s.name.empty() ? "" : " '" + printable_text(s.name) + "'") +
                       " (center vertex " + std::to_string(s.center_vertex) + ", radius " + number_text(s.radius) +
                       "): " + e.message);
  };
  // Runs f, turning what it throws into the entry's failure.
  auto attempt = [](const auto& f) -> std::optional<EntryFailure> {
    try {
      f();
    } catch (const Error& e) {
      return EntryFailure{e.status(), e.what()};
    } catch (const macrocon::Error& e) {
      return EntryFailure{e.status(), e.what()};
    } catch (const std::bad_alloc&) {
      return EntryFailure{MCON_ERROR_OUT_OF_MEMORY, "out of memory cutting the patch"};
    }
    return std::nullopt;
  };
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (auto failure = attempt([&] {
          if (!entries[i].mesh.empty()) meshes.of(entries[i]);
        }))
      entry_error(i, *failure);
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> done{0};
  std::vector<AuthoringReport> reports(entries.size());
  for (std::size_t first = 0; first < entries.size(); first += kChunk) {
    const std::size_t count = std::min(kChunk, entries.size() - first);
    std::vector<macrocon::Patch> patches(count);
    std::vector<macrocon::EntryData> contents(count);
    std::vector<std::optional<EntryFailure>> errors(count);
    for_each_block(count, 1, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t k = begin; k < end; ++k) {
        errors[k] = attempt([&] {
          const EntrySpec& spec = entries[first + k];
          const HostMesh& host = meshes.of(spec);
          patches[k] = cut_patch(host, spec);
          contents[k] = entry_content(spec);
          reports[first + k] = author_constraints(host, patches[k], spec.authoring, contents[k]);
        });
        bar.update(static_cast<double>(++done) / static_cast<double>(entries.size()));
      }
    });
    for (std::size_t k = 0; k < count; ++k) {
      if (errors[k]) entry_error(first + k, *errors[k]);
      if (auto failure = attempt([&] { lib.add(patches[k], contents[k]); })) entry_error(first + k, *failure);
    }
  }
  return reports;
}

// The retrieval options of `library build`, from mcon_retrieval_options_init's defaults.
mcon_retrieval_options retrieval_options(const Parsed& p) {
  mcon_retrieval_options o = macrocon::Library::default_retrieval_options();
  const std::string descriptor = get(p, "descriptor", "curv9");
  try {
    o.descriptor = macrocon::retrieval_descriptor_from_name(descriptor);
  } catch (const macrocon::Error& e) {
    fail(e.status(), std::string("--descriptor: ") + e.what());
  }
  const long rings = parse_integer("rings", get(p, "rings", std::to_string(o.rings)));
  const long k = parse_integer("vocabulary", get(p, "vocabulary", std::to_string(o.vocabulary_size)));
  const long seed = parse_integer("seed", get(p, "seed", std::to_string(o.seed)));
  require(rings >= 1 && rings <= 64, MCON_ERROR_INVALID_ARGUMENT, "--rings must be 1..64");
  require(k >= 1 && k <= 65536, MCON_ERROR_INVALID_ARGUMENT, "--vocabulary must be 1..65536");
  require(seed >= 0, MCON_ERROR_INVALID_ARGUMENT, "--seed must be >= 0");
  o.rings = static_cast<std::uint32_t>(rings);
  o.vocabulary_size = static_cast<std::uint32_t>(k);
  o.seed = static_cast<std::uint64_t>(seed);
  o.sigma_bof = parse_real("sigma", get(p, "sigma", number_text(o.sigma_bof)));
  return o;
}

// `library build --json`: the summary, the timings and what each entry's constraint files gave.
tools::Json build_report(const macrocon::Library& lib, const std::string& out, const Parsed& p,
                         const std::vector<AuthoringReport>& reports, double patch_seconds, double build_seconds) {
  tools::Json j = library_summary(lib);
  j.set("library", out);
  j.set("entry_seconds", patch_seconds);
  j.set("build_seconds", build_seconds);
  tools::Json authoring = tools::Json::array();
  for (std::size_t i = 0; i < reports.size(); ++i)
    if (!p.entries[i].authoring.empty()) {
      tools::Json r = reports[i].json();
      r.set("entry", static_cast<unsigned long>(i));
      authoring.push_back(r);
    }
  j.set("authoring", authoring);
  return j;
}

int run_build(const Args& args) {
  Parsed p = parse(args, {"out", "spec", "descriptor", "rings", "vocabulary", "seed", "sigma"});
  const std::string out = required(p, "out");
  if (p.global.count("spec")) {
    std::vector<EntrySpec> more = read_spec(p.global.at("spec"));
    p.entries.insert(p.entries.end(), more.begin(), more.end());
  }
  require(!p.entries.empty(), MCON_ERROR_INVALID_ARGUMENT, "no entries: give --center-vertex ... or --spec FILE");
  for (std::size_t i = 0; i < p.entries.size(); ++i) check_entry(p.entries[i], i);
  const mcon_retrieval_options options = retrieval_options(p);

  const auto t0 = std::chrono::steady_clock::now();
  const macrocon::Context context;
  MeshCache meshes(context);
  macrocon::Library lib = macrocon::Library::create(context);
  lib.set_descriptor(options.descriptor);  // entries get the chosen descriptor from the start
  std::vector<AuthoringReport> reports;
  const bool bars = progress_wanted(p.quiet, p.progress);
  {
    ProgressBar bar("patches", bars);
    reports = add_entries(lib, meshes, p.entries, bar);
  }
  const double patch_seconds = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  ProgressBar bar("retrieval", bars);
  lib.build_retrieval(options, bar.callback());
  bar.finish();
  const double build_seconds = seconds_since(t1);
  lib.save(out);

  if (p.json) {
    const tools::Json report = build_report(lib, out, p, reports, patch_seconds, build_seconds);
    std::printf("%s\n", tools::write_json(report, false).c_str());
  } else {
    const mcon_library_info c = lib.info();
    std::printf("%s: %zu entries, descriptor %s, %u words x %u rings, sigma %.4g (patches %.2f s, retrieval %.2f s)\n",
                printable_text(out).c_str(), c.entry_count, printable_text(lib.string(MCON_LIBRARY_DESCRIPTOR)).c_str(),
                c.vocabulary_size, c.rings, c.sigma_bof, patch_seconds, build_seconds);
  }
  return 0;
}

int run_add(const Args& args) {
  Parsed p = parse(args, {"library", "id"});
  const std::string path = required(p, "library");
  require(p.entries.size() == 1, MCON_ERROR_INVALID_ARGUMENT,
          "library add takes exactly one --center-vertex (got " + std::to_string(p.entries.size()) + ")");
  check_entry(p.entries[0], 0);
  const macrocon::Context context;
  macrocon::Library lib = macrocon::Library::open(context, path);
  macrocon::EntryData content = entry_content(p.entries[0]);
  const long id = parse_integer("id", get(p, "id", "0"));
  require(id >= 0, MCON_ERROR_INVALID_ARGUMENT, "--id must be >= 0 (0 = assign)");
  content.id = static_cast<std::uint64_t>(id);
  MeshCache meshes(context);
  const EntrySpec& spec = p.entries[0];
  const HostMesh& host = meshes.of(spec);
  const macrocon::Patch patch = cut_patch(host, spec);
  const AuthoringReport report = author_constraints(host, patch, spec.authoring, content);
  const std::uint64_t assigned = lib.add(patch, content);
  lib.save(path);
  const mcon_library_info info = lib.info();
  if (p.json) {
    tools::Json j = tools::Json::object();
    j.set("library", path);
    j.set("id", std::to_string(assigned));
    j.set("index", static_cast<unsigned long>(info.entry_count - 1));
    j.set("entries", static_cast<unsigned long>(info.entry_count));
    j.set("has_histogram", info.vocabulary_size > 0);  // an entry gets one when the library has words
    j.set("authoring", report.json());
    std::printf("%s\n", tools::write_json(j, false).c_str());
  } else {
    std::printf("%s: added entry id %llu (index %zu)%s\n", printable_text(path).c_str(),
                static_cast<unsigned long long>(assigned), info.entry_count - 1,
                info.vocabulary_size > 0 ? "" : "; no vocabulary yet: run library build to query");
  }
  return 0;
}

// What `library info` lists of one entry (strings as stored; the callers escape them).
struct EntrySummary {
  mcon_library_entry_info info;
  std::string name, class_label;
  std::size_t guides = 0, features = 0;
  std::vector<std::string> field_names;
  std::vector<std::uint32_t> field_kinds, field_dimensions;
};

EntrySummary entry_summary(const macrocon::Library& lib, std::size_t index) {
  EntrySummary s;
  s.info = lib.entry_info(index);
  s.name = lib.entry_string(index, MCON_ENTRY_NAME, 0);
  s.class_label = lib.entry_string(index, MCON_ENTRY_CLASS_LABEL, 0);
  for (std::size_t l = 0; l < s.info.polyline_count; ++l) {
    std::uint32_t kind = 0;
    macrocon::check(mcon_library_get_entry_polyline(lib.get(), index, l, &kind, nullptr, nullptr, nullptr, 0));
    ++(kind == MCON_POLYLINE_GUIDE ? s.guides : s.features);
  }
  for (std::size_t f = 0; f < s.info.field_count; ++f) {
    std::uint32_t kind = 0, dimension = 0;
    macrocon::check(mcon_library_get_entry_field(lib.get(), index, f, &kind, &dimension, nullptr, nullptr, 0));
    s.field_names.push_back(lib.entry_string(index, MCON_ENTRY_FIELD_NAME, f));
    s.field_kinds.push_back(kind);
    s.field_dimensions.push_back(dimension);
  }
  return s;
}

tools::Json entry_json(const EntrySummary& e) {
  tools::Json o = tools::Json::object();
  o.set("id", std::to_string(e.info.id));
  o.set("name", e.name);
  o.set("class", e.class_label);
  o.set("vertices", static_cast<unsigned long>(e.info.vertex_count));
  o.set("triangles", static_cast<unsigned long>(e.info.triangle_count));
  o.set("guides", static_cast<unsigned long>(e.guides));
  o.set("features", static_cast<unsigned long>(e.features));
  o.set("singularities", static_cast<unsigned long>(e.info.singularity_count));
  tools::Json fields = tools::Json::array(), kinds = tools::Json::array();
  for (std::size_t f = 0; f < e.field_names.size(); ++f) {
    fields.push_back(e.field_names[f]);
    tools::Json k = tools::Json::object();
    k.set("name", e.field_names[f]);
    k.set("kind", field_kind_name(e.field_kinds[f]));
    k.set("dimension", static_cast<unsigned long>(e.field_dimensions[f]));
    kinds.push_back(k);
  }
  o.set("fields", fields);
  o.set("field_kinds", kinds);
  o.set("source_scale", e.info.source_scale);
  if (e.info.has_up) {
    tools::Json up = tools::Json::array();
    for (double c : e.info.up) up.push_back(c);
    o.set("up", up);
  }
  return o;
}

int run_info(const Args& args) {
  Parsed p = parse(args, {"library"});
  require(p.entries.empty(), MCON_ERROR_INVALID_ARGUMENT, "library info takes no entries");
  const std::string path = required(p, "library");
  const macrocon::Context context;
  const macrocon::Library lib = macrocon::Library::open(context, path);
  const mcon_library_info c = lib.info();
  if (p.json) {
    tools::Json j = library_summary(lib);
    j.set("library", path);
    j.set("name", lib.string(MCON_LIBRARY_NAME));
    j.set("format_version", static_cast<unsigned long>(c.format_version));
    j.set("checksum_verified", c.checksum_verified != 0);
    tools::Json entries = tools::Json::array();
    for (std::size_t i = 0; i < c.entry_count; ++i) entries.push_back(entry_json(entry_summary(lib, i)));
    j.set("entry_list", entries);
    std::printf("%s\n", tools::write_json(j, true).c_str());
    return 0;
  }
  // Human-readable output escapes what comes from the file: an entry name must not be able to
  // move the cursor or clear the screen (the JSON output escapes it its own way).
  std::printf("%s: %zu entries; descriptor %s (d = %u), %u words x %u rings, sigma %.4g, seed %llu\n",
              printable_text(path).c_str(), c.entry_count, printable_text(lib.string(MCON_LIBRARY_DESCRIPTOR)).c_str(),
              c.descriptor_dimension, c.vocabulary_size, c.rings, c.sigma_bof, static_cast<unsigned long long>(c.seed));
  std::printf("format %u, %s\n", c.format_version,
              c.checksum_verified ? "content checksum verified" : "no content checksum (format 1)");
  std::printf("%8s  %-24s %-16s %8s %6s %6s %6s\n", "id", "name", "class", "vertices", "lines", "sing", "fields");
  for (std::size_t i = 0; i < c.entry_count; ++i) {
    const EntrySummary e = entry_summary(lib, i);
    std::printf("%8llu  %-24s %-16s %8zu %6zu %6zu %6zu\n", static_cast<unsigned long long>(e.info.id),
                printable_text(e.name).c_str(), printable_text(e.class_label).c_str(), e.info.vertex_count,
                e.guides + e.features, e.info.singularity_count, e.info.field_count);
  }
  return 0;
}

int run_library(const Args& args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const Args rest(args.begin() + 1, args.end());
  if (args[0] == "build") return run_build(rest);
  if (args[0] == "add") return run_add(rest);
  if (args[0] == "info") return run_info(rest);
  fail(MCON_ERROR_INVALID_ARGUMENT, "unknown library command '" + args[0] + "' (build, add or info)");
}

const Registration registration{"library", "build, extend and describe constraint library files", run_library};

}  // namespace
}  // namespace mcon::cli
