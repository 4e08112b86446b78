#include "library/library_retrieval.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include "operators/cotan_laplacian.h"
#include "base/error.h"
#include "base/parallel_blocks.h"
#include "retrieval/retrieval_descriptors.h"

namespace mcon {
namespace {

// The patch as a library stores it: positions rounded to float (the file's type).
TriMesh float_rounded(const TriMesh& mesh) {
  // Through the entry's own conversion (set_entry_mesh / entry_mesh), so both are rounded by the
  // same code. (An in-place `p[k] = double(float(p[k]))` loop over Vec3s left the x and y of the
  // last vertices unrounded in the -O3 Release build; observed, not analysed.)
  MacroConstraint scratch;
  set_entry_mesh(scratch, mesh);
  return entry_mesh(scratch);
}

// Descriptor values as stored (float) and read back, so an entry and a query of the same patch
// go through exactly the same numbers.
void round_to_float(Eigen::MatrixXd& values) {
  for (Eigen::Index i = 0; i < values.size(); ++i)
    values.data()[i] = static_cast<double>(static_cast<float>(values.data()[i]));
}

// Caller-supplied descriptors: n x d, finite and representable as float.
void check_custom_descriptors(const Eigen::MatrixXd& values, std::size_t n, std::uint32_t dimension) {
  require(values.cols() >= 1, MCON_ERROR_INVALID_ARGUMENT, "custom descriptors have dimension 0");
  require(static_cast<std::size_t>(values.rows()) == n, MCON_ERROR_INVALID_ARGUMENT,
          "custom descriptors have " + std::to_string(values.rows()) + " rows, the patch has " + std::to_string(n) +
              " vertices");
  require(dimension == 0 || static_cast<std::uint32_t>(values.cols()) == dimension, MCON_ERROR_INVALID_ARGUMENT,
          "custom descriptors have dimension " + std::to_string(values.cols()) + ", the library uses " +
              std::to_string(dimension));
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  for (Eigen::Index v = 0; v < values.rows(); ++v)
    for (Eigen::Index j = 0; j < values.cols(); ++j)
      require(std::isfinite(values(v, j)) && std::abs(values(v, j)) <= kFloatMax, MCON_ERROR_NON_FINITE,
              "custom descriptor value " + std::to_string(j) + " of vertex " + std::to_string(v) +
                  " is not finite (or too large for float)");
}

Eigen::MatrixXd stored_descriptors(const MacroConstraint& e, std::uint32_t d) {
  const Eigen::Index n = static_cast<Eigen::Index>(e.vertex_count());
  Eigen::MatrixXd values(n, static_cast<Eigen::Index>(d));
  for (Eigen::Index v = 0; v < n; ++v)
    for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(d); ++j)
      values(v, j) = static_cast<double>(e.descriptors[static_cast<std::size_t>(v) * d + static_cast<std::size_t>(j)]);
  return values;
}

std::vector<float> to_float_rows(const Eigen::MatrixXd& values) {
  std::vector<float> out(static_cast<std::size_t>(values.size()));
  const std::size_t d = static_cast<std::size_t>(values.cols());
  for (Eigen::Index v = 0; v < values.rows(); ++v)
    for (Eigen::Index j = 0; j < values.cols(); ++j)
      out[static_cast<std::size_t>(v) * d + static_cast<std::size_t>(j)] = static_cast<float>(values(v, j));
  return out;
}

bool has_vocabulary(const RetrievalConfig& c) { return c.vocabulary_size > 0; }

void report(const std::function<bool(double)>& progress, double fraction) {
  if (progress && !progress(fraction)) fail(MCON_ERROR_CANCELLED, "cancelled by the progress callback");
}

}  // namespace

ConstraintLibrary with_config(const ConstraintLibrary& like, RetrievalConfig config,
                              std::vector<MacroConstraint> entries) {
  ConstraintLibrary out(std::move(config), std::move(entries));
  out.set_name(like.name());
  out.set_description(like.description());
  return out;
}

