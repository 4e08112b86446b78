// Reads QuadWild `.rosy` files (as vcglib's ImporterFIELD::Load4ROSY does: face count, symmetry,
// then three numbers per face), for tests and tools.
#include <cmath>
#include <string>

#include "base/error.h"
#include "io/mesh_io.h"
#include "io/text_cursor.h"

namespace mcon::io {

std::vector<Vec3> read_rosy(const std::string& path) {
  const std::string text = read_file_maybe_gz(path);
  TextCursor cur(text, path);
  long long count = 0, symmetry = 0;
  cur.skip_space(false);
  if (!cur.read_integer(count) || count < 0) cur.error("expected the face count, found " + cur.quote_here());
  cur.skip_space(false);
  if (!cur.read_integer(symmetry)) cur.error("expected the symmetry, found " + cur.quote_here());
  require(symmetry == 4, MCON_ERROR_UNSUPPORTED,
          path + ": only 4-symmetric fields are supported, the file has symmetry " + std::to_string(symmetry));
  // Each face takes at least 6 bytes ("0 0 0\n"): reject absurd counts before allocating.
  if (static_cast<unsigned long long>(count) > text.size() / 6 + 1)
    cur.error("face count " + std::to_string(count) + " does not fit the file size");
  std::vector<Vec3> directions(static_cast<std::size_t>(count));
  for (Vec3& d : directions)
    for (int i = 0; i < 3; ++i) {
      cur.skip_space(false);
      const std::string here = cur.quote_here();
      if (!cur.read_double(d[i])) cur.error("expected a direction component, found " + here);
      if (!std::isfinite(d[i])) cur.error("direction component " + here + " is not finite");
    }
  cur.skip_space(false);
  if (!cur.at_end()) cur.error("unexpected " + cur.quote_here() + " after " + std::to_string(count) + " directions");
  return directions;
}

}  // namespace mcon::io
