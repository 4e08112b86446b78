// Constraint library files (.mcl, schema/macrocon_library.fbs). Files come from third parties:
// loading checks the size, runs the FlatBuffers Verifier with explicit limits, checks the file
// identifier and format version, and then validates the meaning of every field (docs/design.md §6).
// Any failure is an mcon::Error, never a crash:
//   MCON_ERROR_INVALID_LIBRARY  corrupt, truncated, forged or inconsistent contents (the message
//                               says what and where: "entry 3 'nose_07': triangle 12 uses ...")
//   MCON_ERROR_UNSUPPORTED      a format_version newer than this build reads
//   MCON_ERROR_IO               the file cannot be opened, read, written or renamed
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "library/constraint_library.h"

namespace mcon {

inline constexpr char kLibraryFileIdentifier[] = "MCLB";
inline constexpr std::uint32_t kLibraryFormatVersion = 1;
// Root offset + identifier + the smallest vtable and table: anything shorter is not a library.
inline constexpr std::size_t kLibraryMinBytes = 16;
// FlatBuffers offsets are 32-bit signed: a buffer is < 2 GiB (and the Verifier asserts it is
// smaller than FLATBUFFERS_MAX_BUFFER_SIZE = 2^31 - 1).
inline constexpr std::size_t kLibraryMaxBytes = (std::size_t{1} << 31) - 2;

// The library as a finished FlatBuffer (deterministic: same library, same bytes). A library too
// large for one buffer throws MCON_ERROR_INVALID_ARGUMENT.
std::vector<std::uint8_t> serialize_library(const ConstraintLibrary& library);

// Parses and validates; copies everything out, so `data` may be freed afterwards. A `data` not
// aligned to 8 bytes is copied first.
ConstraintLibrary load_library_from_buffer(const void* data, std::size_t size);

// Reads the whole file into memory (after checking its size) and loads that copy, so another
// process rewriting the file meanwhile can only make the load fail (MCON_ERROR_IO if it shrank
// while being read, else INVALID_LIBRARY), never crash it.
ConstraintLibrary load_library_from_file(const std::string& path);

// serialize_library, then write_file_atomic (base/atomic_file.h): on failure the previous file is
// untouched and no temporary file is left; MCON_ERROR_IO.
void save_library_atomic(const ConstraintLibrary& library, const std::string& path);

}  // namespace mcon
