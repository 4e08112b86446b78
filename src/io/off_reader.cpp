// Object File Format (Geomview OFF): optional [ST][C][N]OFF header keyword, `#` comments, the
// counts line, one vertex per line (anything after x y z, e.g. COFF colours or NOFF normals, is
// skipped) and one polygon per line ("n i0 ... in-1", trailing face colours skipped).
#include <algorithm>
#include <cctype>
#include <climits>

#include "io/polygon_soup.h"
#include "io/text_cursor.h"

namespace mcon::io {
namespace {

// Accepts the header keyword variants whose vertex lines still start with x y z.
void read_header_keyword(TextCursor& in) {
  const char c = in.peek();
  if (std::isdigit(static_cast<unsigned char>(c))) return;  // the keyword is optional
  const std::string keyword(in.word());
  std::string_view rest = keyword;
  if (rest.substr(0, 2) == "ST") rest.remove_prefix(2);
  if (rest.substr(0, 1) == "C") rest.remove_prefix(1);
  if (rest.substr(0, 1) == "N") rest.remove_prefix(1);
  if (!rest.empty() && (rest[0] == '4' || rest[0] == 'n') && rest.substr(1) == "OFF")
    in.error("'" + keyword + "' (4D or n-dimensional OFF) is not supported");
  if (rest != "OFF") in.error("not an OFF file (header keyword '" + TextCursor::printable(keyword) + "')");
  // The counts may follow on the same line; "OFF BINARY" announces a binary body.
  in.skip_blanks();
  const std::size_t start = in.position();
  if (in.word() == "BINARY") in.error("binary OFF is not supported");
  in.rewind_on_line(start);
}

int read_count(TextCursor& in, const char* what) {
  in.skip_space(true);
  long long count = 0;
  if (!in.read_integer(count)) in.error(std::string("expected the ") + what + " count, found " + in.quote_here());
  if (count < 0 || count > INT_MAX - 1) in.error(std::string("invalid ") + what + " count " + std::to_string(count));
  return static_cast<int>(count);
}

}  // namespace

PolygonSoup parse_off(std::string_view text, const std::string& file_name) {
  PolygonSoup soup;
  TextCursor in(text, file_name);
  in.skip_space(true);
  if (in.at_end()) in.error("empty OFF file");
  read_header_keyword(in);
  const int nv = read_count(in, "vertex");
  const int nf = read_count(in, "face");
  if (!in.at_line_end()) read_count(in, "edge");  // present in the standard, unused
  in.next_line();

  // Each vertex and face needs at least a few bytes, so bogus counts cannot force huge reserves.
  const std::size_t cap = text.size() / 4 + 1;
  soup.positions.reserve(std::min<std::size_t>(static_cast<std::size_t>(nv), cap));
  for (int v = 0; v < nv; ++v) {
    in.skip_space(true);
    double xyz[3];
    for (double& value : xyz)
      if (!in.read_double(value))
        in.error("vertex " + std::to_string(v) + ": expected a coordinate, found " + in.quote_here());
    soup.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    in.next_line();
  }
  soup.face_start.reserve(std::min<std::size_t>(static_cast<std::size_t>(nf), cap) + 1);
  for (int f = 0; f < nf; ++f) {
    in.skip_space(true);
    long long n = 0;
    if (!in.read_integer(n)) in.error("face " + std::to_string(f) + ": expected the vertex count, found " + in.quote_here());
    if (n < 3 || static_cast<unsigned long long>(n) > text.size())
      in.error("face " + std::to_string(f) + " has an invalid vertex count " + std::to_string(n));
    for (long long k = 0; k < n; ++k) {
      long long index = 0;
      if (!in.read_integer(index))
        in.error("face " + std::to_string(f) + ": expected a vertex index, found " + in.quote_here());
      if (index < 0 || index >= nv)
        in.error("face " + std::to_string(f) + " uses vertex index " + std::to_string(index) + " but the file has " +
                 std::to_string(nv) + " vertices");
      soup.corners.push_back(static_cast<int>(index));
    }
    if (soup.corners.size() > static_cast<std::size_t>(INT_MAX)) in.error("too many face corners");
    soup.face_start.push_back(static_cast<int>(soup.corners.size()));
    in.next_line();
  }
  return soup;
}

}  // namespace mcon::io
