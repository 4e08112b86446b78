# Every option of every command of `macrocon` and `macrocon-eval` has a line of --help
# (tools/command/args.h OptionHelp); the script first checks that it catches an option without one.
find_program(MACROCON_PYTHON3 NAMES python3 REQUIRED)
add_test(NAME scripts.cli_help_describes_every_option
  COMMAND ${MACROCON_PYTHON3} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli_help.py
          $<TARGET_FILE:macrocon_cli> $<TARGET_FILE:macrocon_eval>)
