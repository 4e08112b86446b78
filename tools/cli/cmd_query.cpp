// `macrocon query`: the library entries nearest to a patch of a mesh file (thesis §3.2:
// bag-of-features histograms under the L1 distance).
#include <chrono>
#include <cstdio>
#include <string>

#include "base/text.h"
#include "command/args.h"
#include "command/progress_bar.h"
#include "io/mesh_io.h"
#include "json/json.h"
#include "macrocon/macrocon.hpp"
#include "sdk_arrays.h"

namespace mcon::cli {
namespace {

const char* kUsage =
    "usage: macrocon query --library LIB.mclb --mesh FILE --center-vertex N --radius R [--top N]\n"
    "                      [--face-range A:B] [--json] [--quiet | --progress]\n"
    "Cuts the geodesic disk of radius R (mesh units) around vertex N (file numbering; --face-range\n"
    "keeps file faces [A, B)) and prints the N (default 5) nearest library entries by L1 distance of\n"
    "their bag-of-features histograms, nearest first.\n"
    "A progress bar over the stages (reading the library, cutting the patch, its histogram, the scan)\n"
    "is drawn on stderr when it is a terminal; --quiet hides it, --progress draws it anyway.\n"
    MACROCON_HELP_NUMBERING;

int run_query(const Args& args) {
  static const OptionHelp help{
      {"library", "the constraint library (.mclb)"},
      {"mesh", "the mesh to query on (OBJ, PLY, OFF; .gz too)"},
      {"center-vertex", "center of the query region (file vertex)"},
      {"radius", "geodesic radius of the query region in mesh units"},
      {"top", "how many entries to print, nearest first (default 5)"},
  };
  const ArgParser p(args, {"library", "mesh", "center-vertex", "radius", "top", "face-range"},
                    {"json", "quiet", "progress"}, kUsage, help);
  const std::string path = p.required("library");
  const std::string mesh_path = p.required("mesh");
  const long center_vertex = ArgParser::parse_integer("center-vertex", p.required("center-vertex"));
  const double radius = ArgParser::parse_number("radius", p.required("radius"));
  const long top = p.integer("top", 5);
  require(top >= 1, MCON_ERROR_INVALID_ARGUMENT, "--top must be >= 1");
  require(radius > 0, MCON_ERROR_INVALID_ARGUMENT, "--radius must be > 0 (got " + std::to_string(radius) + ")");

  // A bar over the stages, not inside them (loading and the scan take no callback): reading and
  // verifying the file grows with the library, so it gets the largest share.
  ProgressBar bar("query", progress_wanted(p));
  bar.update(0.0);
  const macrocon::Context context;
  const macrocon::Library lib = macrocon::Library::open(context, path);
  bar.update(0.6);
  require(lib.info().vocabulary_size > 0, MCON_ERROR_INVALID_ARGUMENT,
          "'" + path + "' has no vocabulary yet: run macrocon library build");
  io::MeshFileOptions file_options;
  if (p.has("face-range")) parse_range("face-range", p.get("face-range"), file_options.face_begin, file_options.face_end);
  const io::LoadedMesh loaded = io::read_mesh(mesh_path, file_options);
  const int center = io::mesh_vertex_of_file_vertex(loaded, center_vertex, "--center-vertex", mesh_path);
  const macrocon::Patch patch = macrocon::Patch::extract(
      sdk_mesh(context, loaded.mesh), macrocon::PatchOptions::at_vertex(static_cast<std::uint32_t>(center), radius));
  bar.update(0.7);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<macrocon::QueryHit> hits = lib.query(patch, static_cast<std::size_t>(top));
  bar.update(1.0);
  bar.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (p.flag("json")) {
    tools::Json j = tools::Json::object();
    j.set("library", path);
    j.set("patch_vertices", static_cast<unsigned long>(patch.vertex_count()));
    j.set("query_seconds", seconds);
    tools::Json list = tools::Json::array();
    for (std::size_t r = 0; r < hits.size(); ++r) {
      tools::Json h = tools::Json::object();
      h.set("rank", static_cast<unsigned long>(r + 1));
      h.set("id", std::to_string(hits[r].id));
      h.set("index", static_cast<unsigned long>(hits[r].index));
      h.set("name", lib.entry_string(hits[r].index, MCON_ENTRY_NAME, 0));
      h.set("class", lib.entry_string(hits[r].index, MCON_ENTRY_CLASS_LABEL, 0));
      h.set("distance", hits[r].distance);
      list.push_back(h);
    }
    j.set("hits", list);
    std::printf("%s\n", tools::write_json(j, false).c_str());
  } else {
    std::printf("%4s %8s  %-24s %-16s %10s\n", "rank", "id", "name", "class", "distance");
    for (std::size_t r = 0; r < hits.size(); ++r) {
      // Names come from the library file: escaped, so they cannot drive the terminal.
      std::printf("%4zu %8llu  %-24s %-16s %10.6f\n", r + 1, static_cast<unsigned long long>(hits[r].id),
                  printable_text(lib.entry_string(hits[r].index, MCON_ENTRY_NAME, 0)).c_str(),
                  printable_text(lib.entry_string(hits[r].index, MCON_ENTRY_CLASS_LABEL, 0)).c_str(),
                  hits[r].distance);
    }
  }
  return 0;
}

const Registration registration{"query", "find the library entries nearest to a patch of a mesh", run_query};

}  // namespace
}  // namespace mcon::cli
