# `macrocon embed` on the bundled MakeHuman body: the nose (r 0.45) onto a re-cut of the same nose
# with a different radius (0.55), once with both patches cut from the mesh and once with the
# source given as an already-cut patch file. The outputs must exist and the map must have no flip.
add_test(NAME scripts.embed_cli
  COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_cli>
          -DMESH=${PROJECT_SOURCE_DIR}/samples/data/makehuman-body.obj.gz
          -DOUT=${CMAKE_CURRENT_BINARY_DIR}/embed_cli
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/embed_cli.cmake)
set_tests_properties(scripts.embed_cli PROPERTIES TIMEOUT 600)
