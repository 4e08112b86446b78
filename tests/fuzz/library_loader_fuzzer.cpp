// libFuzzer target for the constraint library loader (hostile files, docs/design.md §6), from
// memory and from a file path. Any input must either load or throw mcon::Error with
// INVALID_LIBRARY or UNSUPPORTED; a crash, a sanitizer report, another exception or status is a
// finding. So is a file load that disagrees with the memory load of the same bytes, an accepted
// library that does not survive its own save/load round trip unchanged, or one that cannot be
// queried: what the loader accepts, retrieval must handle.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "base/error.h"
#include "fuzz/fuzz_input_file.h"
#include "library/library_file.h"
#include "operators/cotan_laplacian.h"
#include "retrieval/bag_of_features.h"
#include "retrieval/retrieval_index.h"

namespace {

using mcon_fuzz::finding;

// The query side on entries the library holds: each entry's stored descriptors and vertex areas
// through bag_of_features (the ring distances from the center are Euclidean here, not geodesic:
// the fuzzer has no heat solver, and bag_of_features only bins them), then a top-n scan with an
// entry's own stored histogram, which must come first at distance 0.
void query(const mcon::ConstraintLibrary& library) {
  const mcon::RetrievalConfig& c = library.retrieval();
  if (c.vocabulary_size == 0 || library.size() == 0) return;
  const std::size_t length = c.histogram_length(), d = c.dimension;
  std::vector<float> flat;
  for (const mcon::MacroConstraint& e : library.entries()) flat.insert(flat.end(), e.histogram.begin(), e.histogram.end());
  const std::size_t queried = std::min<std::size_t>(library.size(), 4);
  for (std::size_t i = 0; i < queried; ++i) {
    const mcon::MacroConstraint& e = library.entries()[i];
    const mcon::TriMesh mesh = mcon::entry_mesh(e);
    mcon::PatchDescriptors pd;
    pd.areas = mcon::vertex_areas(mesh);
    const auto n = static_cast<Eigen::Index>(e.vertex_count());
    pd.values.resize(n, static_cast<Eigen::Index>(d));
    for (Eigen::Index v = 0; v < n; ++v)
      for (std::size_t j = 0; j < d; ++j) pd.values(v, static_cast<Eigen::Index>(j)) = e.descriptors[v * d + j];
    mcon::Vec3 center = mcon::Vec3::Zero();
    for (int k = 0; k < 3; ++k)
      center += e.center.barycentric[k] * mesh.positions[static_cast<std::size_t>(mesh.triangles[e.center.triangle][k])];
    pd.center_distance.resize(n);
    for (Eigen::Index v = 0; v < n; ++v) pd.center_distance[v] = (mesh.positions[v] - center).norm();
    std::vector<float> histogram;
    try {
      histogram = mcon::bag_of_features(c, pd);
    } catch (const mcon::Error& err) {
      finding("an accepted library's entry cannot be described for a query: ", err.what());
    }
    if (histogram.size() != length) finding("query histogram of the wrong length");
    for (float h : histogram)
      if (!(std::isfinite(h) && h >= 0)) finding("query histogram value not finite and >= 0");
    const auto hits = mcon::top_n_l1(flat.data(), library.size(), length, histogram.data(), 3);
    if (hits.empty()) finding("query found nothing");
    for (const auto& hit : hits)
      if (std::isnan(hit.distance)) finding("query distance is NaN");
    const auto self = mcon::top_n_l1(flat.data(), library.size(), length, e.histogram.data(), 1);
    if (self.size() != 1 || self[0].distance != 0) finding("an entry's own histogram is not at distance 0");
  }
}

// Loads through `load`; returns the library's bytes as saved, or an empty vector with `*status`
// set when the loader refused it with a documented status.
template <typename Load>
std::vector<std::uint8_t> load_checked(Load load, mcon_status* status) {
  *status = MCON_OK;
  try {
    return mcon::serialize_library(load());
  } catch (const mcon::Error& e) {
    if (e.status() != MCON_ERROR_INVALID_LIBRARY && e.status() != MCON_ERROR_UNSUPPORTED) {
      std::fprintf(stderr, "unexpected status %d: %s\n", static_cast<int>(e.status()), e.what());
      std::abort();
    }
    *status = e.status();
    return {};
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // As a file would be loaded (mutations almost never carry a matching checksum), from memory and
  // from a path: both must give the same answer for the same bytes.
  mcon_status memory_status = MCON_OK, file_status = MCON_OK;
  const std::vector<std::uint8_t> from_memory =
      load_checked([&] { return mcon::load_library_from_buffer(data, size); }, &memory_status);
  const std::string path = mcon_fuzz::write_input_file(data, size, ".mcl");
  const std::vector<std::uint8_t> from_file =
      load_checked([&] { return mcon::load_library_from_file(path); }, &file_status);
  if (file_status != memory_status || from_file != from_memory)
    finding("loading from a file and from memory disagree on the same bytes");
  // ... and past the checksum, so that mutations reach the Verifier and the validator behind it.
  mcon::ConstraintLibrary library;
  try {
    library = mcon::load_library_from_buffer(data, size, /*check_checksum=*/false);
  } catch (const mcon::Error& e) {
    if (e.status() != MCON_ERROR_INVALID_LIBRARY && e.status() != MCON_ERROR_UNSUPPORTED) {
      std::fprintf(stderr, "unexpected status %d: %s\n", static_cast<int>(e.status()), e.what());
      std::abort();
    }
    return 0;
  }
  // Accepted: serializing (the bytes mcon_library_save_memory returns) and loading again must
  // give the same bytes (the validator and the writer agree on what a library is).
  const std::vector<std::uint8_t> bytes = mcon::serialize_library(library);
  const mcon::ConstraintLibrary again = mcon::load_library_from_buffer(bytes.data(), bytes.size());
  if (mcon::serialize_library(again) != bytes) finding("accepted library does not round-trip");
  query(library);
  return 0;
}
