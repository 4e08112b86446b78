#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "base/error.h"
#include "command/args.h"
#include "command/command.h"
#include "macrocon/macrocon.hpp"

namespace mcon::cli {

std::vector<Command>& commands() {
  static std::vector<Command> list;
  return list;
}

namespace {

// To stdout when asked for (--help, help), to stderr when the command line was wrong.
void print_usage(const char* program, std::FILE* out) {
  auto cmds = commands();
  std::sort(cmds.begin(), cmds.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  std::fprintf(out, "%s %d.%d.%d\nusage: %s <command> [options]   (%s help <command>, or %s <command> --help)\n\n",
               program, MCON_VERSION_MAJOR, MCON_VERSION_MINOR, MCON_VERSION_PATCH, program, program, program);
  for (const auto& c : cmds) std::fprintf(out, "  %-16s %s\n", c.name.c_str(), c.summary.c_str());
  std::fprintf(out, "  %-16s %s\n", "help", "this list, or a command's options (help <command>)");
}

}  // namespace

int run_commands(const char* program, int argc, char** argv) {
  if (argc < 2) {
    print_usage(program, stderr);
    return 2;
  }
  const std::string first = argv[1];
  if (first == "--help" || first == "-h" || (first == "help" && argc == 2)) {
    print_usage(program, stdout);
    return 0;
  }
  if (first == "--version") {
    std::printf("%d.%d.%d\n", MCON_VERSION_MAJOR, MCON_VERSION_MINOR, MCON_VERSION_PATCH);
    return 0;
  }
  // `help CMD [SUB]` is `CMD [SUB] --help`.
  const bool help = first == "help";
  const std::string name = help ? argv[2] : first;
  Args args(argv + (help ? 3 : 2), argv + argc);
  if (help) args.push_back("--help");
  const auto report = [&](mcon_status s, const char* what) {
    const char* status = status_name(s);
    std::fprintf(stderr, "%s %s: error (%s): %s\n", program, name.c_str(), status ? status : "?", what);
    return 1;
  };
  for (const auto& c : commands()) {
    if (c.name != name) continue;
    try {
      return c.run(args);
    } catch (const HelpShown&) {
      return 0;
    } catch (const Error& e) {
      return report(e.status(), e.what());
    } catch (const macrocon::Error& e) {  // the public API's calls, which the product commands use
      return report(e.status(), e.what());
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "%s %s: error (MCON_ERROR_OUT_OF_MEMORY): out of memory\n", program, name.c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s %s: error: %s\n", program, name.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "%s: unknown command '%s'\n\n", program, name.c_str());
  print_usage(program, stderr);
  return 2;
}

}  // namespace mcon::cli
