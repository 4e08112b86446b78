// Leave-family-out retrieval (issue 14): a library built from one model family only (MakeHuman
// people or ICT faces), queried with the patches of the other family, so that nothing of the
// query's family chooses the vocabulary or fills the library. Top-1 and top-3 by class label.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "common/retrieval_benchmark.h"

namespace mcon::tools {

struct LeaveFamilyOutResult {
  std::string library_model, query_model;
  double radius_scale = 1;  // of the query patches, x the class's relative radius
  int queries = 0, library_entries = 0;
  int failed_queries = 0;     // query patches that could not be cut at this radius (not counted)
  double top1 = 0, top3 = 0;  // share of queries whose first (any of the first 3) hit has their class
  // The same for the first 3 distinct suggestions (library/distinct_suggestions.h: one per class),
  // what mcon_library_query_distinct returns.
  double top3_distinct = 0;
  std::map<std::string, double> class_top1, class_top3, class_top3_distinct;
  std::map<std::string, int> class_size;
};

// The vocabulary (normalization, k-means, sigma) is fitted on `library`'s patches only, every
// library patch is an entry, and every patch of `queries` is answered with its top 3 (L1 on
// bag-of-features histograms, options.rings.front() rings). Descriptor `descriptor_index` of both
// sets. A query class that the library does not hold still counts (as a miss).
LeaveFamilyOutResult evaluate_leave_family_out(const RetrievalBenchmark& library, const RetrievalBenchmark& queries,
                                               const RetrievalEvalOptions& options, std::size_t descriptor_index = 0);

// The benchmark: eye, nose, mouth, ear and face patches of `base.people` MakeHuman people
// and `base.faces` ICT faces (base's seed, descriptor and re-tessellation), each family's library at
// radius x1.0 queried by the other family's patches at x0.7, x1.0 and x1.4: six results, MakeHuman
// library first, scales in that order.
std::vector<LeaveFamilyOutResult> leave_family_out(const RetrievalBenchmarkOptions& base,
                                                   const RetrievalEvalOptions& options);

}  // namespace mcon::tools
