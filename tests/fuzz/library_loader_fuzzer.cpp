// libFuzzer target for the constraint library loader (hostile files, docs/design.md §6). Any input
// must either load or throw mcon::Error with INVALID_LIBRARY or UNSUPPORTED; a crash, a sanitizer
// report, another exception or status, or an accepted library that does not survive its own
// save/load round trip unchanged is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "base/error.h"
#include "library/library_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mcon::ConstraintLibrary library;
  try {
    library = mcon::load_library_from_buffer(data, size);
  } catch (const mcon::Error& e) {
    if (e.status() != MCON_ERROR_INVALID_LIBRARY && e.status() != MCON_ERROR_UNSUPPORTED) {
      std::fprintf(stderr, "unexpected status %d: %s\n", static_cast<int>(e.status()), e.what());
      std::abort();
    }
    return 0;
  }
  // Accepted: serializing and loading again must give the same bytes (the validator and the
  // writer agree on what a library is).
  const std::vector<std::uint8_t> bytes = mcon::serialize_library(library);
  const mcon::ConstraintLibrary again = mcon::load_library_from_buffer(bytes.data(), bytes.size());
  if (mcon::serialize_library(again) != bytes) {
    std::fprintf(stderr, "accepted library does not round-trip\n");
    std::abort();
  }
  return 0;
}
