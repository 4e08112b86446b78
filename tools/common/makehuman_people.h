// Random MakeHuman people for the benchmark: base body + sum_k w_k * target_k with the weights drawn
// per shared/bench/README.md ("Making random instances"): MakeHuman's own macro rule (gender, age,
// muscle, weight, ethnic shares) and the local-detail targets (opposite pairs, one-sided targets,
// l-/r- pairs drawn once with a slight asymmetry; eyefold and epicanthus excluded). Every person
// has the base body's vertices and triangles, so the ground truth between two people is the
// identity on vertex indices. Person i of seed s is a pure function of (s, i) (bench_random.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "mesh/mesh.h"

namespace mcon::tools {

// The body surface of meshes/makehuman/base.obj.gz: the first 13378 faces (group `body`, all
// quads) and their vertices 0..13379.
constexpr int kMakeHumanBodyFaces = 13378;
constexpr int kMakeHumanBodyVertices = 13380;

// One random draw of local detail: an opposite pair (weight v ~ U[-0.4, 0.4]: `second` with v if
// v > 0, else `first` with -v) or a one-sided target (`second` empty, weight ~ U[0, 0.4]). `sides`
// has one entry, or two for an l-/r- pair (left first); the right side gets an extra
// U[-0.04, 0.04] (one-sided weights stay >= 0). Target names are "<category>/<file name without
// .target.gz>".
struct LocalTargetDraw {
  // The draw's name: "<category>/<name without side prefix>", for a pair with both last words
  // (e.g. "ears/ear-trans-down-up").
  std::string key;
  bool opposite_pair = true;
  struct Side {
    std::string first, second;
  };
  std::vector<Side> sides;
};

// Lists the local-detail targets of <targets_dir>/<category>/ (ears, eyes, nose, mouth, head, chin,
// cheek, forehead, eyebrows, neck, armslegs) as draws, sorted by key. Throws
// mcon::Error(MCON_ERROR_IO) if a category folder is missing.
std::vector<LocalTargetDraw> list_local_target_draws(const std::string& targets_dir);

struct TargetWeight {
  std::string target;  // "<category>/<name>"
  double weight = 0.0;
};

struct PersonRecipe {
  double gender = 0.0;       // 0 female .. 1 male
  double age = 0.0;          // MakeHuman's age parameter in [0.375, 0.875]
  double age_years = 0.0;
  double muscle = 0.0;       // 0 .. 1
  double body_weight = 0.0;  // 0 .. 1
  std::array<double, 3> ethnic{};  // african, asian, caucasian shares (sum 1)
  std::vector<TargetWeight> targets;  // non-zero weights in application order (macro, then local)
};

// The macro-detail target weights of one parameter set (MakeHuman's rule, bench/README.md).
std::vector<TargetWeight> macro_target_weights(double gender, double age, double muscle, double body_weight,
                                               const std::array<double, 3>& ethnic);

class MakeHumanPeople {
 public:
  // Reads <shared_dir>/meshes/makehuman/base.obj.gz (body only) and lists the targets; target files
  // are parsed on first use and cached for the process (morph_target.h).
  explicit MakeHumanPeople(const std::string& shared_dir);

  // The base body as read (triangulated a,b,c / a,c,d; triangle_to_face gives the OBJ quad).
  const io::LoadedMesh& base() const { return base_; }
  const std::vector<LocalTargetDraw>& local_draws() const { return draws_; }

  PersonRecipe recipe(std::uint64_t seed, std::uint64_t index) const;
  // The base's (validated) connectivity with the summed positions, which are finite because target
  // offsets and weights are; not re-validated (a person is a smooth deformation of the base).
  TriMesh build(const PersonRecipe& recipe) const;
  TriMesh person(std::uint64_t seed, std::uint64_t index) const { return build(recipe(seed, index)); }

  // Parses every target file now (in parallel) so that later people cost only the sums.
  void preload_targets() const;

 private:
  std::string targets_dir_;
  io::LoadedMesh base_;
  std::vector<LocalTargetDraw> draws_;
};

}  // namespace mcon::tools
