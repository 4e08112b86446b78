#include "json/json_file.h"

#include <fstream>

#include "base/error.h"
#include "io/mesh_io.h"

namespace mcon::tools {

Json read_json_file(const std::string& path) {
  const std::string text = io::read_file_maybe_gz(path);
  try {
    return parse_json(text);
  } catch (const Error& e) {
    fail(e.status(), "'" + path + "': " + e.what());
  }
}

void write_json_file(const std::string& path, const Json& value, bool pretty) {
  const std::string text = write_json(value, pretty);
  std::ofstream out(path, std::ios::binary);
  require(static_cast<bool>(out), MCON_ERROR_IO, "cannot write '" + path + "'");
  out << text;
  out.close();
  require(static_cast<bool>(out), MCON_ERROR_IO, "error writing '" + path + "'");
}

}  // namespace mcon::tools
