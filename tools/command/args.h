// Minimal `--key value` / `--flag` argument parsing for the CLI subcommands.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>
#include <algorithm>

#include "command/command.h"
#include "base/error.h"

// The sentence every help text that takes a vertex, face or triangle number carries (issue 17:
// OBJ's own indices count from 1, ours from 0, and users mix them up).
#define MACROCON_HELP_NUMBERING                                                                    \
  "Vertex, face and triangle numbers count from 0: vertex 0 is the file's first vertex (its first\n" \
  "OBJ 'v' line, although OBJ 'f' lines count vertices from 1), face 0 its first face.\n"

namespace mcon::cli {

// "a,b,,c" -> {"a", "b", "c"}: a comma-separated list of names (empty items dropped).
inline std::vector<std::string> split_names(const std::string& s) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= s.size()) {
    const std::size_t end = std::min(s.find(',', begin), s.size());
    if (end > begin) out.push_back(s.substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

class ArgParser {
 public:
  // `flags` take no value; every other `--key` takes one.
  ArgParser(const Args& args, const std::set<std::string>& keys, const std::set<std::string>& flags) {
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      require(a.rfind("--", 0) == 0, MCON_ERROR_INVALID_ARGUMENT, "unexpected argument '" + a + "'");
      const std::string key = a.substr(2);
      if (flags.count(key)) {
        flags_.insert(key);
      } else {
        require(keys.count(key) > 0, MCON_ERROR_INVALID_ARGUMENT, "unknown option '" + a + "'");
        require(i + 1 < args.size(), MCON_ERROR_INVALID_ARGUMENT, "option '" + a + "' needs a value");
        values_[key] = args[++i];
      }
    }
  }
  bool has(const std::string& key) const { return values_.count(key) > 0; }
  bool flag(const std::string& key) const { return flags_.count(key) > 0; }
  std::string get(const std::string& key, const std::string& fallback = "") const {
    auto it = values_.find(key);
    return it == values_.end() ? fallback : it->second;
  }
  std::string required(const std::string& key) const {
    require(has(key), MCON_ERROR_INVALID_ARGUMENT, "missing required option --" + key);
    return get(key);
  }
  double number(const std::string& key, double fallback) const {
    if (!has(key)) return fallback;
    return parse_number(key, get(key));
  }
  long integer(const std::string& key, long fallback) const {
    if (!has(key)) return fallback;
    return parse_integer(key, get(key));
  }
  // The whole text must be the number; out-of-range values are errors, not clamped (strtol
  // saturates at LONG_MAX with ERANGE, which once let --top 2**64+1 through).
  static long parse_integer(const std::string& key, const std::string& s) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    require(end && *end == '\0' && !s.empty(), MCON_ERROR_INVALID_ARGUMENT,
            "--" + key + " expects an integer, got '" + s + "'");
    require(errno != ERANGE, MCON_ERROR_INVALID_ARGUMENT, "--" + key + " is out of range: '" + s + "'");
    return v;
  }
  static double parse_number(const std::string& key, const std::string& s) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &end);
    require(end && *end == '\0' && !s.empty(), MCON_ERROR_INVALID_ARGUMENT,
            "--" + key + " expects a number, got '" + s + "'");
    require(std::isfinite(v) && !(errno == ERANGE && v != 0), MCON_ERROR_INVALID_ARGUMENT,
            "--" + key + " is out of range: '" + s + "'");
    return v;
  }

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
};

}  // namespace mcon::cli
