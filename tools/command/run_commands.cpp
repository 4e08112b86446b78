#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "base/error.h"
#include "command/command.h"
#include "macrocon/macrocon.h"

namespace mcon::cli {

std::vector<Command>& commands() {
  static std::vector<Command> list;
  return list;
}

namespace {

void print_usage(const char* program) {
  auto cmds = commands();
  std::sort(cmds.begin(), cmds.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  std::fprintf(stderr, "%s %d.%d.%d\nusage: %s <command> [options]   (%s <command> --help)\n\n", program,
               MCON_VERSION_MAJOR, MCON_VERSION_MINOR, MCON_VERSION_PATCH, program, program);
  for (const auto& c : cmds) std::fprintf(stderr, "  %-16s %s\n", c.name.c_str(), c.summary.c_str());
}

}  // namespace

int run_commands(const char* program, int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    print_usage(program);
    return argc < 2 ? 2 : 0;
  }
  if (std::string(argv[1]) == "--version") {
    std::printf("%d.%d.%d\n", MCON_VERSION_MAJOR, MCON_VERSION_MINOR, MCON_VERSION_PATCH);
    return 0;
  }
  const std::string name = argv[1];
  for (const auto& c : commands()) {
    if (c.name != name) continue;
    try {
      return c.run(Args(argv + 2, argv + argc));
    } catch (const Error& e) {
      const char* status = status_name(e.status());
      std::fprintf(stderr, "%s %s: error (%s): %s\n", program, name.c_str(), status ? status : "?", e.what());
      return 1;
    } catch (const std::bad_alloc&) {
      std::fprintf(stderr, "%s %s: error (MCON_ERROR_OUT_OF_MEMORY): out of memory\n", program, name.c_str());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s %s: error: %s\n", program, name.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "%s: unknown command '%s'\n\n", program, name.c_str());
  print_usage(program);
  return 2;
}

}  // namespace mcon::cli
