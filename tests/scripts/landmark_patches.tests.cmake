# `macrocon patch` on every benchmark landmark of both shared models: each must give a disk
# (one boundary loop, Euler characteristic 1) with a flip-free parametrization.
foreach(model makehuman ict)
  add_test(NAME scripts.landmark_patches_${model}
    COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_cli> -DSHARED=${MACROCON_SHARED_DIR}
            -DSPEC=${MACROCON_SHARED_DIR}/bench/${model}-landmarks.json
            -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_landmark_patches.cmake)
  set_tests_properties(scripts.landmark_patches_${model} PROPERTIES TIMEOUT 1200)
endforeach()
