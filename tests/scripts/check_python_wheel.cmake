file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${PYTHON} ${SRC}/build_wheel.py --library ${LIB} --out ${WORK}/dist
  OUTPUT_VARIABLE wheel RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the wheel failed")
endif()
file(ARCHIVE_EXTRACT INPUT ${wheel} DESTINATION ${WORK}/site)
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=MACROCON_LIBRARY PYTHONPATH=${WORK}/site
  ${PYTHON} -c "import macrocon, os; assert os.path.dirname(macrocon.__file__).startswith('${WORK}'); print(macrocon.version())"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "importing from the wheel failed: ${err}")
endif()
message(STATUS "wheel ${wheel} imports: ${out}")
