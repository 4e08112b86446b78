// Map quality on ground truth (`macrocon-eval eval-mapping`, docs/design.md §3): pairs of the same patch
// class cut on two different random people (MakeHuman) or faces (ICT), the target re-tessellated
// by seeded random decimation (surviving vertices keep their identity), mirrored pairs included
// (a right eye onto a left eye; the ground truth then goes through the base mesh's mirror
// involution). For each source vertex that is a host vertex whose true vertex survives in the
// target patch, eps = geodesic distance on the target patch (heat method) between the mapped
// point and the true vertex, divided by sqrt(target patch area); only points mapped inside the
// target count (the overlap is reported separately). Several methods run on the same pairs:
//   macrocon  the SDK's map (map_patches)
//   rigid     its rigid initialization alone
//   thesis    the thesis' fixed-step gradient descent from the same rigid start
//             (common/thesis_gradient_descent.h)
//   proximity what users have without the SDK: similarity ICP of the source onto the target in
//             3D host coordinates (map/similarity_icp.h), then the closest target surface point
//             of each source vertex (a mirrored pair's source is mirrored x -> -x first)
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/mesh_perturbation.h"
#include "json/json_file.h"

namespace mcon::tools {

extern const char* const kMappingMethods[4];  // "macrocon", "rigid", "thesis", "proximity"
extern const char* const kMappingParts[8];    // eye, nose, mouth, ear, face, hand, foot, arm

// One kind of pair: model ("makehuman" or "ict"), body part, and whether the target is the
// other side's class (sided parts only).
struct MappingSlot {
  std::string model;
  std::string part;
  bool mirrored = false;
  std::string source_class;  // e.g. "eye_r"
  std::string target_class;  // e.g. "eye_l" for a mirrored pair
};

struct MappingEvalOptions {
  std::string shared_dir;
  std::uint64_t seed = 1;
  int pairs = 0;                         // 0: one pair per MakeHuman slot (the default run)
  std::vector<std::string> parts;        // empty: all parts
  std::vector<std::string> methods = {"macrocon", "rigid", "thesis", "proximity"};
  // Applied to every target host after its decimation, then oriented and validated as
  // mcon_mesh_create does (common/mesh_perturbation.h); the source stays clean.
  MeshPerturbation perturbation;
  int alignment_samples = 10000;         // rigid candidates (thesis: 10,000)
  int thesis_iterations = 15000;
  int max_evaluated_vertices = 300;      // per pair, deterministic stride subsample
  int threads = 2;
  int landmarks = 4;                     // corresponding points of the `landmarks` method
  // macrocon-frame's anchor weight (PatchMapOptions::world_frame_anchor); < 0: the SDK default.
  double frame_anchor = -1;
  double frame_anchor_decay = -1;  // its decay per stage (SurfaceMapOptions::anchor_decay); < 0: default
  // Also map every macrocon / -frame / -up pair backwards (target onto source, same options) and
  // report the forward/backward consistency as a confidence signal (doubles those methods' time).
  bool cycle_signal = false;
  bool plain_newton = false;  // macrocon, -frame, -up: one factorization per Newton iteration (no reuse)
  double up_anchor = -1;  // macrocon-up's start anchor (PatchMapOptions::up_start_anchor); < 0: default
  std::function<void(const std::string&)> log;  // one line per pair (stderr in the CLI)
  std::function<void(double)> progress;         // fraction of the pairs done, after each pair
};

struct MethodPairResult {
  double mean_eps = 0;      // mean eps over evaluated points mapped inside the target
  double within_0_05 = 0;   // share of those points with eps <= 0.05
  int evaluated = 0;        // points that entered the mean
  int flipped_triangles = 0;
  double overlap = 0;       // source vertex area mapped inside the target / total
  double seconds = 0;
  int iterations = 0;
  bool reflected = false;   // the map reverses orientation (expected exactly for mirrored pairs)
};

struct MappingPairResult {
  MappingSlot slot;
  int person_a = 0, person_b = 0;
  int source_vertices = 0, target_vertices = 0;
  int ground_truth_vertices = 0;  // source vertices with a surviving true vertex
  // The target's resolution in eps units: mean 3D edge length / sqrt(target patch area). A point
  // a third of an edge away from its true vertex scores about a third of this; it tells how far
  // below one target edge a method's mean eps lies.
  double target_edge_eps = 0;
  std::string orientation_note;   // the map's orientation evidence (rigid scores, level-0 energies)
  std::map<std::string, MethodPairResult> methods;
};

// The slots in run order: MakeHuman first (eye same side, eye mirrored, nose, mouth, ...), then
// ICT; restricted to `parts` if non-empty. Throws INVALID_ARGUMENT for an unknown part.
std::vector<MappingSlot> mapping_slots(const std::string& shared_dir, const std::vector<std::string>& parts);

// Runs the evaluation (pair i uses slot i mod #slots and people/faces 2i, 2i+1 of the seed).
// Throws mcon::Error (IO for missing data, INVALID_ARGUMENT for bad options).
// With a perturbation and `uncut_pairs`, a pair whose target no retry can cut is listed there and
// left out of the results instead of ending the run.
std::vector<MappingPairResult> run_mapping_evaluation(const MappingEvalOptions& options,
                                                      std::vector<std::string>* uncut_pairs = nullptr);

// {"pairs": N, "methods": {m: {"overall": M, "per_class": {part: M}}},
//  "target_edge_eps100": {"overall": e, "per_class": {part: e}}} with M = {mean_eps100,
// within_0_05, flipped_triangles, overlap, seconds_median, iterations_median}; mean_eps100,
// within_0_05, overlap and e (100 x MappingPairResult::target_edge_eps) are means over pairs (each
// pair weighs the same).
Json mapping_evaluation_json(const std::vector<MappingPairResult>& pairs, const std::vector<std::string>& methods);

// Cross-family pairs (`eval-mapping --cross-family`): a MakeHuman patch mapped onto an ICT patch of
// the same class or back (eye, nose, mouth, ear, face; eye and ear also mirrored), cut on random
// instances (source 2i, target 2i + 1 of its model), scored on the semantic landmarks of
// bench/semantic-landmarks.json that lie in both patches (the true correspondent of a mirrored
// pair's landmark is its other-side twin): landmark eps = geodesic distance on the target (heat
// method) between the mapped and the true landmark / sqrt(target patch area).
struct CrossFamilySlot {
  std::string source_model, target_model;  // "makehuman" / "ict"
  std::string part;
  bool mirrored = false;
  std::string source_class, target_class;
};

struct CrossFamilyMethodResult {
  std::vector<double> landmark_eps;  // per landmark of the pair, in CrossFamilyPairResult::landmarks order
  bool reflected = false;
  // Orientation (mapping_benchmark.cpp, check_orientation): landmark pairs checked for their
  // left-right (x) or up-down (y) order on the target, those the map inverts, and their names.
  int checked_pairs = 0, inverted_pairs = 0;
  std::string inverted;
  double seconds = 0;
  // Candidate confidence signals of the map (macrocon, macrocon-frame; mapping_benchmark.cpp,
  // kConfidenceSignals): name -> value, for the ROC AUC in cross_family_json.
  std::map<std::string, double> signals;
};

struct CrossFamilyPairResult {
  CrossFamilySlot slot;
  int person_a = 0, person_b = 0;
  std::vector<std::string> landmarks;  // names (source side) of the landmarks in both patches
  std::string orientation_note;
  std::map<std::string, CrossFamilyMethodResult> methods;
};

// The 14 slots (restricted to `parts` if non-empty; parts other than the five face parts are ignored).
std::vector<CrossFamilySlot> cross_family_slots(const std::vector<std::string>& parts);

// Runs every cross-family slot once with options.methods (macrocon, rigid, thesis, proximity only).
std::vector<CrossFamilyPairResult> run_cross_family_evaluation(const MappingEvalOptions& options);

// {"pairs": N, "methods": {m: {"overall": C, "per_class": {part: C}}}, "cases": [...]} with C =
// {pairs, mean_eps100 (mean over pairs of the pair's mean landmark eps), landmark_mean_eps100 and
// median_eps100 (over all landmarks), gross_failures (share of pairs whose median landmark eps >
// 0.15), orientation_errors (pairs with an inverted landmark pair), seconds_median}.
Json cross_family_json(const std::vector<CrossFamilyPairResult>& pairs, const std::vector<std::string>& methods);

}  // namespace mcon::tools
