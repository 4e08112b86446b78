#include <cerrno>
#include <cstdio>
#include <cstring>
#include <algorithm>

#include <zlib.h>

#include "base/error.h"
#include "io/file_suffix.h"
#include "io/mesh_io.h"

namespace mcon::io {
namespace {

void write_gz(const std::string& path, std::string_view bytes) {
  gzFile f = gzopen(path.c_str(), "wb");
  require(f != nullptr, MCON_ERROR_IO, "cannot create '" + path + "'");
  std::size_t done = 0;
  while (done < bytes.size()) {
    const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(bytes.size() - done, 1u << 24));
    const int n = gzwrite(f, bytes.data() + done, chunk);
    if (n <= 0) {
      int errnum = 0;
      const std::string msg = gzerror(f, &errnum);
      gzclose(f);
      fail(MCON_ERROR_IO, "error writing '" + path + "': " + msg);
    }
    done += static_cast<std::size_t>(n);
  }
  require(gzclose(f) == Z_OK, MCON_ERROR_IO, "error closing '" + path + "'");
}

}  // namespace

void write_file_maybe_gz(const std::string& path, std::string_view bytes) {
  if (is_gzip_path(path)) {
    write_gz(path, bytes);
    return;
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  require(f != nullptr, MCON_ERROR_IO, "cannot create '" + path + "': " + std::strerror(errno));
  const std::size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
  const int write_errno = errno;
  const bool closed = std::fclose(f) == 0;
  require(written == bytes.size(), MCON_ERROR_IO, "error writing '" + path + "': " + std::strerror(write_errno));
  require(closed, MCON_ERROR_IO, "error writing '" + path + "': " + std::strerror(errno));
}

}  // namespace mcon::io
