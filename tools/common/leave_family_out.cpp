#include "common/leave_family_out.h"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "base/error.h"
#include "library/distinct_suggestions.h"
#include "retrieval/bag_of_features.h"
#include "retrieval/retrieval_index.h"

namespace mcon::tools {

LeaveFamilyOutResult evaluate_leave_family_out(const RetrievalBenchmark& library, const RetrievalBenchmark& queries,
                                               const RetrievalEvalOptions& options, std::size_t descriptor_index) {
  require(!library.patches.empty() && !queries.patches.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "leave-family-out: the library and the queries need at least one patch each");
  std::vector<Eigen::MatrixXd> training;
  for (const BenchmarkPatch& p : library.patches) training.push_back(p.descriptors[descriptor_index].values);
  RetrievalConfig config =
      build_retrieval_config(training, retrieval_build_options(options, library.descriptors[descriptor_index]));
  config.rings = options.rings.empty() ? 1u : options.rings.front();

  const std::size_t n = library.patches.size(), length = config.histogram_length();
  std::vector<float> entries(n * length);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t e) {
    const std::vector<float> h = bag_of_features(config, library.patches[e].descriptors[descriptor_index]);
    std::copy(h.begin(), h.end(), entries.begin() + static_cast<std::ptrdiff_t>(e * length));
  });
  std::vector<MacroConstraint> labels(n);  // only the class labels, for the distinct suggestions
  for (std::size_t e = 0; e < n; ++e) labels[e].class_label = library.patches[e].label;
  const std::size_t nq = queries.patches.size();
  std::vector<char> hit1(nq, 0), hit3(nq, 0), hit3d(nq, 0);
  tbb::parallel_for(std::size_t{0}, nq, [&](std::size_t q) {
    const BenchmarkPatch& query = queries.patches[q];
    const std::vector<float> hq = bag_of_features(config, query.descriptors[descriptor_index]);
    const std::vector<RetrievalHit> ranked = top_n_l1(entries.data(), n, length, hq.data(), n);
    for (std::size_t k = 0; k < std::min<std::size_t>(3, ranked.size()); ++k)
      if (library.patches[ranked[k].entry].label == query.label) {
        hit1[q] = hit1[q] || k == 0;
        hit3[q] = 1;
      }
    for (const DistinctSuggestion& s : distinct_suggestions(ranked, labels, 3))
      hit3d[q] = hit3d[q] || library.patches[s.entry].label == query.label;
  });

  LeaveFamilyOutResult r;
  r.library_model = library.patches.front().model;
  r.query_model = queries.patches.front().model;
  r.queries = static_cast<int>(nq);
  r.library_entries = static_cast<int>(n);
  for (std::size_t q = 0; q < nq; ++q) {
    const std::string& c = queries.patches[q].label;
    ++r.class_size[c];
    r.class_top1[c] += hit1[q];
    r.class_top3[c] += hit3[q];
    r.class_top3_distinct[c] += hit3d[q];
    r.top1 += hit1[q];
    r.top3 += hit3[q];
    r.top3_distinct += hit3d[q];
  }
  for (auto& [c, size] : r.class_size) {
    r.class_top1[c] /= size;
    r.class_top3[c] /= size;
    r.class_top3_distinct[c] /= size;
  }
  r.top1 /= static_cast<double>(nq);
  r.top3 /= static_cast<double>(nq);
  r.top3_distinct /= static_cast<double>(nq);
  return r;
}

std::vector<LeaveFamilyOutResult> leave_family_out(const RetrievalBenchmarkOptions& base,
                                                   const RetrievalEvalOptions& options) {
  require(base.people > 0 && base.faces > 0, MCON_ERROR_INVALID_ARGUMENT,
          "leave-family-out: needs people and faces (--people N --faces N, both >= 1)");
  const double scales[3] = {0.7, 1.0, 1.4};
  std::vector<RetrievalBenchmark> sets[2];  // [family][scale]
  for (int family = 0; family < 2; ++family)
    for (const double scale : scales) {
      RetrievalBenchmarkOptions o = base;
      o.people = family == 0 ? base.people : 0;
      o.faces = family == 1 ? base.faces : 0;
      o.parts = {"eye", "nose", "mouth", "ear", "face"};
      o.radius_scale = scale;
      sets[family].push_back(build_retrieval_benchmark(o));
      require(scale != 1.0 || sets[family].back().failed_patches.empty(), MCON_ERROR_UNKNOWN,
              "leave-family-out: a library patch could not be cut");
    }
  std::vector<LeaveFamilyOutResult> results;
  for (int family = 0; family < 2; ++family)
    for (int s = 0; s < 3; ++s) {
      results.push_back(evaluate_leave_family_out(sets[family][1], sets[1 - family][s], options));
      results.back().radius_scale = scales[s];
      results.back().failed_queries = static_cast<int>(sets[1 - family][s].failed_patches.size());
    }
  return results;
}

}  // namespace mcon::tools
