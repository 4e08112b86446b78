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
// 2: Library.content_checksum (FNV-1a 64, docs/design.md §6). Format 1 files still load.
inline constexpr std::uint32_t kLibraryFormatVersion = 2;
// Root offset + identifier + the smallest vtable and table: anything shorter is not a library.
inline constexpr std::size_t kLibraryMinBytes = 16;
// FlatBuffers offsets are 32-bit signed: a buffer is < 2 GiB (and the Verifier asserts it is
// smaller than FLATBUFFERS_MAX_BUFFER_SIZE = 2^31 - 1).
inline constexpr std::size_t kLibraryMaxBytes = (std::size_t{1} << 31) - 2;

// The library as a finished FlatBuffer (deterministic: same library, same bytes). A library too
// large for one buffer throws MCON_ERROR_INVALID_ARGUMENT.
std::vector<std::uint8_t> serialize_library(const ConstraintLibrary& library);

// FNV-1a 64 over `size` bytes, the 8 at `checksum_offset` read as zero. Every change of one
// byte changes it (each step is a bijection of the state), so every single bit flip is caught.
std::uint64_t library_content_checksum(const std::uint8_t* bytes, std::size_t size, std::size_t checksum_offset);

// Writes the checksum of a finished library buffer into its content_checksum field (which must
// be present: serialize_library writes it). Tests and fuzzers that forge buffers use it to get
// past the checksum to the checks behind it. Throws INVALID_ARGUMENT if the field is missing.
void seal_library_buffer(std::vector<std::uint8_t>& bytes);

// Byte position of the content_checksum field in a buffer that passed the Verifier, 0 if absent.
std::size_t library_checksum_offset(const std::uint8_t* verified_bytes);

// Parses and validates; copies everything out, so `data` may be freed afterwards. A `data` not
// aligned to 8 bytes is copied first.
// `check_checksum` false is for fuzzers only, which must reach the checks behind the checksum.
ConstraintLibrary load_library_from_buffer(const void* data, std::size_t size, bool check_checksum = true);

// Reads the whole file into memory (after checking its size) and loads that copy, so another
// process rewriting the file meanwhile can only make the load fail (MCON_ERROR_IO if it shrank
// while being read, else INVALID_LIBRARY), never crash it.
ConstraintLibrary load_library_from_file(const std::string& path);

// serialize_library, then write_file_atomic (base/atomic_file.h): on failure the previous file is
// untouched and no temporary file is left; MCON_ERROR_IO.
void save_library_atomic(const ConstraintLibrary& library, const std::string& path);

}  // namespace mcon