MacroConstraint make_library_entry(const Patch& patch, MacroConstraint content, const RetrievalConfig& config,
                                   const Eigen::MatrixXd* custom_descriptors) {
  require(patch.center.triangle >= 0 && patch.center.triangle < patch.mesh.num_triangles(),
          MCON_ERROR_INVALID_ARGUMENT, "the patch has no center triangle");
  MacroConstraint e = std::move(content);
  set_entry_mesh(e, patch.mesh);
  e.center.triangle = patch.center.triangle;
  e.center.barycentric = patch.center.barycentric;
  e.source_scale = patch.radius;
  for (int k = 0; k < 3; ++k) e.source_origin[static_cast<std::size_t>(k)] = patch.center_position[k];

  const bool custom = is_custom_descriptor(config.descriptor);
  Eigen::MatrixXd values;
  if (custom) {
    require(custom_descriptors != nullptr, MCON_ERROR_INVALID_ARGUMENT,
            "the library uses caller-supplied descriptors ('" + config.descriptor +
                "'): give the entry's per-vertex descriptors");
    check_custom_descriptors(*custom_descriptors, e.vertex_count(), config.dimension);
    values = *custom_descriptors;
    round_to_float(values);
  } else {
    require(custom_descriptors == nullptr, MCON_ERROR_INVALID_ARGUMENT,
            "the library computes its own descriptor ('" + config.descriptor +
                "'): caller-supplied descriptors are only for a custom library (an empty one becomes custom)");
    require(is_builtin_descriptor(config.descriptor), MCON_ERROR_UNSUPPORTED,
            "this build cannot compute the library's descriptor '" + config.descriptor + "'");
    values = compute_retrieval_descriptor(entry_mesh(e), config.descriptor);
    round_to_float(values);
  }
  e.descriptors = to_float_rows(values);
  e.histogram.clear();
  if (has_vocabulary(config)) {
    PatchDescriptors pd;
    pd.values = std::move(values);
    const PatchDescriptors geometry = describe_library_entry(e, 0, "", config.rings);
    pd.areas = geometry.areas;
    pd.center_distance = geometry.center_distance;
    e.histogram = bag_of_features(config, pd);
  }
  return e;
}

std::uint64_t add_library_entry(ConstraintLibrary& library, const Patch& patch, MacroConstraint content,
                                const Eigen::MatrixXd* custom_descriptors) {
  const RetrievalConfig& current = library.retrieval();
  if (library.size() == 0 && !has_vocabulary(current)) {
    // The first entry fixes the dimension (and an empty library takes caller descriptors).
    RetrievalConfig config = current;
    if (custom_descriptors != nullptr && !is_custom_descriptor(config.descriptor))
      config.descriptor = kCustomDescriptorApi;
    if (custom_descriptors == nullptr && is_custom_descriptor(config.descriptor))
      config.descriptor = kDescriptorCurv9;
    const std::uint32_t d = custom_descriptors != nullptr
                                ? static_cast<std::uint32_t>(custom_descriptors->cols())
                                : static_cast<std::uint32_t>(builtin_descriptor_dimension(config.descriptor));
    if (d != config.dimension) {
      config.dimension = d;
      config.normalization_mean.assign(d, 0.0);  // placeholders until a vocabulary is built
      config.normalization_scale.assign(d, 1.0);
    }
    MacroConstraint e = make_library_entry(patch, std::move(content), config, custom_descriptors);
    ConstraintLibrary fresh = with_config(library, config, {});
    const std::uint64_t id = fresh.add_entry(std::move(e));
    library = std::move(fresh);
    return id;
  }
  MacroConstraint e = make_library_entry(patch, std::move(content), current, custom_descriptors);
  return library.add_entry(std::move(e));
}

PatchDescriptors describe_library_entry(const MacroConstraint& entry, std::uint32_t dimension,
                                        const std::string& recompute, std::uint32_t rings) {
  const TriMesh mesh = entry_mesh(entry);
  PatchDescriptors pd;
  if (rings > 1) {
    pd = patch_areas_and_center_distance(mesh, entry.center);
  } else {
    pd.areas = vertex_areas(mesh);  // plain bag-of-features: no distances needed
  }
  if (!recompute.empty()) {
    pd.values = compute_retrieval_descriptor(mesh, recompute);
    round_to_float(pd.values);
  } else if (dimension > 0) {
    pd.values = stored_descriptors(entry, dimension);
  }
  return pd;
}

