// A read-only memory map of a whole regular file, unmapped on destruction.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "macrocon/macrocon.h"

namespace mcon {

class MappedFile {
 public:
  // Opens and fstat()s the file; maps it only if its size is within [min_size, max_size], so a
  // caller can reject absurd sizes before anything is mapped. Throws mcon::Error:
  // MCON_ERROR_IO (cannot open / not a regular file / mmap failed) or `size_status` (size out of
  // range, message names the size and the limits).
  MappedFile(const std::string& path, std::size_t min_size, std::size_t max_size, mcon_status size_status);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace mcon
