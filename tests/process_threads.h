// The number of threads of the calling process (Linux: the entries of /proc/self/task), for the
// tests that check mcon_shutdown joins every worker thread (docs/design.md §5). Header-only, without
// GoogleTest, so the stand-alone exit test programs use it too.
#pragma once

#include <dirent.h>

namespace mcon::test {

inline int process_thread_count() {
  int n = 0;
  if (DIR* d = opendir("/proc/self/task")) {
    while (dirent* e = readdir(d))
      if (e->d_name[0] != '.') ++n;
    closedir(d);
  }
  return n;
}

}  // namespace mcon::test
