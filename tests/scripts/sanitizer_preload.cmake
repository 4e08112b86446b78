# In the sanitizer build, hosts that are not instrumented (python3, mono) can still load the
# ASan+UBSan libmacrocon when the sanitizer runtimes are preloaded. Sets MACROCON_SANITIZER_ENV to
# the ctest ENVIRONMENT entries that do it (empty outside the sanitizer build or if not found).
set(MACROCON_SANITIZER_ENV "")
if(MACROCON_SANITIZE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libasan.so OUTPUT_VARIABLE asan_rt OUTPUT_STRIP_TRAILING_WHITESPACE)
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libubsan.so OUTPUT_VARIABLE ubsan_rt OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(EXISTS "${asan_rt}" AND EXISTS "${ubsan_rt}")
    # Leaks are the host's (the interpreters never free everything); mono installs its own SEGV
    # handler for its GC, which ASan must leave alone.
    set(MACROCON_SANITIZER_ENV
        "LD_PRELOAD=${asan_rt} ${ubsan_rt}"
        "ASAN_OPTIONS=detect_leaks=0:halt_on_error=1:handle_segv=0:allow_user_segv_handler=1"
        "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1")
  endif()
endif()
