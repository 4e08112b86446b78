// The retrieval benchmark of `macrocon-eval eval-retrieval` (thesis §3.3 on our own data): random
// MakeHuman people and ICT faces (shared/bench/README.md), a geodesic disk at every landmark class
// of both models (left and right instances share the class name without the side), each patch on
// its own triangulation, described by one or more built-in descriptors; then a leave-one-out
// evaluation of the bag-of-features retrieval (each patch queries a library of all the others).
//
// Vocabulary and leave-one-out: the descriptor normalization, the k-means vocabulary and sigma_BoF
// are fitted from the library only, never from the query. Patches are split into folds by subject
// (person i and face i are subject i, fold = i mod F); a query of fold f is answered with the
// vocabulary fitted on all patches of the other folds, and compared with every other patch (its
// own fold included) histogrammed with that vocabulary. So neither the query nor any other patch
// of the same person or face helps to choose the words that describe it: the vocabulary is what a
// vendor built before this user's model existed, and the library entries of the query's fold are
// entries added later to a library whose vocabulary was fixed (as libraries are extended).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/mesh_perturbation.h"
#include "retrieval/bag_of_features.h"
#include "descriptors/curvature_descriptors.h"

namespace mcon::tools {

struct RetrievalBenchmarkOptions {
  std::string shared_dir;
  std::uint64_t seed = 1;
  int people = 8;  // random MakeHuman people (13 patches each)
  int faces = 8;   // random ICT faces (7 patches each)
  // Built-in descriptors to compute per patch ("curv9", "hks", "wks").
  std::vector<std::string> descriptors = {"curv9"};
  PatchBoundary boundary = PatchBoundary::kCutThroughTriangles;  // CURV9 boundary rule
  double min_decimation = 0.2, max_decimation = 0.4;  // fraction of the instance's vertices removed
  int max_attempts = 4;  // re-tessellations tried per patch before a patch that is no disk is an error
  // Applied to every host after the re-tessellation (each patch is a query and a library entry);
  // the perturbed host then goes through the product's input path (orient_and_validate).
  MeshPerturbation perturbation;
  // Only these class parts (e.g. "eye", "nose"); empty = every class of the bench spec.
  std::vector<std::string> parts;
  // Patch radius x this (leave-family-out queries at 0.7, 1.0 and 1.4 of the class's radius).
  double radius_scale = 1.0;
  // Progress lines (may be empty).
  std::function<void(const std::string&)> log;
};

struct BenchmarkPatch {
  std::string model;        // "makehuman" or "ict"
  int instance = 0;         // person or face number
  std::string bench_class;  // e.g. "eye_l"
  std::string label;        // the class compared by retrieval, e.g. "eye"
  int fold = 0;
  std::string diagonals;    // "alternate" or "random"
  int removed_vertices = 0; // by the decimation of the instance
  int attempts = 1;
  int vertices = 0, triangles = 0;
  int host_vertices_before = 0, host_vertices = 0;  // around the perturbation
  int reoriented_triangles = 0;                     // by the orientation repair of the host
  std::string failure;  // perturbed runs: why no attempt gave a patch (then the patch is dropped)
  double prepare_seconds = 0;               // re-tessellation + patch extraction
  std::vector<double> describe_seconds;     // per descriptor
  std::vector<PatchDescriptors> descriptors;  // per descriptor (areas and center distances in each)
};

struct RetrievalBenchmark {
  std::vector<std::string> descriptors;
  std::vector<BenchmarkPatch> patches;
  std::vector<std::string> classes;  // sorted labels
  // Perturbed runs: patches no attempt could cut (evaluated as missing, not as queries or entries).
  std::vector<BenchmarkPatch> failed_patches;
  int folds = 1;
  double instances_seconds = 0;  // building the people and faces
  double patches_seconds = 0;    // preparing and describing all patches (wall clock, parallel)
};

// Builds the set: instances in parallel, then patches in parallel over patches (oneTBB in the
// caller's arena). Every patch is a pure function of (seed, patch number), so the set is identical
// for any thread count. Throws mcon::Error (IO for missing data, NOT_A_DISK if a patch fails on
// all its attempts, the descriptors' errors).
RetrievalBenchmark build_retrieval_benchmark(const RetrievalBenchmarkOptions& options);

struct RetrievalEvalOptions {
  int vocabulary_size = 128;
  double sigma_bof = 0;  // 0: the median rule (bag_of_features.h)
  std::size_t max_training_points = 200000;
  std::uint64_t seed = 1;
  std::vector<std::uint32_t> rings = {1};  // one evaluation per ring count
  std::function<void(const std::string&)> log;
};

// The vocabulary build options of an evaluation for one descriptor (every evaluation that builds
// a vocabulary reads its settings here).
RetrievalBuildOptions retrieval_build_options(const RetrievalEvalOptions& options, const std::string& descriptor);

struct RetrievalEvaluation {
  std::string descriptor;
  std::uint32_t rings = 1;
  int vocabulary_size = 0;       // as built (median over folds)
  double sigma_bof = 0;          // median over folds
  double nn_accuracy = 0;
  std::vector<double> precision_at;  // n = 1..10
  std::vector<double> recall_at;     // n = 1..10
  std::map<std::string, double> class_nn_accuracy;
  std::map<std::string, int> class_size;
  // Wrong nearest neighbours: (query class, neighbour class) -> count.
  std::map<std::pair<std::string, std::string>, int> confusion;
  // Per wrong query: patch index, its nearest neighbour, the rank of the first correct patch.
  struct Miss {
    int query = 0, neighbour = 0, first_correct_rank = 0;
  };
  std::vector<Miss> misses;
  // Median over folds of: vocabulary (wall clock) + the sum of the library entries' histogram times
  // (each timed alone, so the sum is what one thread would spend).
  double library_build_seconds = 0;
  double vocabulary_seconds = 0;     // median over folds: normalization + k-means + sigma
  double query_seconds_median = 0;   // histogram of the query + top-10 scan over the library
  // Symmetrized L1 distances, patches x patches row-major: (d_i(i,j) + d_j(i,j)) / 2 with d_i
  // measured under the vocabulary that answers query i.
  std::vector<double> distances;
};

// Leave-one-out evaluation of descriptor `descriptor_index` of the set (see the header comment
// for how vocabularies are fitted), one result per options.rings entry.
std::vector<RetrievalEvaluation> evaluate_retrieval(const RetrievalBenchmark& set, std::size_t descriptor_index,
                                                    const RetrievalEvalOptions& options);

// Median of the values (mean of the middle two for an even count); 0 for none.
double median_of(std::vector<double> values);

}  // namespace mcon::tools
