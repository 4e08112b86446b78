// `macrocon-eval eval-mapping`: map quality on ground truth (tools/common/mapping_benchmark.h).
#include <cmath>
#include <cstdio>
#include <string>

#include "command/args.h"
#include "command/progress_bar.h"
#include "json/json_file.h"
#include "common/mapping_benchmark.h"

namespace mcon::cli {
namespace {

const char* kUsage =
    "usage: macrocon-eval eval-mapping --shared DIR [--seed S] [--pairs N] [--classes a,b,...] [--method NAME]\n"
    "                             [--samples K] [--thesis-iterations I] [--eval-vertices V] [--threads T]\n"
    "                             [--cross-family] [--noise F] [--density S] [--flip-winding] [--plain-newton] [--cycle-signal] [--json] [--quiet | --progress]\n"
    "Maps patches of the same class between two random people (MakeHuman) or faces (ICT), the target\n"
    "re-tessellated by seeded random decimation, mirrored pairs included (a right eye onto a left\n"
    "eye), and measures eps = geodesic distance on the target between the mapped and the true point /\n"
    "sqrt(target patch area) over source vertices mapped inside the target (docs/design.md §3).\n"
    "Methods: macrocon (the SDK's map), rigid (its initialization only), thesis (the thesis' fixed-step\n"
    "gradient descent, 15,000 iterations, from the same rigid start), proximity (what a DCC user does\n"
    "without the SDK: similarity ICP of the source onto the target in 3D world coordinates, start with\n"
    "centroids matched, scale sqrt(area ratio), identity rotation; then the closest target surface point\n"
    "of each source vertex; a mirrored pair's source is mirrored x -> -x first); --method restricts to a list.\n"
    "Only when asked for: macrocon-frame = the SDK's map with the 3D-aligned start (use_world_frame: the\n"
    "ICP alignment expressed in the two disk parametrizations is the rigid start and decides orientation\n"
    "and reflection; a mirrored pair's source mirrored x -> -x first), beside the frame-free macrocon;\n"
    "frame-rigid = that start alone (what rigid is to macrocon). --frame-anchor W: macrocon-frame's\n"
    "anchor weight (world_frame_anchor; default the SDK's, 0 = no anchor), --frame-anchor-decay D its\n"
    "factor per stage (default the SDK's). macrocon-up = the frame-free map with up hints +y on both\n"
    "patches (source_up/target_up); --up-anchor W its pull towards the rigid start (start_anchor).\n"
    "Diagnostic method, only when asked for (--method macrocon,oracle): oracle = the SDK's map with\n"
    "the ground-truth correspondents' base-mesh positions as extra guidance channels, i.e. what the\n"
    "optimizer and its distortion prior reach when the descriptors are unambiguous; landmarks = the\n"
    "SDK's map guided by the geodesic distances from --landmarks K (default 4) true point pairs, spread\n"
    "by farthest-point sampling: what a few artist-clicked correspondences give.\n"
    "Classes: eye, nose, mouth, ear, face, hand, foot, arm. Pair i uses slot i of the list (MakeHuman:\n"
    "each class once, sided classes once same-side and once mirrored; then ICT likewise) and the people\n"
    "or faces 2i and 2i+1 of the seed. Default --pairs: the MakeHuman slots, i.e. 13 pairs covering\n"
    "all 8 classes (eye, ear, hand, foot, arm each once same-side and once mirrored), about 10 minutes\n"
    "on 2 cores, most of it the thesis baseline; --pairs 20 adds the 7 ICT slots (eye, ear twice;\n"
    "nose, mouth, face), --pairs > 20 cycles with new people. --samples: rigid candidates (default 10000);\n"
    "--eval-vertices: evaluated source vertices per pair (default 300, deterministic stride);\n"
    "--threads: TBB threads (default 2). Per-pair lines go to stderr unless --quiet, above a progress bar\n"
    "when stderr is a terminal (--progress draws it anyway).\n"
    "--plain-newton: macrocon, macrocon-frame and macrocon-up factorize the Hessian at every Newton\n"
    "iteration instead of reusing factorizations (NewtonOptions::reuse_factorization), for side-by-side runs.\n"
    "--cycle-signal: also maps macrocon, macrocon-frame and macrocon-up pairs backwards (same options) and\n"
    "adds the forward/backward consistency (\"cycle\": minus the median return distance, disk radius 1) and\n"
    "\"backward_matching_score\" to the cross-family confidence signals (doubles those methods' time).\n"
    "--json prints {\"pairs\": N, \"methods\": {\"macrocon\": {\"overall\": M, \"per_class\": {\"eye\": M, ...}}, ...}}\n"
    "with M = {mean_eps100, within_0_05, flipped_triangles, overlap, seconds_median, iterations_median},\n"
    "and \"target_edge_eps100\": {\"overall\": e, \"per_class\": {...}}, the target's mean edge length in the\n"
    "same units (100 x edge / sqrt(target patch area)): the scale of one target edge, to read mean_eps100 against.\n"
    "--noise F, --density S, --flip-winding: the in-family target host, after its decimation, is perturbed\n"
    "(Gaussian noise of std F x its mean edge length, decimated or subdivided to S x its vertex count, every\n"
    "triangle reversed; tools/common/mesh_perturbation.h) and then oriented as mcon_mesh_create does; the\n"
    "ground truth follows the vertex identities; the JSON's \"perturbation\" names what was applied.\n"
    "--cross-family: also maps across families, MakeHuman <-> ICT (eye, nose, mouth, ear, face; both\n"
    "directions; eye and ear also mirrored: 14 pairs, restricted by --classes), scored on the semantic\n"
    "landmarks of bench/semantic-landmarks.json inside both patches: landmark eps = geodesic distance on\n"
    "the target between the mapped and the true landmark / sqrt(target patch area). Methods macrocon,\n"
    "rigid, thesis, proximity, macrocon-frame, frame-rigid. Reported per method: mean landmark eps x 100\n"
    "per class and overall (mean over pairs; also over all landmarks, and the median), gross_failures\n"
    "(share of pairs whose median landmark eps > 0.15) and orientation_errors (pairs where a landmark\n"
    "pair separated along x = left-right or y = up by >= 0.08 target radii comes out in the opposite\n"
    "order); --json adds \"cross_family\": {\"pairs\", \"methods\": {m: {\"overall\": C, \"per_class\": {...}}},\n"
    "\"cases\": [...]} beside the in-family numbers, which stay as without the flag.\n";

void print_cross_family(const tools::Json& cross, const std::vector<std::string>& methods) {
  std::printf("cross-family: %lld pairs\n%-9s %-6s %10s %10s %10s %6s %8s %9s\n", cross.at("pairs").as_int(), "method",
              "class", "eps100", "lm.eps100", "median100", "gross", "orient.", "seconds");
  for (const std::string& m : methods) {
    const tools::Json& entry = cross.at("methods").at(m);
    auto row = [&](const std::string& name, const tools::Json& s) {
      std::printf("%-9s %-6s %10.3f %10.3f %10.3f %6.3f %8lld %9.3f\n", m.c_str(), name.c_str(),
                  s.at("mean_eps100").as_number(), s.at("landmark_mean_eps100").as_number(),
                  s.at("median_eps100").as_number(), s.at("gross_failures").as_number(),
                  s.at("orientation_errors").as_int(), s.at("seconds_median").as_number());
    };
    const tools::Json& per = entry.at("per_class");
    for (std::size_t k = 0; k < per.size(); ++k) row(per.key(k), per.value(k));
    row("all", entry.at("overall"));
  }
}

const OptionHelp& mapping_help() {
  static const OptionHelp help{
      {"seed", "seed of the people, faces and re-tessellations (default 1)"},
      {"pairs", "number of pairs (default 13: the MakeHuman slots; 20 adds ICT)"},
      {"classes", "only these classes (eye, nose, mouth, ear, face, hand, foot, arm)"},
      {"method", "only these methods (macrocon, rigid, thesis, proximity, ...)"},
      {"samples", "rigid start candidates (default 10000)"},
      {"thesis-iterations", "iterations of the thesis baseline (default 15000)"},
      {"eval-vertices", "evaluated source vertices per pair (default 300)"},
      {"threads", "worker threads (TBB arena, default 2)"},
      {"landmarks", "true point pairs of the landmarks method (default 4)"},
      {"noise", "Gaussian noise on the target host, std F x its mean edge length"},
      {"density", "decimate or subdivide the target host to S x its vertex count"},
      {"frame-anchor", "macrocon-frame's anchor weight (default the SDK's)"},
      {"frame-anchor-decay", "macrocon-frame's anchor factor per stage (default the SDK's)"},
      {"up-anchor", "macrocon-up's pull towards the rigid start"},
      {"cross-family", "also map MakeHuman <-> ICT, scored on the semantic landmarks"},
      {"flip-winding", "reverse every triangle of the target host"},
      {"plain-newton", "one factorization per Newton iteration (no reuse)"},
      {"cycle-signal", "also map backwards and report the cycle consistency"},
  };
  return help;
}

int run_eval_mapping(const Args& args) {
  const ArgParser p(args,
                    {"shared", "seed", "pairs", "classes", "method", "samples", "thesis-iterations", "eval-vertices",
                     "threads", "landmarks", "noise", "density", "frame-anchor", "frame-anchor-decay", "up-anchor"},
                    {"json", "quiet", "progress", "cross-family", "flip-winding", "plain-newton", "cycle-signal"}, kUsage,
                    mapping_help());
  tools::MappingEvalOptions o;
  o.shared_dir = p.required("shared");
  const long seed = p.integer("seed", 1);
  require(seed >= 0, MCON_ERROR_INVALID_ARGUMENT, "--seed must be >= 0");
  o.seed = static_cast<std::uint64_t>(seed);
  o.pairs = static_cast<int>(p.integer("pairs", 0));
  require(o.pairs >= 0 && o.pairs <= 100000, MCON_ERROR_INVALID_ARGUMENT, "--pairs must be in [1, 100000]");
  require(!p.has("pairs") || o.pairs >= 1, MCON_ERROR_INVALID_ARGUMENT, "--pairs must be in [1, 100000]");
  if (p.has("classes")) o.parts = split_names(p.get("classes"));
  if (p.has("method")) o.methods = split_names(p.get("method"));
  o.alignment_samples = static_cast<int>(p.integer("samples", o.alignment_samples));
  o.thesis_iterations = static_cast<int>(p.integer("thesis-iterations", o.thesis_iterations));
  o.max_evaluated_vertices = static_cast<int>(p.integer("eval-vertices", o.max_evaluated_vertices));
  o.threads = static_cast<int>(p.integer("threads", o.threads));
  o.landmarks = static_cast<int>(p.integer("landmarks", o.landmarks));
  require(o.landmarks >= 1 && o.landmarks <= 64, MCON_ERROR_INVALID_ARGUMENT, "--landmarks must be in [1, 64]");
  require(o.alignment_samples >= 1 && o.thesis_iterations >= 0 && o.max_evaluated_vertices >= 1 && o.threads >= 1 &&
              o.threads <= 256,
          MCON_ERROR_INVALID_ARGUMENT,
          "--samples, --eval-vertices and --threads must be positive, --thesis-iterations >= 0");
  if (p.has("frame-anchor")) {
    o.frame_anchor = p.number("frame-anchor", 0.0);
    require(o.frame_anchor >= 0 && std::isfinite(o.frame_anchor), MCON_ERROR_INVALID_ARGUMENT,
            "--frame-anchor must be a finite number >= 0");
  }
  if (p.has("frame-anchor-decay")) {
    o.frame_anchor_decay = p.number("frame-anchor-decay", 1.0);
    require(o.frame_anchor_decay > 0 && o.frame_anchor_decay <= 1, MCON_ERROR_INVALID_ARGUMENT,
            "--frame-anchor-decay must be in (0, 1]");
  }
  if (p.has("up-anchor")) {
    o.up_anchor = p.number("up-anchor", 0.0);
    require(o.up_anchor >= 0 && std::isfinite(o.up_anchor), MCON_ERROR_INVALID_ARGUMENT,
            "--up-anchor must be a finite number >= 0");
  }
  o.plain_newton = p.flag("plain-newton");
  o.cycle_signal = p.flag("cycle-signal");
  o.perturbation.noise = p.number("noise", 0.0);
  o.perturbation.density = p.number("density", 1.0);
  o.perturbation.flip_winding = p.flag("flip-winding");
  tools::check_perturbation(o.perturbation);
  // One log line per pair above a progress bar (stderr, a terminal or --progress); --quiet: neither.
  ProgressBar bar("pairs", progress_wanted(p.flag("quiet"), p.flag("progress")));
  if (!p.flag("quiet")) o.log = [&bar](const std::string& line) { bar.println(line); };
  o.progress = [&bar](double f) { bar.update(f); };

  std::vector<std::string> uncut;
  bar.update(0.0);
  const std::vector<tools::MappingPairResult> pairs = tools::run_mapping_evaluation(o, &uncut);
  bar.finish();
  tools::Json json = tools::mapping_evaluation_json(pairs, o.methods);
  json.set("perturbation", o.perturbation.describe());
  tools::Json uncut_json = tools::Json::array();
  for (const std::string& u : uncut) uncut_json.push_back(u);
  json.set("uncut_pairs", uncut_json);
  if (p.flag("cross-family")) {
    ProgressBar cross("cross-family pairs", progress_wanted(p.flag("quiet"), p.flag("progress")));
    if (!p.flag("quiet")) o.log = [&cross](const std::string& line) { cross.println(line); };
    o.progress = [&cross](double f) { cross.update(f); };
    cross.update(0.0);
    json.set("cross_family", tools::cross_family_json(tools::run_cross_family_evaluation(o), o.methods));
  }
  if (p.flag("json")) {
    std::printf("%s\n", tools::write_json(json, true).c_str());
    return 0;
  }
  std::printf("%zu pairs\n%-9s %-6s %10s %10s %6s %8s %9s %6s\n", pairs.size(), "method", "class", "eps100",
              "within.05", "flips", "overlap", "seconds", "iters");
  for (const std::string& m : o.methods) {
    const tools::Json& entry = json.at("methods").at(m);
    auto row = [&](const std::string& name, const tools::Json& s) {
      std::printf("%-9s %-6s %10.3f %10.3f %6lld %8.3f %9.3f %6.0f\n", m.c_str(), name.c_str(),
                  s.at("mean_eps100").as_number(), s.at("within_0_05").as_number(),
                  s.at("flipped_triangles").as_int(), s.at("overlap").as_number(), s.at("seconds_median").as_number(),
                  s.at("iterations_median").as_number());
    };
    const tools::Json& per = entry.at("per_class");
    for (std::size_t k = 0; k < per.size(); ++k) row(per.key(k), per.value(k));
    row("all", entry.at("overall"));
  }
  const tools::Json& edge = json.at("target_edge_eps100");
  std::printf("target edge (eps100):");
  const tools::Json& per = edge.at("per_class");
  for (std::size_t k = 0; k < per.size(); ++k) std::printf(" %s %.3f", per.key(k).c_str(), per.value(k).as_number());
  std::printf(" all %.3f\n", edge.at("overall").as_number());
  if (json.contains("cross_family")) print_cross_family(json.at("cross_family"), o.methods);
  return 0;
}

const Registration registration{"eval-mapping", "map quality on ground truth (people, faces; mirrored pairs)",
                                run_eval_mapping};

}  // namespace
}  // namespace mcon::cli
