// `macrocon`: the product commands (patch, query, library, embed, demo). The evaluation commands
// are in `macrocon-eval` (tools/eval).
#include "command/command.h"

int main(int argc, char** argv) { return mcon::cli::run_commands("macrocon", argc, argv); }
