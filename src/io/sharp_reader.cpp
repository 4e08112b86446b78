// Reads QuadWild `.sharp` files ("<count>" then "<kind>,<face>,<edge>" lines), for tests and tools.
#include <string>

#include "base/error.h"
#include "io/mesh_io.h"
#include "io/text_cursor.h"

namespace mcon::io {

std::vector<SharpEdge> read_sharp(const std::string& path) {
  const std::string text = read_file_maybe_gz(path);
  TextCursor cur(text, path);
  long long count = 0;
  cur.skip_space(false);
  if (!cur.read_integer(count) || count < 0) cur.error("expected the edge count, found " + cur.quote_here());
  if (static_cast<unsigned long long>(count) > text.size() / 6 + 1)
    cur.error("edge count " + std::to_string(count) + " does not fit the file size");
  std::vector<SharpEdge> edges(static_cast<std::size_t>(count));
  for (SharpEdge& e : edges) {
    long long values[3];
    cur.skip_space(false);
    for (int i = 0; i < 3; ++i) {
      if (i > 0) {
        if (cur.peek() != ',') cur.error("expected ',', found " + cur.quote_here());
        cur.advance();
      }
      if (!cur.read_integer(values[i], ',')) cur.error("expected an integer, found " + cur.quote_here());
    }
    if (values[0] != 0 && values[0] != 1) cur.error("edge kind must be 0 (concave) or 1 (convex)");
    if (values[1] < 0 || values[1] > 0x7fffffff) cur.error("face index out of range");
    if (values[2] < 0 || values[2] > 2) cur.error("edge index must be 0, 1 or 2");
    e.convex = values[0] == 1;
    e.face = static_cast<int>(values[1]);
    e.edge = static_cast<int>(values[2]);
    if (!cur.at_line_end()) cur.error("unexpected " + cur.quote_here());
  }
  cur.skip_space(false);
  if (!cur.at_end()) cur.error("unexpected " + cur.quote_here() + " after " + std::to_string(count) + " edges");
  return edges;
}

}  // namespace mcon::io
