#include "common/retrieval_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <set>

#include <tbb/parallel_for.h>

#include "common/bench_random.h"
#include "common/bench_spec.h"
#include "common/ict_faces.h"
#include "common/makehuman_people.h"
#include "common/patch_instances.h"
#include "common/retessellate.h"
#include "base/error.h"
#include "patch/geodesic_disk_patch.h"
#include "retrieval/retrieval_descriptors.h"
#include "retrieval/retrieval_index.h"

namespace mcon::tools {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// One model's instances and classes, ready for patch cutting.
struct ModelData {
  std::string name;
  const io::LoadedMesh* base = nullptr;
  BenchModelData bench;
  std::vector<TriMesh> instances;
};

// The task of one patch: which model, instance and class.
struct PatchTask {
  const ModelData* model = nullptr;
  int instance = 0;
  const BenchClass* bench_class = nullptr;
};

// Stream of the per-patch random draws: distinct from the instance generators' streams.
constexpr std::uint64_t kRetessellationSalt = 0x5E7E55E11A7E0001ull;

int mesh_vertex(const io::LoadedMesh& base, int file_vertex, const std::string& what) {
  require(file_vertex >= 0 && file_vertex < static_cast<int>(base.file_to_mesh.size()) &&
              base.file_to_mesh[static_cast<std::size_t>(file_vertex)] >= 0,
          MCON_ERROR_INDEX_OUT_OF_RANGE, "retrieval benchmark: " + what + " is not a surface vertex");
  return base.file_to_mesh[static_cast<std::size_t>(file_vertex)];
}

// The host as a user hands it to the product: perturbed by the evaluation's options, then oriented
// and validated as mcon_mesh_create does. `center` is renumbered to the host's vertices.
TriMesh user_host(const TriMesh& mesh, const MeshPerturbation& perturbation, std::uint64_t seed, int& center,
                  BenchmarkPatch& out) {
  PerturbedMesh p = user_mesh(mesh, perturbation, seed, {center});
  center = perturbed_vertex(p, center);
  require(center >= 0, MCON_ERROR_UNKNOWN, "retrieval benchmark: the perturbation removed a patch center");
  out.host_vertices_before = mesh.num_vertices();
  out.host_vertices = p.mesh.num_vertices();
  out.reoriented_triangles = p.reoriented_triangles;
  return std::move(p.mesh);
}

// Re-tessellates the instance (quad diagonals, then a seeded decimation that keeps the center) and
// cuts the class's disk with the instance-scaled radius. A triangulation on which the heat-method
// disk is no disk (a decimated fingertip can open the hand) is redrawn with the next attempt's seed.
Patch prepare_patch(const PatchTask& task, std::uint64_t seed, std::size_t patch_number,
                    const RetrievalBenchmarkOptions& options, BenchmarkPatch& out) {
  const ModelData& m = *task.model;
  const TriMesh& instance = m.instances[static_cast<std::size_t>(task.instance)];
  const BenchClass& bc = *task.bench_class;
  BenchClass mesh_class = bc;
  mesh_class.center_vertex = mesh_vertex(*m.base, bc.center_vertex, "center of '" + bc.name + "'");
  std::vector<int> base_vertices;
  for (const int v : m.bench.patches.find(bc.name).vertices)
    base_vertices.push_back(mesh_vertex(*m.base, v, "a vertex of patch '" + bc.name + "'"));
  const InstancePatch ip = instance_patch(mesh_class, base_vertices, m.base->mesh, instance, m.base->triangle_to_face);

  const BenchRng rng(seed ^ kRetessellationSalt, patch_number);
  for (int attempt = 0;; ++attempt) {
    const std::uint64_t c = 8 * static_cast<std::uint64_t>(attempt);
    const bool alternate = (rng.bits(c) & 1u) != 0;
    const Retessellation diag = rediagonalize(
        instance, m.base->triangle_to_face, alternate ? DiagonalPattern::Alternate : DiagonalPattern::Random,
        rng.bits(c + 1));
    DecimationOptions dec;
    dec.min_fraction = options.min_decimation;
    dec.max_fraction = options.max_decimation;
    dec.keep = {ip.center_vertex};
    const Retessellation decimated = decimate(diag.mesh, rng.bits(c + 2), dec);
    // Survivors keep their order: the center's new index by binary search in to_original.
    const auto it = std::lower_bound(decimated.to_original.begin(), decimated.to_original.end(), ip.center_vertex);
    require(it != decimated.to_original.end() && *it == ip.center_vertex, MCON_ERROR_UNKNOWN,
            "retrieval benchmark: the decimation removed the center of '" + bc.name + "'");
    PatchOptions po;
    po.center.vertex = static_cast<int>(it - decimated.to_original.begin());
    po.radius = ip.radius * options.radius_scale;
    po.fill_holes = true;
    try {
      const TriMesh host = user_host(decimated.mesh, options.perturbation, rng.bits(c + 3), po.center.vertex, out);
      Patch patch = extract_geodesic_disk(host, po);
      out.diagonals = alternate ? "alternate" : "random";
      out.removed_vertices = decimated.changed;
      out.attempts = attempt + 1;
      return patch;
    } catch (const Error& e) {
      // A perturbed host may also fail numerically or as a mesh; another draw may not.
      const bool retry = e.status() == MCON_ERROR_NOT_A_DISK || options.perturbation.active();
      if (!retry || attempt + 1 >= options.max_attempts)
        fail(e.status(), "retrieval benchmark: " + m.name + " instance " + std::to_string(task.instance) + " class " +
                             bc.name + " (attempt " + std::to_string(attempt + 1) + "): " + e.what());
    }
  }
}

// Prepares and describes one patch. A perturbed host on which no attempt gives a disk (noise can
// tear the geodesic disk, or fold triangles until the heat solve fails), or a patch at a scaled
// radius that is no disk (a face at x1.4 wraps around the head), is not an error of the evaluation
// but one of its results: the patch is marked failed (see drop_failed_patches).
void describe_patch(const PatchTask& task, std::size_t p, const RetrievalBenchmarkOptions& options,
                    BenchmarkPatch& out) {
  const auto tp = Clock::now();
  Patch patch;
  try {
    patch = prepare_patch(task, options.seed, p, options, out);
  } catch (const Error& e) {
    if (!options.perturbation.active() && options.radius_scale == 1.0) throw;
    out.failure = e.what();
    return;
  }
  out.prepare_seconds = seconds_since(tp);
  out.vertices = patch.mesh.num_vertices();
  out.triangles = patch.mesh.num_triangles();
  const auto ta = Clock::now();
  const PatchDescriptors common = patch_areas_and_center_distance(patch.mesh, patch.center);
  const double common_seconds = seconds_since(ta);
  for (const std::string& d : options.descriptors) {
    const auto td = Clock::now();
    PatchDescriptors pd = common;
    pd.values = compute_retrieval_descriptor(patch.mesh, d, options.boundary);
    out.describe_seconds.push_back(common_seconds + seconds_since(td));
    out.descriptors.push_back(std::move(pd));
  }
}

// Moves the failed patches (perturbed runs only) out of the set, in patch order.
template <typename Log>
void drop_failed_patches(RetrievalBenchmark& set, const Log& log) {
  std::vector<BenchmarkPatch> kept;
  for (BenchmarkPatch& p : set.patches) {
    if (p.failure.empty()) {
      kept.push_back(std::move(p));
    } else {
      log("dropped " + p.model + "/" + std::to_string(p.instance) + "/" + p.bench_class + ": " + p.failure);
      set.failed_patches.push_back(std::move(p));
    }
  }
  set.patches = std::move(kept);
}

}  // namespace

