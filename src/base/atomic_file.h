// Crash-safe file replacement: a reader sees either the whole old file or the whole new one.
#pragma once

#include <cstddef>
#include <string>

namespace mcon {

// Writes `data` to a new temporary file in the directory of `path`, fflush + fsync, renames it over
// `path` and fsyncs the directory. A symlink at `path` is followed (the link stays, its target is
// replaced); an existing file's permission bits are kept, a new file gets 0666 & ~umask. On any
// failure before the rename the temporary file is removed and `path` is untouched; throws
// mcon::Error(MCON_ERROR_IO) naming the step and the system error.
void write_file_atomic(const std::string& path, const void* data, std::size_t size);

}  // namespace mcon
