# Builds the wheel (library stripped with STRIP = CMAKE_STRIP), checks the bundled library
# (stripped, same mcon_ exports: packaged_library.cmake) and imports the package from it.
include(${CMAKE_CURRENT_LIST_DIR}/packaged_library.cmake)
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${PYTHON} ${SRC}/build_wheel.py --library ${LIB} --out ${WORK}/dist "--strip=${STRIP}"
  OUTPUT_VARIABLE wheel RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the wheel failed")
endif()
file(ARCHIVE_EXTRACT INPUT ${wheel} DESTINATION ${WORK}/site)
get_filename_component(lib_name ${LIB} NAME)
if(NOT EXISTS ${WORK}/site/macrocon/${lib_name})
  message(FATAL_ERROR "the wheel lacks macrocon/${lib_name}")
endif()
macrocon_check_packaged_library(${WORK}/site/macrocon/${lib_name} ${LIB} "${STRIP}" "${READELF}" "${NM}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=MACROCON_LIBRARY PYTHONPATH=${WORK}/site
  ${PYTHON} -c "import macrocon, os; assert os.path.dirname(macrocon.__file__).startswith('${WORK}'); print(macrocon.version())"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "importing from the wheel failed: ${err}")
endif()
message(STATUS "wheel ${wheel} imports: ${out}")
