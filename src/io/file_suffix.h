// File-name suffix tests for format detection: extensions are matched case-insensitively, so
// `MESH.OBJ.GZ` reads like `mesh.obj.gz`.
#pragma once

#include <cctype>
#include <cstddef>
#include <string_view>

namespace mcon::io {

inline bool ends_with_ignoring_case(std::string_view text, std::string_view suffix) {
  if (text.size() < suffix.size()) return false;
  const std::size_t offset = text.size() - suffix.size();
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[offset + i])) !=
        std::tolower(static_cast<unsigned char>(suffix[i])))
      return false;
  return true;
}

inline bool is_gzip_path(std::string_view path) { return ends_with_ignoring_case(path, ".gz"); }

}  // namespace mcon::io
