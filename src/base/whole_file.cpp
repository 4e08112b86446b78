#include "base/whole_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "base/error.h"

namespace mcon {
namespace {

struct FileDescriptor {
  int fd;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::vector<std::uint8_t> read_whole_file(const std::string& path, std::size_t min_size, std::size_t max_size,
                                          mcon_status size_status) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is rejected below as not regular.
  const FileDescriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (file.fd < 0) fail(MCON_ERROR_IO, "cannot open '" + path + "': " + std::strerror(errno));
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) fail(MCON_ERROR_IO, "cannot stat '" + path + "': " + std::strerror(errno));
  require(S_ISREG(st.st_mode), MCON_ERROR_IO, "'" + path + "' is not a regular file");
  const auto size = static_cast<std::size_t>(st.st_size);
  require(size >= min_size && size <= max_size, size_status,
          "'" + path + "' has " + std::to_string(size) + " bytes, expected " + std::to_string(min_size) + " to " +
              std::to_string(max_size));
  std::vector<std::uint8_t> bytes(size);
  std::size_t done = 0;
  while (done < size) {
    // One read() moves at most about 2 GiB on Linux; loop for the rest and for signals.
    const ssize_t n = ::read(file.fd, bytes.data() + done, std::min<std::size_t>(size - done, std::size_t{1} << 30));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(MCON_ERROR_IO, "cannot read '" + path + "': " + std::strerror(errno));
    if (n == 0)
      fail(MCON_ERROR_IO, "'" + path + "' shrank from " + std::to_string(size) + " to " + std::to_string(done) +
                              " bytes while it was read (another process is rewriting it in place; replace files "
                              "atomically instead: write a new file and rename it over the old one)");
    done += static_cast<std::size_t>(n);
  }
  return bytes;
}

}  // namespace mcon
