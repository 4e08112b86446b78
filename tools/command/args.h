// `--key value`, `--key=value` and `--flag` arguments of the CLI subcommands, parsed by CLI11
// (Debian libcli11-dev); `--help` prints the command's usage text followed by the option list CLI11
// generates from what the command accepts, so the list cannot drift from the parser.
#pragma once

#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "base/error.h"
#include "command/command.h"

// The sentence every help text that takes a vertex, face or triangle number carries (issue 17:
// OBJ's own indices count from 1, ours from 0, and users mix them up).
#define MACROCON_HELP_NUMBERING                                                                    \
  "Vertex, face and triangle numbers count from 0: vertex 0 is the file's first vertex (its first\n" \
  "OBJ 'v' line, although OBJ 'f' lines count vertices from 1), face 0 its first face.\n"

namespace mcon::cli {

// "a,b,,c" -> {"a", "b", "c"}: a comma-separated list of names (empty items dropped).
std::vector<std::string> split_names(const std::string& s);

// "BEGIN:END" of --face-range / --source-face-range (file faces [BEGIN, END), integers, 0 <= BEGIN <
// END), named by `key` in errors.
void parse_range(const std::string& key, const std::string& s, long& begin, long& end);

// "X,Y,Z" of --up and the like: three finite numbers, named by `key` in errors.
std::array<double, 3> parse_vec3(const std::string& key, const std::string& s);

// Thrown after a command's help was printed; run_commands ends the program with status 0.
struct HelpShown {};

// One option occurrence, in command-line order.
struct ArgOccurrence {
  std::string key;    // without the leading "--"
  std::string value;  // empty for a flag
  bool flag = false;
};

// One line of --help per option (key without "--" -> text). Options every command means the same
// way (--json, --quiet, --progress, --face-range, ...) have a shared line a command may override.
using OptionHelp = std::map<std::string, std::string>;
const OptionHelp& shared_option_help();

// Every occurrence in order, for commands whose options apply to what precedes them (library
// build: --mesh, --center-vertex, then that entry's options). `flags` take no value; every other key
// takes one. --help / -h print `usage` and the generated option list (with `help`'s lines), then
// throw HelpShown.
std::vector<ArgOccurrence> parse_in_order(const Args& args, const std::set<std::string>& keys,
                                          const std::set<std::string>& flags, const char* usage,
                                          const OptionHelp& help = {});

class ArgParser {
 public:
  // Each key at most once.
  ArgParser(const Args& args, const std::set<std::string>& keys, const std::set<std::string>& flags,
            const char* usage = nullptr, const OptionHelp& help = {});

  bool has(const std::string& key) const { return values_.count(key) > 0; }
  bool flag(const std::string& key) const { return flags_.count(key) > 0; }
  std::string get(const std::string& key, const std::string& fallback = "") const;
  std::string required(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  long integer(const std::string& key, long fallback) const;
  // The whole text must be the number; out-of-range values are errors, not clamped (strtol
  // saturates at LONG_MAX with ERANGE, which once let --top 2**64+1 through).
  static long parse_integer(const std::string& key, const std::string& s);
  static double parse_number(const std::string& key, const std::string& s);

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
};

}  // namespace mcon::cli
