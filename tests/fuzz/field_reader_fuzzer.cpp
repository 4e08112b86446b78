// libFuzzer target for the QuadWild field readers and the authoring inputs: the first input byte
// picks the reader (% 4: `.rosy`, `.sharp`, OBJ polylines, a value table; bit 2: plain or `.gz`;
// bit 3, tables only: `.csv` or `.ply`), the rest is the file. Any input must either read or throw
// mcon::Error with IO (or UNSUPPORTED for a `.rosy` symmetry other than 4); whatever reads must
// satisfy the readers' postconditions (finite directions; edge kinds, faces and edge indices in
// range; polylines of >= 2 finite points; tables of whole rows of finite values).
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

void read_polylines_file(const std::string& path) {
  for (const mcon::io::FilePolyline& line : mcon::io::read_obj_polylines(path)) {
    if (line.points.size() < (line.closed ? 3u : 2u)) mcon_fuzz::finding("read_obj_polylines returned a short line");
    for (const mcon::Vec3& p : line.points)
      if (!p.allFinite()) mcon_fuzz::finding("read_obj_polylines returned a non-finite point");
  }
}

void read_table_file(const std::string& path) {
  const mcon::io::ValueTable table = mcon::io::read_value_table(path);
  if (table.columns.empty() || table.values.size() % table.columns.size() != 0)
    mcon_fuzz::finding("read_value_table returned a partial row");
  for (double v : table.values)
    if (!std::isfinite(v)) mcon_fuzz::finding("read_value_table returned a non-finite value");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int kind = data[0] % 4;
  const bool rosy = kind == 0;
  const bool gz = (data[0] / 4) % 2 == 1;
  const char* suffix[4] = {".rosy", ".sharp", ".obj", (data[0] / 8) % 2 == 1 ? ".ply" : ".csv"};
  const std::string path = mcon_fuzz::write_input_file(data + 1, size - 1, std::string(suffix[kind]) + (gz ? ".gz" : ""));
  try {
    if (kind == 0) read_rosy_file(path);
    if (kind == 1) read_sharp_file(path);
    if (kind == 2) read_polylines_file(path);
    if (kind == 3) read_table_file(path);
  } catch (const mcon::Error& e) {
    if (e.status() != MCON_ERROR_IO && !(rosy && e.status() == MCON_ERROR_UNSUPPORTED)) {
      std::fprintf(stderr, "unexpected status %d: %s\n", static_cast<int>(e.status()), e.what());
      std::abort();
    }
  }
  return 0;
}
