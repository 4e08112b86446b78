// The content checksum of format-2 library buffers (library_file.h, docs/design.md §6).
#include <cstring>

#include "base/error.h"
#include "library/library_file.h"
#include "macrocon_library_generated.h"

namespace mcon {

std::uint64_t library_content_checksum(const std::uint8_t* bytes, std::size_t size, std::size_t checksum_offset) {
  // FNV-1a 64 (offset basis and prime of the published definition).
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    const bool in_field = i >= checksum_offset && i < checksum_offset + sizeof(std::uint64_t);
    h ^= in_field ? 0u : bytes[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::size_t library_checksum_offset(const std::uint8_t* verified_bytes) {
  const auto* root = flatbuffers::GetRoot<flatbuffers::Table>(verified_bytes);
  const flatbuffers::voffset_t field = root->GetOptionalFieldOffset(fb::Library::VT_CONTENT_CHECKSUM);
  if (field == 0) return 0;
  return static_cast<std::size_t>(reinterpret_cast<const std::uint8_t*>(root) - verified_bytes) + field;
}

void seal_library_buffer(std::vector<std::uint8_t>& bytes) {
  require(bytes.size() >= kLibraryMinBytes, MCON_ERROR_INVALID_ARGUMENT, "seal_library_buffer: not a library buffer");
  const std::size_t at = library_checksum_offset(bytes.data());
  require(at != 0 && at + sizeof(std::uint64_t) <= bytes.size(), MCON_ERROR_INVALID_ARGUMENT,
          "seal_library_buffer: the buffer has no content_checksum field");
  const std::uint64_t h = library_content_checksum(bytes.data(), bytes.size(), at);
  flatbuffers::WriteScalar(bytes.data() + at, h);
}

}  // namespace mcon
