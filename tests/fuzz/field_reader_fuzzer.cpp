// libFuzzer target for the QuadWild field readers: the first input byte picks `.rosy` or
// `.sharp` (and plain or `.gz`), the rest is the file. Any input must either read or throw
// mcon::Error with IO (or UNSUPPORTED for a `.rosy` symmetry other than 4); whatever reads must
// satisfy the readers' postconditions (finite directions; edge kinds, faces and edge indices in
// range).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "base/error.h"
#include "fuzz/fuzz_input_file.h"
#include "io/mesh_io.h"

namespace {

void read_rosy_file(const std::string& path) {
  for (const mcon::Vec3& d : mcon::io::read_rosy(path))
    if (!d.allFinite()) mcon_fuzz::finding("read_rosy returned a non-finite direction");
}

void read_sharp_file(const std::string& path) {
  for (const mcon::io::SharpEdge& e : mcon::io::read_sharp(path))
    if (e.face < 0 || e.edge < 0 || e.edge > 2) mcon_fuzz::finding("read_sharp returned an out-of-range edge");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool rosy = data[0] % 2 == 0;
  const bool gz = (data[0] / 2) % 2 == 1;
  const std::string path =
      mcon_fuzz::write_input_file(data + 1, size - 1, std::string(rosy ? ".rosy" : ".sharp") + (gz ? ".gz" : ""));
  try {
    if (rosy)
      read_rosy_file(path);
    else
      read_sharp_file(path);
  } catch (const mcon::Error& e) {
    if (e.status() != MCON_ERROR_IO && !(rosy && e.status() == MCON_ERROR_UNSUPPORTED)) {
      std::fprintf(stderr, "unexpected status %d: %s\n", static_cast<int>(e.status()), e.what());
      std::abort();
    }
  }
  return 0;
}
