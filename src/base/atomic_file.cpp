#include "base/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "base/error.h"

namespace mcon {
namespace {

[[noreturn]] void io_fail(const std::string& what, int err) {
  fail(MCON_ERROR_IO, what + ": " + std::strerror(err));
}

// The temporary file until it has been renamed: closed and removed on every failure path.
class TempFile {
 public:
  TempFile(const std::string& dir, const std::string& base) {
    static std::atomic<unsigned> counter{0};
    // O_EXCL on a name of our own: never reuses or follows an existing file; mode 0666 & ~umask.
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ = dir + "/." + base + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
      fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd_ >= 0) return;
      if (errno != EEXIST) break;
    }
    const int err = errno;
    path_.clear();
    io_fail("cannot create a temporary file in '" + dir + "'", err);
  }
  ~TempFile() {
    if (file_) std::fclose(file_);
    else if (fd_ >= 0) ::close(fd_);
    if (!path_.empty()) ::unlink(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  void write(const void* data, std::size_t size, const struct stat* keep_mode_of) {
    if (keep_mode_of && ::fchmod(fd_, keep_mode_of->st_mode & 07777) != 0)
      io_fail("cannot set the permissions of '" + path_ + "'", errno);
    file_ = ::fdopen(fd_, "wb");
    if (!file_) io_fail("cannot open '" + path_ + "' for writing", errno);
    errno = 0;
    if (size > 0 && std::fwrite(data, 1, size, file_) != size) io_fail("cannot write '" + path_ + "'", errno ? errno : EIO);
    if (std::fflush(file_) != 0) io_fail("cannot write '" + path_ + "'", errno);
    if (::fsync(fd_) != 0) io_fail("cannot fsync '" + path_ + "'", errno);
    FILE* f = file_;
    file_ = nullptr;
    fd_ = -1;
    if (std::fclose(f) != 0) io_fail("cannot close '" + path_ + "'", errno);
  }

  void rename_to(const std::string& target) {
    if (::rename(path_.c_str(), target.c_str()) != 0)
      io_fail("cannot rename '" + path_ + "' to '" + target + "'", errno);
    path_.clear();  // it is the target now: nothing to remove
  }

 private:
  std::string path_;
  int fd_ = -1;
  FILE* file_ = nullptr;
};

}  // namespace

void write_file_atomic(const std::string& path, const void* data, std::size_t size) {
  require(!path.empty(), MCON_ERROR_IO, "cannot save to an empty path");
  std::string target = path;
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
    if (char* resolved = ::realpath(path.c_str(), nullptr)) {
      target = resolved;
      std::free(resolved);
    }
  }
  const bool exists = ::stat(target.c_str(), &st) == 0;
  require(!exists || S_ISREG(st.st_mode), MCON_ERROR_IO, "'" + target + "' exists and is not a regular file");

  const std::size_t slash = target.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : target.substr(0, slash));
  const std::string base = slash == std::string::npos ? target : target.substr(slash + 1);
  require(!base.empty(), MCON_ERROR_IO, "'" + path + "' names a directory, not a file");

  TempFile temp(dir, base);
  temp.write(data, size, exists ? &st : nullptr);
  temp.rename_to(target);

  // The rename itself is durable only once the directory is synced.
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) io_fail("saved '" + target + "' but cannot open its directory to sync it", errno);
  const int rc = ::fsync(dfd);
  const int err = errno;
  ::close(dfd);
  if (rc != 0) io_fail("saved '" + target + "' but cannot fsync its directory", err);
}

}  // namespace mcon
