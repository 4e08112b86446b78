// Tables of named numbers for authoring inputs: a PLY's extra vertex properties (one row per file
// vertex, as DCC exporters write attributes) or a small CSV. Both come from users' files, so every
// row length, value and name is checked and named by file and line.
#include <charconv>
#include <cmath>
#include <set>
#include <string_view>

#include "base/error.h"
#include "io/file_suffix.h"
#include "io/mesh_io.h"
#include "io/polygon_soup.h"
#include "io/text_cursor.h"

namespace mcon::io {
namespace {

constexpr std::size_t kMaxColumns = 4096;

bool is_separator(char c) { return c == ',' || c == ' ' || c == '\t' || c == '\r' || c == ';'; }

// The tokens of one line before its `#` comment; empty tokens between two commas are kept (as
// empty strings) so a missing value is an error instead of a shifted row.
std::vector<std::string_view> tokens_of(std::string_view line) {
  const std::size_t hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  std::vector<std::string_view> out;
  std::size_t at = 0;
  bool after_comma = true;  // a leading comma leaves an empty first value
  while (at < line.size()) {
    if (is_separator(line[at])) {
      if (line[at] == ',') {
        if (after_comma) out.emplace_back();
        after_comma = true;
      }
      ++at;
      continue;
    }
    std::size_t end = at;
    while (end < line.size() && !is_separator(line[end])) ++end;
    out.push_back(line.substr(at, end - at));
    after_comma = false;
    at = end;
  }
  if (after_comma && !out.empty()) out.emplace_back();
  return out;
}

bool parse_number(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

std::string printable(std::string_view token) { return "'" + TextCursor::printable(token) + "'"; }

void check_columns(const std::vector<std::string>& columns, const std::string& where) {
  require(!columns.empty(), MCON_ERROR_IO, where + ": no columns");
  require(columns.size() <= kMaxColumns, MCON_ERROR_IO, where + ": more than " + std::to_string(kMaxColumns) + " columns");
  std::set<std::string> seen;
  for (const std::string& c : columns) {
    require(!c.empty(), MCON_ERROR_IO, where + ": an empty column name");
    require(seen.insert(c).second, MCON_ERROR_IO, where + ": column '" + c + "' appears twice");
  }
}

ValueTable read_csv(std::string_view text, const std::string& path) {
  ValueTable table;
  int line_number = 0;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    const std::vector<std::string_view> tokens = tokens_of(text.substr(at, end - at));
    at = end + 1;
    ++line_number;
    if (tokens.empty()) continue;
    const std::string where = path + ":" + std::to_string(line_number);
    if (table.columns.empty()) {
      double ignored = 0;
      require(!parse_number(tokens.front(), ignored), MCON_ERROR_IO,
              where + ": the first line must name the columns (e.g. 'x,y,z,index'), found the number " +
                  printable(tokens.front()));
      for (std::string_view t : tokens) table.columns.emplace_back(t);
      check_columns(table.columns, where);
      continue;
    }
    require(tokens.size() == table.columns.size(), MCON_ERROR_IO,
            where + ": " + std::to_string(tokens.size()) + " values, but the header names " +
                std::to_string(table.columns.size()) + " columns");
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      double value = 0;
      require(parse_number(tokens[k], value) && std::isfinite(value), MCON_ERROR_IO,
              where + ": column '" + table.columns[k] + "': " +
                  (tokens[k].empty() ? std::string("missing value") : printable(tokens[k]) + " is not a finite number"));
      table.values.push_back(value);
    }
  }
  require(!table.columns.empty(), MCON_ERROR_IO, "'" + path + "' is empty: it needs a header line of column names");
  return table;
}

// x, y, z first (a point cloud of singularities is a PLY too), then the other scalar properties.
ValueTable read_ply_properties(std::string_view data, const std::string& path) {
  PolygonSoup soup = parse_ply(data, path, true);
  ValueTable table;
  table.columns = {"x", "y", "z"};
  for (std::string& name : soup.vertex_property_names) table.columns.push_back(std::move(name));
  check_columns(table.columns, "'" + path + "'");
  const std::size_t extra = table.columns.size() - 3;
  table.values.reserve(soup.positions.size() * table.columns.size());
  for (std::size_t v = 0; v < soup.positions.size(); ++v) {
    for (int k = 0; k < 3; ++k) table.values.push_back(soup.positions[v][k]);
    for (std::size_t k = 0; k < extra; ++k) table.values.push_back(soup.vertex_property_values[v * extra + k]);
  }
  for (std::size_t i = 0; i < table.values.size(); ++i)
    require(std::isfinite(table.values[i]), MCON_ERROR_IO,
            "'" + path + "': vertex " + std::to_string(i / table.columns.size()) + ", property '" +
                table.columns[i % table.columns.size()] + "' is not finite");
  return table;
}

}  // namespace

int ValueTable::column(const std::string& name) const {
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == name) return static_cast<int>(k);
  return -1;
}

ValueTable read_value_table(const std::string& path, std::size_t max_bytes) {
  std::string_view name = path;
  if (is_gzip_path(name)) name.remove_suffix(3);
  const bool ply = ends_with_ignoring_case(name, ".ply");
  require(ply || ends_with_ignoring_case(name, ".csv") || ends_with_ignoring_case(name, ".txt"), MCON_ERROR_IO,
          "'" + path + "': unknown table format (expected .ply, .csv or .txt, optionally .gz)");
  const std::string data = read_file_maybe_gz(path, max_bytes);
  return ply ? read_ply_properties(data, path) : read_csv(data, path);
}

}  // namespace mcon::io
