# `macrocon patch --json` on an icosahedron written outward, inward (every face reversed) and with
# a Moebius strip: the inward file gives the same patch and reports the repair in "orientation";
# the strip is refused with MCON_ERROR_NON_ORIENTABLE and a message naming the fix.
add_test(NAME scripts.patch_orientation
  COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:macrocon_cli> -DOUT=${CMAKE_CURRENT_BINARY_DIR}/patch_orientation
          -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_patch_orientation.cmake)
