#include "command/args.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <CLI/CLI.hpp>

namespace mcon::cli {
namespace {

// CLI11's messages name its own terms ("The following arguments were not expected"); ours name
// the option and the fix, as the tests and users expect.
[[noreturn]] void rethrow(const CLI::ParseError& e, const Args& args, const std::set<std::string>& keys,
                          const std::set<std::string>& flags) {
  if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
    for (const std::string& a : args) {
      // Values may be negative numbers ("--seed -5"): only words that look like options count.
      if (a.size() < 2 || a[0] != '-' || (a[1] >= '0' && a[1] <= '9') || a[1] == '.') continue;
      const std::string key = a.rfind("--", 0) == 0 ? a.substr(2, a.find('=') - 2) : std::string();
      if (key != "help" && !keys.count(key) && !flags.count(key))
        fail(MCON_ERROR_INVALID_ARGUMENT, "unknown option '" + a + "' (--help lists the options)");
    }
    fail(MCON_ERROR_INVALID_ARGUMENT, std::string(e.what()) + " (every value follows its --option)");
  }
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) != nullptr) {
    const std::string what = e.what();
    const std::string option = what.substr(0, what.find(':'));
    if (what.find("missing") != std::string::npos)
      fail(MCON_ERROR_INVALID_ARGUMENT, "option '" + option + "' needs a value");
  }
  fail(MCON_ERROR_INVALID_ARGUMENT, e.what());
}

// The value's name in the command's synopsis ("--radius R" -> "R"), for the generated list.
std::string value_name(const char* usage, const std::string& key) {
  const std::string text = usage != nullptr ? usage : "";
  const std::string option = "--" + key + " ";
  for (std::size_t at = text.find(option); at != std::string::npos; at = text.find(option, at + 1)) {
    std::size_t b = at + option.size(), e = b;
    int depth = 0;  // "NAME[=COL,COL...]" keeps its brackets; the synopsis' own "]" ends the word
    for (; e < text.size() && text[e] != ' ' && text[e] != '\n' && text[e] != ')'; ++e) {
      if (text[e] == '[') ++depth;
      if (text[e] == ']' && depth-- == 0) break;
    }
    std::string word = text.substr(b, e - b);
    while (!word.empty() && (word.back() == ':' || word.back() == ',')) word.pop_back();  // prose punctuation
    if (!word.empty() && word[0] >= 'A' && word[0] <= 'Z') return word;
  }
  return "VALUE";
}

// The option's line of --help: the command's own, else the shared one, else none.
std::string help_line(const OptionHelp& help, const std::string& key) {
  for (const OptionHelp* table : {&help, &shared_option_help()}) {
    const auto it = table->find(key);
    if (it != table->end()) return it->second;
  }
  return "";
}

// The command's own usage text (its synopsis and prose) replaces CLI11's one-line "Usage:"; the
// option list below it is generated.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_usage(const CLI::App*, std::string) const override { return ""; }
};

// Declares every key (one value each occurrence, any number of occurrences) and flag, parses,
// and handles --help. What a command allows more than once is the caller's decision.
void parse(CLI::App& app, const Args& args, const std::set<std::string>& keys, const std::set<std::string>& flags,
           const char* usage, const OptionHelp& help) {
  app.description(usage != nullptr ? usage : "");
  app.set_help_flag("-h,--help", "print this help and exit");
  app.formatter(std::make_shared<HelpFormatter>());
  app.get_formatter()->column_width(30);
  for (const std::string& key : keys)
    app.add_option("--" + key)
        ->description(help_line(help, key))
        ->type_name(value_name(usage, key))
        ->expected(1)
        ->take_all()
        ->allow_extra_args(false);
  for (const std::string& key : flags)
    app.add_flag("--" + key)->description(help_line(help, key))->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  // CLI11 gives an option its value even when the next word is another option; a forgotten value
  // would then swallow the option after it. A value starting with "--" needs --key=--value.
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i].rfind("--", 0) == 0 && keys.count(args[i].substr(2)) && args[i + 1].rfind("--", 0) == 0)
      fail(MCON_ERROR_INVALID_ARGUMENT, "option '" + args[i] + "' needs a value (the next word is '" + args[i + 1] +
                                            "'; write " + args[i] + "=VALUE for a value starting with --)");
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    throw HelpShown{};
  } catch (const CLI::ParseError& e) {
    rethrow(e, args, keys, flags);
  }
}

}  // namespace

