// Subcommands of the `macrocon` and `macrocon-eval` programs register themselves here, one file
// each, so that adding a command never touches a main():
//   static const mcon::cli::Registration reg{"patch", "extract a geodesic disk patch", run_patch};
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace mcon::cli {

using Args = std::vector<std::string>;  // arguments after the subcommand name

struct Command {
  std::string name;
  std::string summary;
  std::function<int(const Args&)> run;  // returns the process exit status
};

std::vector<Command>& commands();

// The whole program: `<program> <command> [options]`, `--help`, `--version`; errors go to stderr
// with a non-zero exit status. Returns the exit status.
int run_commands(const char* program, int argc, char** argv);

struct Registration {
  Registration(std::string name, std::string summary, std::function<int(const Args&)> run) {
    commands().push_back({std::move(name), std::move(summary), std::move(run)});
  }
};

}  // namespace mcon::cli
