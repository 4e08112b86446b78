# No function in src/ or tools/ is longer than 120 lines (CONTRIBUTING.md); the check itself fails
# on a longer one (a generated 121-line function).
find_program(MACROCON_PYTHON3 NAMES python3 REQUIRED)
add_test(NAME scripts.function_length
  COMMAND ${MACROCON_PYTHON3} ${PROJECT_SOURCE_DIR}/tools/dev/function_lengths.py --top 10 --max 120
          ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}/tools)
set(long_function_dir ${CMAKE_CURRENT_BINARY_DIR}/function_length_fixture)
set(long_body "")
foreach(i RANGE 1 119)
  string(APPEND long_body "  x += ${i};\n")
endforeach()
file(WRITE ${long_function_dir}/long.cpp "int long_function(int x) {\n${long_body}}\n")
add_test(NAME scripts.function_length_catches_a_long_function
  COMMAND ${MACROCON_PYTHON3} ${PROJECT_SOURCE_DIR}/tools/dev/function_lengths.py --max 120 ${long_function_dir})
set_tests_properties(scripts.function_length_catches_a_long_function PROPERTIES WILL_FAIL TRUE)
