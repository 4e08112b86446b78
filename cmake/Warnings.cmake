# Warnings apply to our own targets only; third-party headers come in as SYSTEM includes
# (OpenMesh trips -Wmaybe-uninitialized under g++ 12, docs/design.md §8).
function(macrocon_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local)
  if(MACROCON_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
