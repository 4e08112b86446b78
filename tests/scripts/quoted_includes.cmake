# quoted_includes(<file> <out>): the quoted #include lines of <file>, as "<line>:<header>" items in
# file order, for the include checks (check_include_rule.cmake, check_cli_public_api.cmake).
function(quoted_includes file out)
  file(STRINGS ${file} lines)
  set(found "")
  set(line_number 0)
  foreach(line IN LISTS lines)
    math(EXPR line_number "${line_number} + 1")
    if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\"")
      list(APPEND found "${line_number}:${CMAKE_MATCH_1}")
    endif()
  endforeach()
  set(${out} "${found}" PARENT_SCOPE)
endfunction()
