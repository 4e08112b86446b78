# ABI gate: compare the built library with the committed abidw baseline. Additions pass; an
# incompatible change fails (a deliberate break bumps the major version and the baseline in the
# same commit). Regenerate with: tools/update-abi-baseline.sh
find_program(MACROCON_ABIDIFF abidiff)
if(NOT MACROCON_SANITIZE AND MACROCON_ABIDIFF AND EXISTS ${PROJECT_SOURCE_DIR}/packaging/abi/libmacrocon.abi)
  add_test(NAME packaging.abi_compatible
    COMMAND ${CMAKE_COMMAND} -DABIDIFF=${MACROCON_ABIDIFF} -DLIB=$<TARGET_FILE:macrocon>
            -DBASELINE=${PROJECT_SOURCE_DIR}/packaging/abi/libmacrocon.abi -DHEADERS=${PROJECT_SOURCE_DIR}/include/macrocon
            -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_abi.cmake)
elseif(NOT MACROCON_SANITIZE)
  message(WARNING "ABI gate not registered (abidiff missing or no baseline)")
endif()
