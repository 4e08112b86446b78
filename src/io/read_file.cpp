#include <fstream>
#include <iterator>

#include <zlib.h>

#include "error.h"
#include "io/mesh_io.h"

namespace mcon::io {

std::string read_file_maybe_gz(const std::string& path) {
  const bool gz = path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
  if (!gz) {
    std::ifstream in(path, std::ios::binary);
    require(static_cast<bool>(in), MCON_ERROR_IO, "cannot open '" + path + "'");
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    require(!in.bad(), MCON_ERROR_IO, "error reading '" + path + "'");
    return data;
  }
  gzFile f = gzopen(path.c_str(), "rb");
  require(f != nullptr, MCON_ERROR_IO, "cannot open '" + path + "'");
  std::string data;
  char buffer[1 << 16];
  for (;;) {
    const int n = gzread(f, buffer, sizeof(buffer));
    if (n < 0) {
      int errnum = 0;
      const std::string msg = gzerror(f, &errnum);
      gzclose(f);
      fail(MCON_ERROR_IO, "error decompressing '" + path + "': " + msg);
    }
    if (n == 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
  }
  gzclose(f);
  return data;
}

}  // namespace mcon::io
