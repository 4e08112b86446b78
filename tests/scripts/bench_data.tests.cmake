# core_test_bench_data tests the evaluation tools' benchmark data layer (tools/common), which is not
# part of the core: link it (and with it its include directory) into that one test executable.
if(TARGET core_test_bench_data)
  target_link_libraries(core_test_bench_data PRIVATE macrocon_tools_common)
endif()
