// `macrocon`: the command-line front end. Errors go to stderr with a non-zero exit status.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "command.h"
#include "base/error.h"

namespace mcon::cli {
std::vector<Command>& commands() {
  static std::vector<Command> list;
  return list;
}
}  // namespace mcon::cli

namespace {

void print_usage() {
  auto cmds = mcon::cli::commands();
  std::sort(cmds.begin(), cmds.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  std::fprintf(stderr, "macrocon %d.%d.%d\nusage: macrocon <command> [options]   (macrocon <command> --help)\n\n",
               MCON_VERSION_MAJOR, MCON_VERSION_MINOR, MCON_VERSION_PATCH);
  for (const auto& c : cmds) std::fprintf(stderr, "  %-16s %s\n", c.name.c_str(), c.summary.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    print_usage();
    return argc < 2 ? 2 : 0;
  }
  if (std::string(argv[1]) == "--version") {
    std::printf("%d.%d.%d\n", MCON_VERSION_MAJOR, MCON_VERSION_MINOR, MCON_VERSION_PATCH);
    return 0;
  }
  const std::string name = argv[1];
  for (const auto& c : mcon::cli::commands()) {
    if (c.name != name) continue;
    try {
      return c.run(mcon::cli::Args(argv + 2, argv + argc));
    } catch (const mcon::Error& e) {
      const char* status = mcon::status_name(e.status());
      std::fprintf(stderr, "macrocon %s: error (%s): %s\n", name.c_str(), status ? status : "?", e.what());
      return 1;
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "macrocon %s: error (MCON_ERROR_OUT_OF_MEMORY): out of memory\n", name.c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "macrocon %s: error: %s\n", name.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "macrocon: unknown command '%s'\n\n", name.c_str());
  print_usage();
  return 2;
}