ConstraintLibrary build_library_retrieval(const ConstraintLibrary& library, const LibraryRetrievalOptions& options) {
  const RetrievalConfig& current = library.retrieval();
  const std::size_t count = library.size();
  require(count >= 1, MCON_ERROR_INVALID_ARGUMENT, "building retrieval needs at least one entry");
  require(options.vocabulary_size >= 1 && options.vocabulary_size <= 65536, MCON_ERROR_INVALID_ARGUMENT,
          "vocabulary_size is " + std::to_string(options.vocabulary_size) + ", expected 1..65536");
  require(options.rings >= 1 && options.rings <= 64, MCON_ERROR_INVALID_ARGUMENT,
          "rings is " + std::to_string(options.rings) + ", expected 1..64");
  require(std::isfinite(options.sigma_bof) && options.sigma_bof >= 0, MCON_ERROR_INVALID_ARGUMENT,
          "sigma_bof must be 0 (median rule) or finite and positive");

  // Which descriptor, and whether the stored values can be reused.
  std::string recompute;
  std::uint32_t dimension = current.dimension;
  if (is_custom_descriptor(options.descriptor)) {
    require(options.descriptor == current.descriptor, MCON_ERROR_INVALID_ARGUMENT,
            "custom descriptors cannot be computed: the entries carry '" + current.descriptor + "', not '" +
                options.descriptor + "' (add entries with caller-supplied descriptors)");
  } else {
    const std::uint32_t d = static_cast<std::uint32_t>(builtin_descriptor_dimension(options.descriptor));
    if (options.descriptor != current.descriptor || d != current.dimension) recompute = options.descriptor;
    dimension = d;
  }

  // 1. Every entry's descriptors, areas and ring distances (independent per entry).
  const auto& entries = library.entries();
  std::vector<PatchDescriptors> described(count);
  std::atomic<std::size_t> done{0};
  std::atomic<bool> cancelled{false};
  report(options.progress, 0.0);
  for_each_block(count, 1, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      if (cancelled.load()) return;
      described[i] = describe_library_entry(entries[i], recompute.empty() ? dimension : 0, recompute, options.rings);
      const std::size_t finished = ++done;
      if (options.progress && !options.progress(0.7 * static_cast<double>(finished) / static_cast<double>(count)))
        cancelled.store(true);
    }
  });
  require(!cancelled.load(), MCON_ERROR_CANCELLED, "cancelled by the progress callback");

  // 2. Normalization, vocabulary (k-means++ then Lloyd) and sigma over all library vertices.
  std::vector<Eigen::MatrixXd> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = described[i].values;
  RetrievalBuildOptions build;
  build.descriptor = options.descriptor;
  build.vocabulary_size = static_cast<int>(options.vocabulary_size);
  build.rings = options.rings;
  build.sigma_bof = options.sigma_bof;
  build.seed = options.seed;
  RetrievalConfig config = build_retrieval_config(values, build);
  values.clear();
  report(options.progress, 0.8);

  // 3. Every entry's histogram (eq. 3.1 per ring).
  std::vector<MacroConstraint> out = entries;
  done.store(0);
  for_each_block(count, 1, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      if (cancelled.load()) return;
      if (!recompute.empty()) out[i].descriptors = to_float_rows(described[i].values);
      out[i].histogram = bag_of_features(config, described[i]);
      described[i] = PatchDescriptors{};
      const std::size_t finished = ++done;
      if (options.progress &&
          !options.progress(0.8 + 0.2 * static_cast<double>(finished) / static_cast<double>(count)))
        cancelled.store(true);
    }
  });
  require(!cancelled.load(), MCON_ERROR_CANCELLED, "cancelled by the progress callback");
  return with_config(library, std::move(config), std::move(out));
}

std::vector<float> query_histogram(const RetrievalConfig& config, const Patch& patch,
                                   const Eigen::MatrixXd* custom_descriptors) {
  require(has_vocabulary(config), MCON_ERROR_INVALID_ARGUMENT,
          "the library has no vocabulary yet: build retrieval first");
  require(patch.center.triangle >= 0 && patch.center.triangle < patch.mesh.num_triangles(),
          MCON_ERROR_INVALID_ARGUMENT, "the query patch has no center triangle");
  const TriMesh mesh = float_rounded(patch.mesh);
  PatchDescriptors pd;
  if (config.rings > 1) {
    pd = patch_areas_and_center_distance(mesh, patch.center);
  } else {
    pd.areas = vertex_areas(mesh);
  }
  if (is_custom_descriptor(config.descriptor)) {
    require(custom_descriptors != nullptr, MCON_ERROR_INVALID_ARGUMENT,
            "the library uses caller-supplied descriptors ('" + config.descriptor +
                "'): query with the patch's descriptors");
    check_custom_descriptors(*custom_descriptors, mesh.positions.size(), config.dimension);
    pd.values = *custom_descriptors;
  } else {
    require(custom_descriptors == nullptr, MCON_ERROR_INVALID_ARGUMENT,
            "the library computes its own descriptor ('" + config.descriptor + "'): no caller descriptors");
    require(is_builtin_descriptor(config.descriptor), MCON_ERROR_UNSUPPORTED,
            "this build cannot compute the library's descriptor '" + config.descriptor + "'");
    pd.values = compute_retrieval_descriptor(mesh, config.descriptor);
  }
  round_to_float(pd.values);
  return bag_of_features(config, pd);
}

std::vector<float> flat_histograms(const ConstraintLibrary& library) {
  const std::size_t length = library.retrieval().histogram_length();
  std::vector<float> flat;
  flat.reserve(library.size() * length);
  for (const MacroConstraint& e : library.entries()) flat.insert(flat.end(), e.histogram.begin(), e.histogram.end());
  return flat;
}

std::vector<RetrievalHit> query_top_n(const RetrievalConfig& config, const std::vector<float>& flat,
                                      const std::vector<float>& histogram, std::size_t n) {
  const std::size_t length = config.histogram_length();
  require(n >= 1, MCON_ERROR_INVALID_ARGUMENT, "n must be at least 1");
  require(length > 0, MCON_ERROR_INVALID_ARGUMENT, "the library has no vocabulary yet: build retrieval first");
  require(histogram.size() == length, MCON_ERROR_INVALID_ARGUMENT,
          "query histogram has " + std::to_string(histogram.size()) + " values, the library uses " +
              std::to_string(length));
  require(flat.size() % length == 0, MCON_ERROR_UNKNOWN, "histogram array is not a whole number of entries");
  const std::size_t count = flat.size() / length;
  if (count == 0) return {};
  return top_n_l1(flat.data(), count, length, histogram.data(), n);
}

}  // namespace mcon