std::vector<std::string> split_names(const std::string& s) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= s.size()) {
    const std::size_t end = std::min(s.find(',', begin), s.size());
    if (end > begin) out.push_back(s.substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

void parse_range(const std::string& key, const std::string& s, long& begin, long& end) {
  const auto colon = s.find(':');
  require(colon != std::string::npos, MCON_ERROR_INVALID_ARGUMENT, "--" + key + " expects BEGIN:END, got '" + s + "'");
  begin = ArgParser::parse_integer(key, s.substr(0, colon));
  end = ArgParser::parse_integer(key, s.substr(colon + 1));
  require(begin >= 0 && end > begin, MCON_ERROR_INVALID_ARGUMENT, "--" + key + " needs 0 <= BEGIN < END");
}

const OptionHelp& shared_option_help() {
  static const OptionHelp help{
      {"json", "print the result as one JSON object on stdout"},
      {"quiet", "draw no progress bar"},
      {"progress", "draw the progress bar even when stderr is not a terminal"},
      {"face-range", "keep only the file's faces [A, B) of the mesh"},
      {"seed", "seed of every random choice (same seed, same result)"},
      {"threads", "worker threads (TBB arena)"},
      {"shared", "the shared data folder (meshes/, bench/)"},
  };
  return help;
}

std::array<double, 3> parse_vec3(const std::string& key, const std::string& s) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (std::size_t comma; (comma = s.find(',', begin)) != std::string::npos; begin = comma + 1)
    parts.push_back(s.substr(begin, comma - begin));
  parts.push_back(s.substr(begin));
  require(parts.size() == 3, MCON_ERROR_INVALID_ARGUMENT,
          "--" + key + " expects X,Y,Z (three numbers), got '" + s + "'");
  std::array<double, 3> v{};
  for (std::size_t k = 0; k < 3; ++k) v[k] = ArgParser::parse_number(key, parts[k]);
  return v;
}

std::vector<ArgOccurrence> parse_in_order(const Args& args, const std::set<std::string>& keys,
                                          const std::set<std::string>& flags, const char* usage,
                                          const OptionHelp& help) {
  CLI::App app;
  parse(app, args, keys, flags, usage, help);
  std::map<const CLI::Option*, std::size_t> seen;
  std::vector<ArgOccurrence> out;
  for (const CLI::Option* o : app.parse_order()) {
    const std::string key = o->get_name().substr(2);
    const bool is_flag = flags.count(key) > 0;
    const std::size_t k = seen[o]++;
    out.push_back({key, is_flag ? std::string() : o->results().at(k), is_flag});
  }
  return out;
}

ArgParser::ArgParser(const Args& args, const std::set<std::string>& keys, const std::set<std::string>& flags,
                     const char* usage, const OptionHelp& help) {
  for (const ArgOccurrence& a : parse_in_order(args, keys, flags, usage, help)) {
    if (a.flag) {
      flags_.insert(a.key);
      continue;
    }
    require(values_.count(a.key) == 0, MCON_ERROR_INVALID_ARGUMENT, "option '--" + a.key + "' given twice");
    values_[a.key] = a.value;
  }
}

std::string ArgParser::get(const std::string& key, const std::string& fallback) const {
  auto it = values_.find(key);
  return it == values_.end() ? fallback : it->second;
}

std::string ArgParser::required(const std::string& key) const {
  require(has(key), MCON_ERROR_INVALID_ARGUMENT, "missing required option --" + key);
  return get(key);
}

double ArgParser::number(const std::string& key, double fallback) const {
  return has(key) ? parse_number(key, get(key)) : fallback;
}

long ArgParser::integer(const std::string& key, long fallback) const {
  return has(key) ? parse_integer(key, get(key)) : fallback;
}

long ArgParser::parse_integer(const std::string& key, const std::string& s) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  require(end && *end == '\0' && !s.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "--" + key + " expects an integer, got '" + s + "'");
  require(errno != ERANGE, MCON_ERROR_INVALID_ARGUMENT, "--" + key + " is out of range: '" + s + "'");
  return v;
}

double ArgParser::parse_number(const std::string& key, const std::string& s) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  require(end && *end == '\0' && !s.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "--" + key + " expects a number, got '" + s + "'");
  require(std::isfinite(v) && !(errno == ERANGE && v != 0), MCON_ERROR_INVALID_ARGUMENT,
          "--" + key + " is out of range: '" + s + "'");
  return v;
}

}  // namespace mcon::cli
