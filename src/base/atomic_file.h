// Crash-safe file replacement: a reader sees either the whole old file or the whole new one.
#pragma once

#include <cstddef>
#include <string>

namespace mcon {

// Writes `data` to a new temporary file in the directory of `path`, fflush + fsync, opens the
// directory, renames the temporary over `path` and fsyncs the directory. A symlink at `path` is
// followed (the link stays, its target is replaced); an existing file's permission bits are kept,
// a new file gets 0666 & ~umask. Every step that can fail for a reason the caller can fix (no
// room, no permission, a directory that cannot be opened for reading) comes before the rename:
// then the temporary file is removed and `path` is untouched. Only the final directory fsync
// comes after it (the new file is in place; the message says so). Throws
// mcon::Error(MCON_ERROR_IO) naming the step and the system error.
//
// Before writing, temporaries of the same file left by writers that died mid-save (a crash, a
// kill) are removed: those named with this host's tag and the pid of a process that no longer
// exists. Anything else is left alone.
void write_file_atomic(const std::string& path, const void* data, std::size_t size);

// "<dir>/.<name>.tmp.<host>.<pid>." for `path` and the writer `pid`: write_file_atomic appends a
// counter. <host> is 8 hex digits of this host's name, so that writers on other hosts sharing the
// directory (whose pids mean nothing here) are never taken for dead. For tests and tools.
std::string temporary_file_stem(const std::string& path, long pid);

}  // namespace mcon