RetrievalBuildOptions retrieval_build_options(const RetrievalEvalOptions& options, const std::string& descriptor) {
  RetrievalBuildOptions bo;
  bo.descriptor = descriptor;
  bo.vocabulary_size = options.vocabulary_size;
  bo.sigma_bof = options.sigma_bof;
  bo.seed = options.seed;
  bo.max_training_points = options.max_training_points;
  return bo;
}

RetrievalBenchmark build_retrieval_benchmark(const RetrievalBenchmarkOptions& options) {
  require(options.people >= 0 && options.faces >= 0 && options.people + options.faces >= 1,
          MCON_ERROR_INVALID_ARGUMENT, "retrieval benchmark: need at least one person or face");
  require(!options.descriptors.empty(), MCON_ERROR_INVALID_ARGUMENT, "retrieval benchmark: no descriptor");
  for (const std::string& d : options.descriptors)
    require(is_builtin_descriptor(d), MCON_ERROR_INVALID_ARGUMENT,
            "retrieval benchmark: unknown descriptor '" + d + "' (" + builtin_descriptor_names() + ")");
  require(options.min_decimation >= 0 && options.min_decimation <= options.max_decimation &&
              options.max_decimation < 1,
          MCON_ERROR_INVALID_ARGUMENT, "retrieval benchmark: decimation fractions must satisfy 0 <= min <= max < 1");
  require(options.max_attempts >= 1 && options.radius_scale > 0, MCON_ERROR_INVALID_ARGUMENT,
          "retrieval benchmark: max_attempts must be >= 1 and radius_scale > 0");
  const auto log = [&](const std::string& s) {
    if (options.log) options.log(s);
  };

  RetrievalBenchmark set;
  set.descriptors = options.descriptors;
  const auto t0 = Clock::now();
  std::unique_ptr<MakeHumanPeople> people;
  std::unique_ptr<IctFaces> faces;
  std::vector<ModelData> models;
  models.reserve(2);
  if (options.people > 0) {
    people = std::make_unique<MakeHumanPeople>(options.shared_dir);
    people->preload_targets();
    ModelData m;
    m.name = "makehuman";
    m.base = &people->base();
    m.bench = read_bench_model(options.shared_dir, "makehuman");
    m.instances.resize(static_cast<std::size_t>(options.people));
    tbb::parallel_for(0, options.people, [&](int i) {
      m.instances[static_cast<std::size_t>(i)] = people->person(options.seed, static_cast<std::uint64_t>(i));
    });
    models.push_back(std::move(m));
  }
  if (options.faces > 0) {
    faces = std::make_unique<IctFaces>(options.shared_dir);
    ModelData m;
    m.name = "ict";
    m.base = &faces->neutral();
    m.bench = read_bench_model(options.shared_dir, "ict");
    m.instances.resize(static_cast<std::size_t>(options.faces));
    tbb::parallel_for(0, options.faces, [&](int i) {
      m.instances[static_cast<std::size_t>(i)] = faces->face(options.seed, static_cast<std::uint64_t>(i));
    });
    models.push_back(std::move(m));
  }
  set.instances_seconds = seconds_since(t0);
  log("built " + std::to_string(options.people) + " people and " + std::to_string(options.faces) + " faces in " +
      std::to_string(set.instances_seconds) + " s");

  // Folds by subject (see the header); a single subject is split by patch number instead, so there
  // is always a library vocabulary that excludes the query.
  const int subjects = std::max(options.people, options.faces);
  set.folds = subjects >= 2 ? std::min(4, subjects) : 2;

  std::vector<PatchTask> tasks;
  for (const ModelData& m : models)
    for (int i = 0; i < static_cast<int>(m.instances.size()); ++i)
      for (const BenchClass& bc : m.bench.spec.classes)
        if (options.parts.empty() || std::count(options.parts.begin(), options.parts.end(), bc.part))
          tasks.push_back({&m, i, &bc});
  set.patches.resize(tasks.size());
  const auto t1 = Clock::now();
  // One patch per task; each is a pure function of (seed, patch number), so the parallel loop gives
  // the same set for any thread count.
  tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t p) {
    const PatchTask& task = tasks[p];
    BenchmarkPatch& out = set.patches[p];
    out.model = task.model->name;
    out.instance = task.instance;
    out.bench_class = task.bench_class->name;
    out.label = task.bench_class->part;
    out.fold = subjects >= 2 ? task.instance % set.folds : static_cast<int>(p % 2);
    describe_patch(task, p, options, out);
  });
  drop_failed_patches(set, log);
  set.patches_seconds = seconds_since(t1);
  std::set<std::string> labels;
  for (const BenchmarkPatch& p : set.patches) labels.insert(p.label);
  set.classes.assign(labels.begin(), labels.end());
  log("prepared and described " + std::to_string(set.patches.size()) + " patches in " +
      std::to_string(set.patches_seconds) + " s");
  return set;
}

