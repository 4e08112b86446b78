#include "base/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "base/error.h"

namespace mcon {
namespace {

[[noreturn]] void io_fail(const std::string& what, int err) {
  fail(MCON_ERROR_IO, what + ": " + std::strerror(err));
}

struct Split {
  std::string dir, base;
};

Split split_path(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return {".", path};
  return {slash == 0 ? "/" : path.substr(0, slash), path.substr(slash + 1)};
}

std::string temporary_prefix(const std::string& base) { return "." + base + ".tmp."; }

// 8 hex digits of FNV-1a over the host name: short, and the same for every writer on this host.
std::string host_tag() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) name[0] = '\0';
  std::uint32_t h = 2166136261u;
  for (const char* p = name; *p != '\0'; ++p) h = (h ^ static_cast<unsigned char>(*p)) * 16777619u;
  char out[9];
  std::snprintf(out, sizeof out, "%08x", static_cast<unsigned>(h));
  return out;
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// Best effort, failures ignored: a save must not fail over someone else's leftovers. Removes
// "<prefix><pid>.<counter>" regular files whose pid no longer exists (kill(pid, 0) says ESRCH; a
// live pid, even an unrelated process that reused it, keeps its file).
void remove_stale_temporaries(const std::string& dir, const std::string& base) {
  const std::unique_ptr<DIR, int (*)(DIR*)> d(::opendir(dir.c_str()), ::closedir);
  if (!d) return;
  const std::string prefix = temporary_prefix(base) + host_tag() + ".";
  std::vector<std::string> stale;
  while (const dirent* e = ::readdir(d.get())) {
    const std::string name = e->d_name;
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const std::size_t dot = rest.find('.');
    if (dot == std::string::npos || dot > 9 || !all_digits(rest.substr(0, dot)) || !all_digits(rest.substr(dot + 1)))
      continue;
    const long pid = std::stol(rest.substr(0, dot));
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    stale.push_back(dir + "/" + name);
  }
  for (const std::string& p : stale) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode)) ::unlink(p.c_str());
  }
}

// The directory, opened for reading (fsync needs that) before anything is replaced.
class Directory {
 public:
  Directory(const std::string& dir, const std::string& target) : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0)
      io_fail("cannot open the directory '" + dir + "' of '" + target +
                  "' for reading, which syncing the save needs (give it read permission); nothing was replaced",
              errno);
  }
  ~Directory() { ::close(fd_); }
  Directory(const Directory&) = delete;
  Directory& operator=(const Directory&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

// The temporary file until it has been renamed: closed and removed on every failure path.
class TempFile {
 public:
  TempFile(const std::string& dir, const std::string& stem) {
    static std::atomic<unsigned> counter{0};
    // O_EXCL on a name of our own: never reuses or follows an existing file; mode 0666 & ~umask.
    for (int attempt = 0; attempt < 100; ++attempt) {
      path_ = stem + std::to_string(counter++);
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

std::string temporary_file_stem(const std::string& path, long pid) {
  const Split p = split_path(path);
  return p.dir + "/" + temporary_prefix(p.base) + host_tag() + "." + std::to_string(pid) + ".";
}

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

  const Split where = split_path(target);
  require(!where.base.empty(), MCON_ERROR_IO, "'" + path + "' names a directory, not a file");

  remove_stale_temporaries(where.dir, where.base);
  TempFile temp(where.dir, temporary_file_stem(target, static_cast<long>(::getpid())));
  temp.write(data, size, exists ? &st : nullptr);
  const Directory directory(where.dir, target);
  temp.rename_to(target);

  // The rename itself is durable only once the directory is synced.
  if (::fsync(directory.fd()) != 0) io_fail("saved '" + target + "' but cannot fsync its directory", errno);
}

}  // namespace mcon
