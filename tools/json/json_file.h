// The strict JSON value (json/json.h) plus file I/O for the evaluation commands: reading goes
// through the SDK's io layer, so a spec may be gzip-compressed.
#pragma once

#include <string>

#include "json/json.h"

namespace mcon::tools {

// Reads and parses a file (gzip-compressed if it ends in .gz); errors name the file.
Json read_json_file(const std::string& path);

void write_json_file(const std::string& path, const Json& value, bool pretty = true);

}  // namespace mcon::tools