namespace {

constexpr std::size_t kTop = 10;  // hits kept per query (precision and recall at 1..kTop)

// What the folds gather, per ring count r. distance[r] row q is d_q(q, .) under q's vocabulary.
struct FoldRuns {
  std::vector<std::vector<double>> distance;  // d_i(i, j), row i
  std::vector<std::vector<double>> query_seconds, build_seconds;
  std::vector<double> vocab_seconds, sigmas, vocab_sizes;
  std::vector<std::vector<std::vector<RetrievalHit>>> top;
};

// Histograms of every patch under this fold's vocabulary (library entries and the queries), then
// each query against all other patches, for one ring count.
void answer_fold_queries(const RetrievalBenchmark& set, std::size_t descriptor_index, const RetrievalConfig& config,
                         const std::vector<std::size_t>& queries, const std::vector<std::size_t>& library,
                         std::size_t r, FoldRuns& runs) {
  const std::size_t n = set.patches.size();
  const std::size_t length = config.histogram_length();
  std::vector<float> hist(n * length);
  std::vector<double> hist_seconds(n);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t p) {
    const auto th = Clock::now();
    const std::vector<float> h = bag_of_features(config, set.patches[p].descriptors[descriptor_index]);
    hist_seconds[p] = seconds_since(th);
    std::copy(h.begin(), h.end(), hist.begin() + static_cast<std::ptrdiff_t>(p * length));
  });
  double library_hist = 0;
  for (const std::size_t p : library) library_hist += hist_seconds[p];
  runs.build_seconds[r].push_back(runs.vocab_seconds.back() + library_hist);

  // Each query against all other patches: a flat library array without the query (what a real
  // library holds), scanned by top_n_l1, timed together with the query's own histogram.
  std::vector<float> others((n - 1) * length);
  std::vector<std::size_t> others_index(n - 1);
  for (const std::size_t q : queries) {
    std::size_t e = 0;
    for (std::size_t p = 0; p < n; ++p) {
      if (p == q) continue;
      std::copy(hist.begin() + static_cast<std::ptrdiff_t>(p * length),
                hist.begin() + static_cast<std::ptrdiff_t>((p + 1) * length),
                others.begin() + static_cast<std::ptrdiff_t>(e * length));
      others_index[e++] = p;
    }
    const auto tq = Clock::now();
    const std::vector<float> hq = bag_of_features(config, set.patches[q].descriptors[descriptor_index]);
    std::vector<RetrievalHit> hits = top_n_l1(others.data(), n - 1, length, hq.data(), kTop);
    runs.query_seconds[r].push_back(seconds_since(tq));
    for (RetrievalHit& h : hits) h.entry = others_index[h.entry];
    runs.top[r][q] = std::move(hits);
    // The whole row (for ranks, the confusion and the MDS picture).
    for (std::size_t p = 0; p < n; ++p)
      runs.distance[r][q * n + p] =
          p == q ? 0.0 : l1_distance(hist.data() + q * length, hist.data() + p * length, length);
  }
}

