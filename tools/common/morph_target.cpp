#include "common/morph_target.h"

#include <charconv>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include "base/error.h"
#include "io/mesh_io.h"

namespace mcon::tools {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r'; }

}  // namespace

MorphTarget parse_morph_target(std::string_view text, const std::string& source) {
  MorphTarget target;
  std::size_t line_start = 0;
  int line_number = 0;
  while (line_start < text.size()) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string_view::npos) line_end = text.size();
    const std::string_view line = text.substr(line_start, line_end - line_start);
    line_start = line_end + 1;
    ++line_number;
    std::size_t p = 0;
    while (p < line.size() && is_space(line[p])) ++p;
    if (p == line.size() || line[p] == '#') continue;
    const auto bad_line = [&](const char* what) {
      fail(MCON_ERROR_IO, "'" + source + "' line " + std::to_string(line_number) + ": " + what);
    };
    // Fields: index dx dy dz, separated by blanks; nothing else on the line.
    const auto next_token = [&]() -> std::string_view {
      while (p < line.size() && is_space(line[p])) ++p;
      const std::size_t begin = p;
      while (p < line.size() && !is_space(line[p])) ++p;
      return line.substr(begin, p - begin);
    };
    const std::string_view index_text = next_token();
    int index = -1;
    auto r = std::from_chars(index_text.data(), index_text.data() + index_text.size(), index);
    if (r.ec != std::errc() || r.ptr != index_text.data() + index_text.size() || index < 0)
      bad_line("expected a non-negative vertex index");
    Vec3 offset;
    for (int k = 0; k < 3; ++k) {
      const std::string_view t = next_token();
      double v = 0.0;
      r = std::from_chars(t.data(), t.data() + t.size(), v);
      if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size() || !std::isfinite(v))
        bad_line("expected three finite offsets after the vertex index");
      offset[k] = v;
    }
    if (!next_token().empty()) bad_line("more than four fields");
    target.indices.push_back(index);
    target.offsets.push_back(offset);
  }
  return target;
}

const MorphTarget& load_morph_target(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<const MorphTarget>> cache;
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(path);
    if (it != cache.end()) return *it->second;
  }
  // Parse outside the lock so that several threads can load different files at once.
  auto target = std::make_unique<const MorphTarget>(parse_morph_target(io::read_file_maybe_gz(path), path));
  std::lock_guard<std::mutex> lock(mutex);
  const auto inserted = cache.emplace(path, std::move(target));  // keeps the first if raced
  return *inserted.first->second;
}

void add_morph_target(std::vector<Vec3>& positions, const MorphTarget& target, double weight) {
  const std::size_t n = positions.size();
  for (std::size_t k = 0; k < target.indices.size(); ++k) {
    const auto v = static_cast<std::size_t>(target.indices[k]);
    if (v < n) positions[v] += weight * target.offsets[k];
  }
}

}  // namespace mcon::tools
