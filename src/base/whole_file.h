// A whole regular file read into memory with one size check before anything is allocated.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "macrocon/macrocon.h"

namespace mcon {

// Opens and fstat()s the file, checks its size is within [min_size, max_size] and only then
// allocates and reads it. The bytes are the caller's own copy: whatever another process does to
// the file afterwards (truncating or rewriting it in place) cannot change what was read, unlike a
// memory map, where a file shrinking under its reader raises SIGBUS. Throws mcon::Error:
// MCON_ERROR_IO (cannot open or read / not a regular file / the file shrank while it was read),
// `size_status` (size out of range; the message names the size and the limits), and
// std::bad_alloc if the size passes but memory runs out.
std::vector<std::uint8_t> read_whole_file(const std::string& path, std::size_t min_size, std::size_t max_size,
                                          mcon_status size_status);

}  // namespace mcon