// One fold: the vocabulary of the other folds, every patch histogrammed with it, and the fold's
// queries answered against all other patches, for every ring count.
void evaluate_fold(const RetrievalBenchmark& set, std::size_t descriptor_index, const RetrievalEvalOptions& options,
                   int fold, FoldRuns& runs) {
  const std::size_t n = set.patches.size();
  std::vector<std::size_t> queries, library;
  std::vector<Eigen::MatrixXd> training;
  for (std::size_t p = 0; p < n; ++p) {
    if (set.patches[p].fold == fold) {
      queries.push_back(p);
    } else {
      library.push_back(p);
      training.push_back(set.patches[p].descriptors[descriptor_index].values);
    }
  }
  if (queries.empty()) return;
  require(!library.empty(), MCON_ERROR_INVALID_ARGUMENT, "retrieval evaluation: a fold holds every patch");
  const RetrievalBuildOptions bo = retrieval_build_options(options, set.descriptors[descriptor_index]);
  const auto tv = Clock::now();
  RetrievalConfig config = build_retrieval_config(training, bo);
  runs.vocab_seconds.push_back(seconds_since(tv));
  runs.sigmas.push_back(config.sigma_bof);
  runs.vocab_sizes.push_back(config.vocabulary_size);
  training.clear();

  for (std::size_t r = 0; r < options.rings.size(); ++r) {
    config.rings = options.rings[r];
    answer_fold_queries(set, descriptor_index, config, queries, library, r, runs);
  }
  if (options.log)
    options.log("fold " + std::to_string(fold) + ": " + std::to_string(queries.size()) + " queries, vocabulary of " +
                std::to_string(config.vocabulary_size) + " words from " + std::to_string(library.size()) +
                " patches in " + std::to_string(runs.vocab_seconds.back()) + " s");
}

// Rank of the first same-class patch in query q's full row (ties broken by index, as top_n_l1).
int first_correct_rank(const RetrievalBenchmark& set, const std::vector<double>& distance, std::size_t q) {
  const std::size_t n = set.patches.size();
  const std::string& label = set.patches[q].label;
  std::vector<std::size_t> order;
  for (std::size_t p = 0; p < n; ++p)
    if (p != q) order.push_back(p);
  const double* row = distance.data() + q * n;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return row[a] < row[b]; });
  int rank = 0;
  for (std::size_t i = 0; i < order.size() && rank == 0; ++i)
    if (set.patches[order[i]].label == label) rank = static_cast<int>(i + 1);
  return rank;
}

