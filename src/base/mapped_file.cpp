#include "base/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

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

MappedFile::MappedFile(const std::string& path, std::size_t min_size, std::size_t max_size,
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
  void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, file.fd, 0);
  if (p == MAP_FAILED) fail(MCON_ERROR_IO, "cannot map '" + path + "': " + std::strerror(errno));
  data_ = static_cast<const std::uint8_t*>(p);
  size_ = size;
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(const_cast<std::uint8_t*>(data_), size_);
}

}  // namespace mcon
