#include <algorithm>
#include <fstream>
#include <iterator>

#include <zlib.h>

#include "base/error.h"
#include "io/file_suffix.h"
#include "io/mesh_io.h"

namespace mcon::io {

std::string read_file_maybe_gz(const std::string& path) {
  if (!is_gzip_path(path)) {
    std::ifstream in(path, std::ios::binary);
    require(static_cast<bool>(in), MCON_ERROR_IO, "cannot open '" + path + "'");
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    require(!in.bad(), MCON_ERROR_IO, "error reading '" + path + "'");
    return data;
  }
  gzFile f = gzopen(path.c_str(), "rb");
  require(f != nullptr, MCON_ERROR_IO, "cannot open '" + path + "'");
  std::string data;
  std::size_t size = 0;
  for (;;) {
    // Decompress straight into the string, growing it geometrically.
    if (data.size() - size < (1u << 16)) data.resize(std::max<std::size_t>(2 * data.size(), 1u << 20));
    const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(data.size() - size, 1u << 30));
    const int n = gzread(f, &data[size], chunk);
    // gzread returns the data before a premature end without failing; gzerror then reports
    // Z_BUF_ERROR, so a truncated archive is an error rather than a silently shorter file.
    int errnum = Z_OK;
    const char* message = gzerror(f, &errnum);
    if (n < 0 || (n == 0 && errnum != Z_OK)) {
      const std::string msg = message ? message : "unknown zlib error";
      gzclose(f);
      fail(MCON_ERROR_IO, "error decompressing '" + path + "': " + msg);
    }
    if (n == 0) break;
    size += static_cast<std::size_t>(n);
  }
  data.resize(size);
  data.shrink_to_fit();
  gzclose(f);
  return data;
}

}  // namespace mcon::io
