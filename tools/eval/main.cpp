// `macrocon-eval`: the evaluation commands (eval-mapping, eval-retrieval, bench) on the benchmark
// data of tools/common. Not part of the product: the `macrocon` CLI links none of it.
#include "command/command.h"

int main(int argc, char** argv) { return mcon::cli::run_commands("macrocon-eval", argc, argv); }
