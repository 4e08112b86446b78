# Packs the C# binding as a .nupkg without nuget.exe (none can be downloaded here): a .nupkg is an
# OPC zip with the .nuspec at its root. Reads the <file src= target=> entries of NUSPEC, copies
# DLL (Macrocon.dll) and LIB (the native library, real file behind the symlinks; stripped with
# STRIP = CMAKE_STRIP, unstripped if empty) to those targets, adds the OPC parts
# ([Content_Types].xml, _rels/.rels) and zips it to OUT. The native library's non-system runtime
# dependencies and their licence notices (THIRD_PARTY_NOTICES.txt) are bundled next to it.
#   cmake -DNUSPEC=... -DDLL=... -DLIB=... -DVERSION=0.1.0 -DOUT=.../Macrocon.0.1.0.nupkg [-DSTRIP=/usr/bin/strip] -P nuget.pack.cmake
include(${CMAKE_CURRENT_LIST_DIR}/packaged_library.cmake)
foreach(v NUSPEC DLL LIB VERSION OUT)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "nuget.pack.cmake: -D${v}= is required")
  endif()
endforeach()
get_filename_component(out_dir ${OUT} DIRECTORY)
set(stage ${out_dir}/nupkg-stage)
file(REMOVE_RECURSE ${stage})
file(MAKE_DIRECTORY ${stage})
file(READ ${NUSPEC} spec)
string(REPLACE "$version$" "${VERSION}" spec "${spec}")
file(WRITE ${stage}/Macrocon.nuspec "${spec}")
get_filename_component(lib_real ${LIB} REALPATH)
get_filename_component(repo ${CMAKE_CURRENT_LIST_DIR}/../.. ABSOLUTE)
set(sources "Macrocon.dll=${DLL}" "libmacrocon.so=${lib_real}" "LICENSE=${repo}/LICENSE")
string(REGEX MATCHALL "<file src=\"[^\"]+\" target=\"[^\"]+\"" entries "${spec}")
set(members Macrocon.nuspec)
foreach(e ${entries})
  string(REGEX REPLACE "<file src=\"([^\"]+)\" target=\"([^\"]+)\"" "\\1;\\2" pair "${e}")
  list(GET pair 0 src)
  list(GET pair 1 target)
  set(from "")
  foreach(s ${sources})
    string(REPLACE "=" ";" kv "${s}")
    list(GET kv 0 k)
    list(GET kv 1 path)
    if(k STREQUAL src)
      set(from ${path})
    endif()
  endforeach()
  if(NOT from)
    message(FATAL_ERROR "nuget.pack.cmake: no input for <file src=\"${src}\">")
  endif()
  get_filename_component(target_dir ${stage}/${target} DIRECTORY)
  file(MAKE_DIRECTORY ${target_dir})
  if(src STREQUAL "libmacrocon.so")
    macrocon_strip_copy(${from} ${stage}/${target} "${STRIP}")
  else()
    file(COPY_FILE ${from} ${stage}/${target})
  endif()
  list(APPEND members ${target})
  if(src STREQUAL "libmacrocon.so")
    set(native_dir ${target_dir})
  endif()
endforeach()
# The native library's non-system runtime dependencies (libtbb, libz: found with ldd) go next to it
# with their licence notices (packaged_library.cmake); libmacrocon's RUNPATH $ORIGIN finds them.
# They are listed in the staged nuspec too, and get OPC content types by part name (their
# extensions are version numbers).
macrocon_bundled_dependencies(${lib_real} deps)
macrocon_bundle_dependencies("${deps}" ${native_dir} ${native_dir}/THIRD_PARTY_NOTICES.txt "${STRIP}")
file(RELATIVE_PATH native_rel ${stage} ${native_dir})
set(extra_files "")
set(overrides "")
foreach(d ${deps} "THIRD_PARTY_NOTICES.txt=")
  string(REGEX REPLACE "=.*$" "" name "${d}")
  string(APPEND extra_files "    <file src=\"${name}\" target=\"${native_rel}/${name}\" />\n")
  if(NOT name MATCHES "[.]txt$")
    string(APPEND overrides "<Override PartName=\"/${native_rel}/${name}\" ContentType=\"application/octet\" />")
  endif()
  list(APPEND members ${native_rel}/${name})
endforeach()
string(REPLACE "  </files>" "${extra_files}  </files>" spec "${spec}")
file(WRITE ${stage}/Macrocon.nuspec "${spec}")
file(WRITE "${stage}/[Content_Types].xml"
  "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
  "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">"
  "<Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\" />"
  "<Default Extension=\"nuspec\" ContentType=\"application/octet\" />"
  "<Default Extension=\"dll\" ContentType=\"application/octet\" />"
  "<Default Extension=\"so\" ContentType=\"application/octet\" />"
  "<Default Extension=\"txt\" ContentType=\"text/plain\" />"
  "<Override PartName=\"/LICENSE\" ContentType=\"text/plain\" />"
  "${overrides}"
  "</Types>\n")
file(MAKE_DIRECTORY ${stage}/_rels)
file(WRITE ${stage}/_rels/.rels
  "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
  "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">"
  "<Relationship Type=\"http://schemas.microsoft.com/packaging/2010/07/manifest\" Target=\"/Macrocon.nuspec\" Id=\"R0\" />"
  "</Relationships>\n")
list(APPEND members "[Content_Types].xml" _rels/.rels)
file(REMOVE ${OUT})
# Fixed timestamps: the same inputs give the same package bytes.
execute_process(COMMAND ${CMAKE_COMMAND} -E tar cf ${OUT} --format=zip "--mtime=2026-01-01 00:00:00 UTC" -- ${members}
  WORKING_DIRECTORY ${stage} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nuget.pack.cmake: zipping ${OUT} failed")
endif()
message(STATUS "packed ${OUT}: ${members}")
