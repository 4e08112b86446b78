// The file readers take paths: the fuzz targets write each input to a per-process temporary file
// with the suffix that selects the format (and `.gz` for the gzip path), then read it back.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace mcon_fuzz {

inline std::string write_input_file(const std::uint8_t* data, std::size_t size, const std::string& suffix) {
  const char* tmp = std::getenv("TMPDIR");
  const std::string path = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/macrocon_fuzz_" +
                           std::to_string(static_cast<long>(::getpid())) + suffix;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
    std::perror(path.c_str());
    std::abort();  // the harness, not the reader, failed
  }
  return path;
}

[[noreturn]] inline void finding(const char* what, const char* detail = "") {
  std::fprintf(stderr, "%s%s\n", what, detail);
  std::abort();
}

}  // namespace mcon_fuzz
