# run_checked(): the scripted tests' one way to run a command and check how it exited, so that a
# failure always says what ran and shows what it printed. Include it from a script run with
# `cmake -P`:  include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
#
#   run_checked([WHAT <text>] [OUTPUT_VARIABLE <var>] [ERROR_VARIABLE <var>]
#               [WORKING_DIRECTORY <dir>] [EXPECT_FAILURE <regex>]
#               COMMAND <command> [<arg>...])
#
# By default the command must exit with status 0. With EXPECT_FAILURE it must instead exit with a
# non-zero status and print a message matching <regex> on stderr (bad input is refused with a
# clear message); a crash (a signal, not an exit status) does not count as refusing. Otherwise the
# script stops with FATAL_ERROR naming WHAT (default: the command line), the exit status, the
# command line and the command's stdout and stderr. OUTPUT_VARIABLE and ERROR_VARIABLE receive
# stdout and stderr in the caller's scope. COMMAND comes last: everything after it is the command
# line (which therefore must not contain the words above; empty arguments are dropped, an
# argument's own ';' is kept).
function(run_checked)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "WHAT;OUTPUT_VARIABLE;ERROR_VARIABLE;WORKING_DIRECTORY;EXPECT_FAILURE"
                        "COMMAND")
  if(arg_UNPARSED_ARGUMENTS OR NOT arg_COMMAND)
    message(FATAL_ERROR "run_checked: usage: run_checked([WHAT ..] [OUTPUT_VARIABLE ..] [ERROR_VARIABLE ..] "
                        "[WORKING_DIRECTORY ..] [EXPECT_FAILURE ..] COMMAND ..), got '${ARGV}'")
  endif()
  set(options "")
  if(DEFINED arg_WORKING_DIRECTORY)
    set(options WORKING_DIRECTORY ${arg_WORKING_DIRECTORY})
  endif()
  execute_process(COMMAND ${arg_COMMAND} ${options} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)

  # For messages: the arguments separated by spaces (an argument's own ';' stays a ';').
  string(REPLACE "\\;" "<semicolon>" command_line "${arg_COMMAND}")
  string(REPLACE ";" " " command_line "${command_line}")
  string(REPLACE "<semicolon>" ";" command_line "${command_line}")
  if(DEFINED arg_WHAT)
    set(what "${arg_WHAT}")
  else()
    set(what "${command_line}")
  endif()
  set(problem "")
  if(DEFINED arg_EXPECT_FAILURE)
    if(NOT rc MATCHES "^[0-9]+$")
      set(problem "expected a refusal matching '${arg_EXPECT_FAILURE}', but it did not exit normally (${rc})")
    elseif(rc EQUAL 0)
      set(problem "expected a refusal matching '${arg_EXPECT_FAILURE}', but it exited with status 0")
    elseif(NOT err MATCHES "${arg_EXPECT_FAILURE}")
      set(problem "exited with status ${rc} as expected, but stderr does not match '${arg_EXPECT_FAILURE}'")
    endif()
  elseif(NOT rc STREQUAL "0")
    set(problem "failed (exit status '${rc}')")
  endif()
  if(NOT problem STREQUAL "")
    string(STRIP "${out}" shown_out)
    string(STRIP "${err}" shown_err)
    message(FATAL_ERROR "${what}: ${problem}\n  command: ${command_line}\n"
                        "--- stdout ---\n${shown_out}\n--- stderr ---\n${shown_err}")
  endif()
  if(DEFINED arg_EXPECT_FAILURE)
    string(STRIP "${err}" refusal)
    message(STATUS "refused as expected (status ${rc}): ${refusal}")
  endif()
  if(DEFINED arg_OUTPUT_VARIABLE)
    set(${arg_OUTPUT_VARIABLE} "${out}" PARENT_SCOPE)
  endif()
  if(DEFINED arg_ERROR_VARIABLE)
    set(${arg_ERROR_VARIABLE} "${err}" PARENT_SCOPE)
  endif()
endfunction()
