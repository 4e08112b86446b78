#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>

#include <zlib.h>

#include "base/error.h"
#include "io/file_suffix.h"
#include "io/mesh_io.h"

namespace mcon::io {
namespace {

constexpr const char* kLimitVariable = "MACROCON_MAX_INPUT_BYTES";

std::string raise_hint(std::size_t limit) {
  return " (the input limit is " + std::to_string(limit) + " bytes; set the environment variable " + kLimitVariable +
         "=<bytes> to raise it)";
}

struct GzFile {
  gzFile f;
  ~GzFile() {
    if (f != nullptr) gzclose(f);
  }
};

}  // namespace

std::size_t max_input_bytes(std::size_t requested) {
  if (requested != 0) return requested;
  const char* text = std::getenv(kLimitVariable);
  if (text == nullptr || *text == '\0') return kDefaultMaxInputBytes;
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text, &end, 10);
  require(*text >= '0' && *text <= '9' && *end == '\0' && errno == 0 && value > 0 &&
              value <= std::numeric_limits<std::size_t>::max(),
          MCON_ERROR_INVALID_ARGUMENT,
          std::string(kLimitVariable) + " is '" + text + "', expected a positive number of bytes (e.g. 4294967296)");
  return static_cast<std::size_t>(value);
}

std::string read_file_maybe_gz(const std::string& path, std::size_t max_bytes) {
  const std::size_t limit = max_input_bytes(max_bytes);
  if (!is_gzip_path(path)) {
    std::ifstream in(path, std::ios::binary);
    require(static_cast<bool>(in), MCON_ERROR_IO, "cannot open '" + path + "'");
    struct stat st {};
    const bool regular = ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
    require(!regular || static_cast<std::uintmax_t>(st.st_size) <= limit,
            MCON_ERROR_IO, "'" + path + "' has more than " + std::to_string(limit) + " bytes" + raise_hint(limit));
    std::string data;
    std::size_t size = 0;
    // In chunks, checked as they come: the size above says nothing for pipes or growing files. The
    // first chunk is the file's size plus one byte (to see the end), so a small file does not
    // allocate and zero a whole megabyte; later chunks double up to 1 MiB.
    std::size_t step = std::clamp<std::size_t>(regular ? static_cast<std::size_t>(st.st_size) + 1 : 0, 4096, 1u << 20);
    while (in) {
      require(size <= limit, MCON_ERROR_IO,
              "'" + path + "' has more than " + std::to_string(limit) + " bytes" + raise_hint(limit));
      data.resize(size + step);
      in.read(&data[size], static_cast<std::streamsize>(step));
      size += static_cast<std::size_t>(in.gcount());
      step = std::min<std::size_t>(2 * step, 1u << 20);
    }
    require(!in.bad(), MCON_ERROR_IO, "error reading '" + path + "'");
    require(size <= limit, MCON_ERROR_IO,
            "'" + path + "' has more than " + std::to_string(limit) + " bytes" + raise_hint(limit));
    data.resize(size);
    return data;
  }
  const GzFile file{gzopen(path.c_str(), "rb")};
  require(file.f != nullptr, MCON_ERROR_IO, "cannot open '" + path + "'");
  // One byte past the limit is room enough to notice a file that exceeds it.
  const std::size_t room = limit == std::numeric_limits<std::size_t>::max() ? limit : limit + 1;
  std::string data;
  std::size_t size = 0;
  for (;;) {
    // Decompress straight into the string, growing it geometrically up to the limit.
    if (data.size() - size < (1u << 16) && data.size() < room)
      data.resize(std::min(std::max<std::size_t>(2 * data.size(), 1u << 17), room));
    if (size == data.size())  // `room` bytes and not at the end: over the limit
      fail(MCON_ERROR_IO, "'" + path + "' decompresses to more than " + std::to_string(limit) + " bytes" +
                              raise_hint(limit));
    const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(data.size() - size, 1u << 30));
    const int n = gzread(file.f, &data[size], chunk);
    // gzread returns the data before a premature end without failing; gzerror then reports
    // Z_BUF_ERROR, so a truncated archive is an error rather than a silently shorter file.
    int errnum = Z_OK;
    const char* message = gzerror(file.f, &errnum);
    if (n < 0 || (n == 0 && errnum != Z_OK))
      fail(MCON_ERROR_IO, "error decompressing '" + path + "': " + (message ? message : "unknown zlib error"));
    if (n == 0) break;
    size += static_cast<std::size_t>(n);
  }
  require(size <= limit, MCON_ERROR_IO,
          "'" + path + "' decompresses to more than " + std::to_string(limit) + " bytes" + raise_hint(limit));
  data.resize(size);
  data.shrink_to_fit();
  return data;
}

}  // namespace mcon::io
