// `macrocon query`: the library entries nearest to a patch of a mesh file (thesis §3.2:
// bag-of-features histograms under the L1 distance).
#include <chrono>
#include <cstdio>
#include <string>

#include "base/text.h"
#include "command/args.h"
#include "command/progress_bar.h"
#include "library_cli.h"
#include "library/library_file.h"
#include "library/library_retrieval.h"

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
  const ArgParser p(args, {"library", "mesh", "center-vertex", "radius", "top", "face-range"},
                    {"json", "quiet", "progress"}, kUsage);
  const std::string path = p.required("library");
  EntrySpec spec;
  spec.mesh = p.required("mesh");
  spec.face_range = p.get("face-range");
  spec.center_vertex = parse_integer("center-vertex", p.required("center-vertex"));
  spec.radius = parse_real("radius", p.required("radius"));
  const long top = p.integer("top", 5);
  require(top >= 1, MCON_ERROR_INVALID_ARGUMENT, "--top must be >= 1");

  // A bar over the stages, not inside them (loading and the scan take no callback): reading and
  // verifying the file grows with the library, so it gets the largest share.
  ProgressBar bar("query", progress_wanted(p));
  bar.update(0.0);
  const ConstraintLibrary lib = load_library_from_file(path);
  bar.update(0.6);
  require(lib.retrieval().vocabulary_size > 0, MCON_ERROR_INVALID_ARGUMENT,
          "'" + path + "' has no vocabulary yet: run macrocon library build");
  MeshCache meshes;
  const Patch patch = cut_patch(meshes, spec);
  bar.update(0.7);
  const std::vector<float> flat = flat_histograms(lib);
  bar.update(0.8);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<float> histogram = query_histogram(lib.retrieval(), patch);
  bar.update(0.85);
  const std::vector<RetrievalHit> hits = query_top_n(lib.retrieval(), flat, histogram, static_cast<std::size_t>(top));
  bar.update(1.0);
  bar.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (p.flag("json")) {
    tools::Json j = tools::Json::object();
    j.set("library", path);
    j.set("patch_vertices", static_cast<unsigned long>(patch.mesh.positions.size()));
    j.set("query_seconds", seconds);
    tools::Json list = tools::Json::array();
    for (std::size_t r = 0; r < hits.size(); ++r) {
      const MacroConstraint& e = lib.entries()[hits[r].entry];
      tools::Json h = tools::Json::object();
      h.set("rank", static_cast<unsigned long>(r + 1));
      h.set("id", std::to_string(e.id));
      h.set("index", static_cast<unsigned long>(hits[r].entry));
      h.set("name", e.name);
      h.set("class", e.class_label);
      h.set("distance", static_cast<double>(hits[r].distance));
      list.push_back(h);
    }
    j.set("hits", list);
    std::printf("%s\n", tools::write_json(j, false).c_str());
  } else {
    std::printf("%4s %8s  %-24s %-16s %10s\n", "rank", "id", "name", "class", "distance");
    for (std::size_t r = 0; r < hits.size(); ++r) {
      const MacroConstraint& e = lib.entries()[hits[r].entry];
      // Names come from the library file: escaped, so they cannot drive the terminal.
      std::printf("%4zu %8llu  %-24s %-16s %10.6f\n", r + 1, static_cast<unsigned long long>(e.id),
                  printable_text(e.name).c_str(), printable_text(e.class_label).c_str(),
                  static_cast<double>(hits[r].distance));
    }
  }
  return 0;
}

const Registration registration{"query", "find the library entries nearest to a patch of a mesh", run_query};

}  // namespace
}  // namespace mcon::cli