// The scores of ring count r from the gathered top hits and distances.
void score_rings(const RetrievalBenchmark& set, const FoldRuns& runs, std::size_t r,
                 std::map<std::string, int>& class_size, RetrievalEvaluation& ev) {
  const std::size_t n = set.patches.size();
  ev.precision_at.assign(kTop, 0.0);
  ev.recall_at.assign(kTop, 0.0);
  std::map<std::string, int> class_hits;
  int correct = 0, recall_queries = 0;
  for (std::size_t q = 0; q < n; ++q) {
    const std::string& label = set.patches[q].label;
    const std::vector<RetrievalHit>& hits = runs.top[r][q];
    const int relevant = class_size[label] - 1;
    int same = 0;
    for (std::size_t i = 0; i < kTop; ++i) {
      if (i < hits.size() && set.patches[hits[i].entry].label == label) ++same;
      ev.precision_at[i] += static_cast<double>(same) / static_cast<double>(i + 1);
      if (relevant > 0) ev.recall_at[i] += static_cast<double>(same) / relevant;
    }
    if (relevant > 0) ++recall_queries;
    const bool hit = !hits.empty() && set.patches[hits[0].entry].label == label;
    if (hit) {
      ++correct;
      ++class_hits[label];
    } else if (!hits.empty()) {
      ++ev.confusion[{label, set.patches[hits[0].entry].label}];
      const int rank = first_correct_rank(set, runs.distance[r], q);
      ev.misses.push_back({static_cast<int>(q), static_cast<int>(hits[0].entry), rank});
    }
  }
  ev.nn_accuracy = static_cast<double>(correct) / static_cast<double>(n);
  for (double& v : ev.precision_at) v /= static_cast<double>(n);
  for (double& v : ev.recall_at) v = recall_queries > 0 ? v / recall_queries : 0.0;
  for (const auto& [label, size] : class_size)
    ev.class_nn_accuracy[label] = static_cast<double>(class_hits[label]) / static_cast<double>(size);
}

}  // namespace

std::vector<RetrievalEvaluation> evaluate_retrieval(const RetrievalBenchmark& set, std::size_t descriptor_index,
                                                    const RetrievalEvalOptions& options) {
  require(descriptor_index < set.descriptors.size(), MCON_ERROR_INVALID_ARGUMENT,
          "retrieval evaluation: descriptor index out of range");
  require(!options.rings.empty(), MCON_ERROR_INVALID_ARGUMENT, "retrieval evaluation: no ring count");
  const std::size_t n = set.patches.size();
  require(n >= 2, MCON_ERROR_INVALID_ARGUMENT, "retrieval evaluation: need at least two patches");

  const std::size_t R = options.rings.size();
  // Per fold: the vocabulary of the other folds, every patch histogrammed with it, and the fold's
  // queries answered against all other patches. distance[r] row q is d_q(q, .) under q's vocabulary.
  std::vector<RetrievalEvaluation> results(R);
  FoldRuns runs;
  runs.distance.assign(R, std::vector<double>(n * n, 0.0));
  runs.query_seconds.resize(R);
  runs.build_seconds.resize(R);
  runs.top.assign(R, std::vector<std::vector<RetrievalHit>>(n));
  for (int fold = 0; fold < set.folds; ++fold) evaluate_fold(set, descriptor_index, options, fold, runs);

  std::map<std::string, int> class_size;
  for (const BenchmarkPatch& p : set.patches) ++class_size[p.label];

  for (std::size_t r = 0; r < R; ++r) {
    RetrievalEvaluation& ev = results[r];
    ev.descriptor = set.descriptors[descriptor_index];
    ev.rings = options.rings[r];
    ev.vocabulary_size = static_cast<int>(median_of(runs.vocab_sizes));
    ev.sigma_bof = median_of(runs.sigmas);
    ev.class_size = class_size;
    score_rings(set, runs, r, class_size, ev);
    ev.library_build_seconds = median_of(runs.build_seconds[r]);
    ev.vocabulary_seconds = median_of(runs.vocab_seconds);
    ev.query_seconds_median = median_of(runs.query_seconds[r]);
    ev.distances.assign(n * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        ev.distances[i * n + j] = 0.5 * (runs.distance[r][i * n + j] + runs.distance[r][j * n + i]);
  }
  return results;
}

double median_of(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

}  // namespace mcon::tools
