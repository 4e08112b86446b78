# Python binding tests with Debian's interpreter (numpy + pytest come from Debian packages).
# In the sanitizer build the uninstrumented python3 loads the ASan library with the sanitizer
# runtimes preloaded (sanitizer_preload.cmake); the wheel test is Release-only.
include(${CMAKE_CURRENT_LIST_DIR}/sanitizer_preload.cmake)
if(NOT MACROCON_SANITIZE OR MACROCON_SANITIZER_ENV)
  set(MACROCON_PYTHON /usr/bin/python3 CACHE FILEPATH "Python with numpy and pytest for the binding tests")
  # The clean-exit tests (subprocesses that leave handles open after parallel work; the exit hook
  # must release them and mcon_shutdown must succeed) are their own ctest entry.
  add_test(NAME python.pytest
    COMMAND ${MACROCON_PYTHON} -m pytest -q -p no:cacheprovider -k "not exits_cleanly"
            ${PROJECT_SOURCE_DIR}/bindings/python/tests)
  add_test(NAME python.exit_clean_after_parallel_work
    COMMAND ${MACROCON_PYTHON} -m pytest -q -p no:cacheprovider -k "exits_cleanly"
            ${PROJECT_SOURCE_DIR}/bindings/python/tests)
  set_tests_properties(python.pytest python.exit_clean_after_parallel_work PROPERTIES
    ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;PYTHONPATH=${PROJECT_SOURCE_DIR}/bindings/python;${MACROCON_SANITIZER_ENV}"
    TIMEOUT 1800)
endif()
if(NOT MACROCON_SANITIZE)
  # Turning per length of every demo guide (tools/dev/guide_turning.py): traced guides must stay
  # within 2.5x of their source's (measured at most 1.68x; 6.65x before they were straightened on
  # the surface, docs/design.md §16).
  add_test(NAME tools.guide_turning
    COMMAND ${MACROCON_PYTHON} ${PROJECT_SOURCE_DIR}/tools/dev/guide_turning.py
            --library ${MACROCON_STARTER_LIBRARY} --body ${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz
            --fail-over 2.5)
  set_tests_properties(tools.guide_turning PROPERTIES TIMEOUT 600
    ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;PYTHONPATH=${PROJECT_SOURCE_DIR}/bindings/python:${PROJECT_SOURCE_DIR}/samples/python")
  # A guide that goes out and back along a toe (the foot entry on a hand with Gaussian noise of 0.1
  # edge length) was straightened into a guide that crossed itself, and the cut refused it; the
  # trace must reach the cut (docs/design.md §16).
  add_test(NAME tools.guide_turning.out_and_back
    COMMAND ${MACROCON_PYTHON} ${PROJECT_SOURCE_DIR}/tools/dev/guide_turning.py
            --library ${MACROCON_STARTER_LIBRARY} --body ${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz
            --noise 0.1 --region hand_r:3197:1.2:foot_r)
  set_tests_properties(tools.guide_turning.out_and_back PROPERTIES TIMEOUT 600
    ENVIRONMENT "MACROCON_LIBRARY=$<TARGET_FILE:macrocon>;PYTHONPATH=${PROJECT_SOURCE_DIR}/bindings/python:${PROJECT_SOURCE_DIR}/samples/python")
  # The wheel bundles the library: install it into a scratch folder and import it from there
  # without MACROCON_LIBRARY.
  add_test(NAME python.wheel
    COMMAND ${CMAKE_COMMAND} -DPYTHON=${MACROCON_PYTHON} -DLIB=$<TARGET_FILE:macrocon>
            -DSRC=${PROJECT_SOURCE_DIR}/bindings/python -DWORK=${PROJECT_BINARY_DIR}/python-wheel
            -DSTARTER=${MACROCON_STARTER_LIBRARY}
            "-DSTRIP=${CMAKE_STRIP}" "-DREADELF=${CMAKE_READELF}" "-DNM=${CMAKE_NM}"
            -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_python_wheel.cmake)
endif()
