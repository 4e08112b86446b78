# The API reference builds from the headers without a Doxygen warning (a broken reference, an
# unknown command, a comment attached to nothing it can document).
if(MACROCON_DOXYGEN)
  add_test(NAME docs.api_reference
    COMMAND ${CMAKE_COMMAND} -DDOXYGEN=${MACROCON_DOXYGEN} -DDOXYFILE=${PROJECT_BINARY_DIR}/docs/Doxyfile
            -DOUT=${MACROCON_DOXYGEN_OUT} -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_api_reference.cmake)
  set_tests_properties(docs.api_reference PROPERTIES TIMEOUT 300)
else()
  message(STATUS "docs.api_reference NOT registered: doxygen was not found (apt-get install doxygen)")
endif()

# docs/python_api.md is the Python binding's reference, generated from its docstrings: it must
# match what the generator writes now (a changed docstring or signature means regenerating it).
if(NOT MACROCON_SANITIZE)
  set(MACROCON_PYTHON /usr/bin/python3 CACHE FILEPATH "Python with numpy and pytest for the binding tests")
  add_test(NAME docs.python_api_reference
    COMMAND ${MACROCON_PYTHON} ${PROJECT_SOURCE_DIR}/tools/dev/python_api_reference.py
            --out ${PROJECT_SOURCE_DIR}/docs/python_api.md --check)
  set_tests_properties(docs.python_api_reference PROPERTIES TIMEOUT 120
    ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;PYTHONPATH=${PROJECT_SOURCE_DIR}/bindings/python")
endif()
