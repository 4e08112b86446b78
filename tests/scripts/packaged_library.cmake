# The native library as the packages (nupkg, wheel) bundle it: a `strip --strip-unneeded` copy
# (12.6 MB -> a fraction: the Release build carries DWARF and a full .symtab), and the check that a
# packaged copy is stripped yet still exports every mcon_ symbol of the built library.
# Included by nuget.pack.cmake, nuget.check.cmake and check_python_wheel.cmake (script mode).

# Copies FROM to TO, stripped with STRIP (CMAKE_STRIP, found by CMake); without a strip tool the
# copy stays unstripped and a message says so.
function(macrocon_strip_copy from to strip)
  get_filename_component(from_real ${from} REALPATH)
  if(strip AND EXISTS "${strip}")
    execute_process(COMMAND ${strip} --strip-unneeded -o ${to} ${from_real}
      RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${strip} --strip-unneeded ${from_real} failed: ${err}")
    endif()
  else()
    message(STATUS "no strip tool (CMAKE_STRIP='${strip}'): bundling ${from_real} unstripped")
    file(COPY_FILE ${from_real} ${to})
  endif()
endfunction()

# The sorted defined dynamic mcon_ symbols of LIB, into OUT_VAR.
function(macrocon_exported_mcon lib nm out_var)
  execute_process(COMMAND ${nm} -D --defined-only ${lib} OUTPUT_VARIABLE out RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${nm} -D ${lib} failed: ${err}")
  endif()
  string(REGEX MATCHALL "[ \t]T mcon_[A-Za-z0-9_]+" hits "${out}")
  set(names "")
  foreach(h ${hits})
    string(REGEX REPLACE "^[ \t]T " "" h "${h}")
    list(APPEND names ${h})
  endforeach()
  list(SORT names)
  set(${out_var} "${names}" PARENT_SCOPE)
endfunction()

# FATAL_ERROR if SECTIONS (a `readelf -S -W` listing of WHAT) still has a .debug_info or .symtab
# section.
function(macrocon_require_stripped sections what)
  foreach(section .debug_info .symtab)
    string(FIND "${sections}" " ${section} " at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${what} still has a ${section} section (not stripped)")
    endif()
  endforeach()
endfunction()

# PACKED (the library inside a package) against BUILT (the build's library): with a strip tool,
# no .debug_info section and the same exported mcon_ symbols; without one, identical bytes.
function(macrocon_check_packaged_library packed built strip readelf nm)
  get_filename_component(built_real ${built} REALPATH)
  if(NOT (strip AND EXISTS "${strip}"))
    file(SHA256 ${packed} a)
    file(SHA256 ${built_real} b)
    if(NOT a STREQUAL b)
      message(FATAL_ERROR "${packed} differs from ${built_real} (no strip tool: it must be a plain copy)")
    endif()
    message(STATUS "no strip tool: ${packed} is the unstripped library, as intended")
    return()
  endif()
  if(readelf AND EXISTS "${readelf}")
    execute_process(COMMAND ${readelf} -S -W ${packed} OUTPUT_VARIABLE sections RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${readelf} -S ${packed} failed: ${err}")
    endif()
    string(FIND "${sections}" ".dynsym" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${packed} has no .dynsym section: not a shared library?")
    endif()
    macrocon_require_stripped("${sections}" "${packed}")
  else()
    message(STATUS "SKIPPED the .debug_info check of ${packed}: readelf not found (CMAKE_READELF='${readelf}')")
  endif()
  if(NOT (nm AND EXISTS "${nm}"))
    message(FATAL_ERROR "nm not found (CMAKE_NM='${nm}'): cannot check the exported mcon_ symbols of ${packed}")
  endif()
  macrocon_exported_mcon(${packed} ${nm} packed_names)
  macrocon_exported_mcon(${built_real} ${nm} built_names)
  list(LENGTH packed_names n)
  if(n EQUAL 0 OR NOT packed_names STREQUAL built_names)
    message(FATAL_ERROR "${packed} exports ${n} mcon_ functions, not those of ${built_real}")
  endif()
  file(SIZE ${packed} packed_size)
  file(SIZE ${built_real} built_size)
  if(NOT packed_size LESS built_size)
    message(FATAL_ERROR "${packed} (${packed_size} bytes) is not smaller than ${built_real} (${built_size} bytes)")
  endif()
  message(STATUS "${packed}: stripped (${packed_size} of ${built_size} bytes), no .debug_info, ${n} mcon_ functions exported")
endfunction()

# ---- Bundled runtime dependencies (issue 5: a customer without Debian's libtbb12 / zlib1g) ----
# The packages carry every shared library that libmacrocon needs beyond the C/C++ runtime every
# Linux has (glibc's libraries, the dynamic loader, libstdc++, libgcc_s), found with ldd (the
# resolved paths, transitively), never from a fixed list. libmacrocon has RUNPATH $ORIGIN
# (src/CMakeLists.txt), so the loader takes them from the package folder.
set(MACROCON_SYSTEM_LIBRARY_REGEX
    "^(linux-vdso|linux-gate|ld-linux[-a-z0-9_]*|libc|libm|libmvec|libpthread|libdl|librt|libresolv|libutil|libstdc\\+\\+|libgcc_s)[.]so([.].*)?$")

# The non-system runtime dependencies of LIB as "soname=resolved path" entries, sorted, into
# OUT_VAR. A dependency the loader cannot resolve is an error (the package would be broken).
function(macrocon_bundled_dependencies lib out_var)
  get_filename_component(lib_real ${lib} REALPATH)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH --unset=LD_PRELOAD ldd ${lib_real}
    OUTPUT_VARIABLE out RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "ldd ${lib_real} failed (${rc}): ${err}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  set(deps "")
  foreach(line ${lines})
    string(STRIP "${line}" line)
    if(line MATCHES "^([^ ]+) => not found")
      message(FATAL_ERROR "${lib_real} needs ${CMAKE_MATCH_1}, which the loader does not find")
    endif()
    if(NOT line MATCHES "^([^ ]+) => ([^ ]+) [(]")
      continue()  # linux-vdso, the absolute loader path
    endif()
    set(soname ${CMAKE_MATCH_1})
    set(path ${CMAKE_MATCH_2})
    if(NOT soname MATCHES "${MACROCON_SYSTEM_LIBRARY_REGEX}")
      list(APPEND deps "${soname}=${path}")
    endif()
  endforeach()
  list(SORT deps)
  set(${out_var} "${deps}" PARENT_SCOPE)
endfunction()

# The Debian package owning the library PATH (dpkg knows it under one of /lib and /usr/lib, as
# linked or as the real file) into OUT_VAR; empty if none.
function(macrocon_owning_package path out_var)
  get_filename_component(real ${path} REALPATH)
  set(candidates ${path} ${real})
  foreach(p ${path} ${real})
    if(p MATCHES "^/usr(/.*)$")
      list(APPEND candidates ${CMAKE_MATCH_1})
    else()
      list(APPEND candidates /usr${p})
    endif()
  endforeach()
  foreach(p ${candidates})
    execute_process(COMMAND dpkg-query -S ${p} OUTPUT_VARIABLE out RESULT_VARIABLE rc ERROR_QUIET)
    if(rc EQUAL 0 AND out MATCHES "^([^:,]+)")
      set(${out_var} ${CMAKE_MATCH_1} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out_var} "" PARENT_SCOPE)
endfunction()

# Copies the DEPS (from macrocon_bundled_dependencies) into DIR under their sonames, stripped like
# libmacrocon, and writes NOTICES: per library a "==== <soname> ====" section naming the Debian
# package and version, followed by that package's copyright file (the licence texts: oneTBB is
# Apache-2.0, zlib the zlib licence). No owning package or copyright file is an error: a
# redistributed library without its licence notice must not ship.
# The notices start with the repository's THIRD_PARTY_NOTICES (what libmacrocon compiles in) and a
# heading; build_wheel.py writes the same bytes.
set(MACROCON_SOURCE_NOTICES ${CMAKE_CURRENT_LIST_DIR}/../../THIRD_PARTY_NOTICES)
function(macrocon_bundle_dependencies deps dir notices strip)
  file(READ ${MACROCON_SOURCE_NOTICES} source_notices)
  string(REPEAT "-" 59 rule)
  string(CONCAT text "${source_notices}" "\n7. Libraries bundled in this package (wheel, NuGet package)\n" "${rule}\n\n"
           "Third-party libraries bundled with libmacrocon (runtime dependencies, unmodified\n"
           "except for stripping), with their copyright and licence notices as shipped by Debian.\n")
  foreach(d ${deps})
    string(REGEX REPLACE "=.*$" "" soname "${d}")
    string(REGEX REPLACE "^[^=]*=" "" path "${d}")
    macrocon_strip_copy(${path} ${dir}/${soname} "${strip}")
    macrocon_owning_package(${path} pkg)
    if(NOT pkg OR NOT EXISTS /usr/share/doc/${pkg}/copyright)
      message(FATAL_ERROR "no licence notice for ${soname} (${path}): owning Debian package '${pkg}' "
                          "has no /usr/share/doc/<package>/copyright; refusing to bundle it without one")
    endif()
    execute_process(COMMAND dpkg-query -W --showformat=\${Version} ${pkg} OUTPUT_VARIABLE ver ERROR_QUIET)
    file(READ /usr/share/doc/${pkg}/copyright copyright)
    string(APPEND text "\n==== ${soname} ====\nDebian package ${pkg} ${ver}, /usr/share/doc/${pkg}/copyright:\n\n${copyright}")
  endforeach()
  file(WRITE ${notices} "${text}")
endfunction()

# Checks the bundled dependencies in DIR (the extracted package folder holding PACKED, the
# packaged libmacrocon) against those of BUILT: each present under its soname, an ELF file with
# that SONAME, stripped if STRIP exists; PACKED has RUNPATH/RPATH $ORIGIN and no empty entry;
# NOTICES has a section with a License: field per library; and ldd, with no LD_LIBRARY_PATH, resolves each dependency of
# PACKED to the copy in DIR (the proof that the bundled copies are the ones used).
function(macrocon_check_bundled_dependencies dir packed built notices strip readelf)
  if(NOT (readelf AND EXISTS "${readelf}"))
    message(FATAL_ERROR "readelf not found (CMAKE_READELF='${readelf}'): cannot check RUNPATH and SONAME")
  endif()
  macrocon_bundled_dependencies(${built} deps)
  list(LENGTH deps n)
  if(n EQUAL 0)
    message(FATAL_ERROR "${built} has no non-system dependencies: expected at least oneTBB")
  endif()
  execute_process(COMMAND ${readelf} -d -W ${packed} OUTPUT_VARIABLE dyn RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR NOT dyn MATCHES "[(](RUNPATH|RPATH)[)][^\n]*[[]([^]\n]*)[]]")
    message(FATAL_ERROR "${packed} has no RUNPATH/RPATH:\n${dyn}")
  endif()
  string(REPLACE ":" ";" runpath "${CMAKE_MATCH_2}")
  list(FIND runpath "$ORIGIN" at)  # script mode: no policies, so no IN_LIST
  if(at EQUAL -1)
    message(FATAL_ERROR "${packed}: ${CMAKE_MATCH_1} is '${CMAKE_MATCH_2}', which lacks $ORIGIN")
  endif()
  # An empty entry (CMake pads build RPATHs with ':') means the current directory to the loader: a
  # customer's program would load a libtbb.so.12 from wherever it is started.
  if(CMAKE_MATCH_2 MATCHES "(^|:)(:|$)")
    message(FATAL_ERROR "${packed}: ${CMAKE_MATCH_1} '${CMAKE_MATCH_2}' has an empty entry (the current directory)")
  endif()
  file(READ ${notices} notice_text)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH --unset=LD_PRELOAD ldd ${packed}
    OUTPUT_VARIABLE ldd_out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "ldd ${packed} failed")
  endif()
  get_filename_component(dir_real ${dir} REALPATH)
  foreach(d ${deps})
    string(REGEX REPLACE "=.*$" "" soname "${d}")
    set(copy ${dir}/${soname})
    if(NOT EXISTS ${copy})
      message(FATAL_ERROR "the package lacks the bundled dependency ${soname} next to ${packed}")
    endif()
    file(READ ${copy} head LIMIT 4 HEX)
    execute_process(COMMAND ${readelf} -d -S -W ${copy} OUTPUT_VARIABLE info RESULT_VARIABLE rc)
    string(REPLACE "+" "[+]" soname_re "${soname}")
    if(NOT head STREQUAL "7f454c46" OR NOT rc EQUAL 0 OR NOT info MATCHES "[(]SONAME[)][^\n]*[[]${soname_re}[]]")
      message(FATAL_ERROR "${copy} is not a shared library with SONAME ${soname}")
    endif()
    if(strip AND EXISTS "${strip}")
      macrocon_require_stripped("${info}" "${copy}")
    endif()
    string(FIND "${notice_text}" "==== ${soname} ====" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${notices} has no section for ${soname}")
    endif()
    string(SUBSTRING "${notice_text}" ${at} -1 section)
    string(REGEX REPLACE "^==== [^\n]*\n" "" section "${section}")
    string(REGEX REPLACE "\n==== .*$" "" section "${section}")
    if(NOT section MATCHES "\nLicense: [^\n]+")
      message(FATAL_ERROR "${notices}: the section of ${soname} names no licence")
    endif()
    if(NOT ldd_out MATCHES "${soname_re} => ([^ \n]+)")
      message(FATAL_ERROR "ldd ${packed} does not list ${soname}:\n${ldd_out}")
    endif()
    get_filename_component(resolved ${CMAKE_MATCH_1} REALPATH)
    get_filename_component(expected ${copy} REALPATH)
    if(NOT resolved STREQUAL expected)
      message(FATAL_ERROR "ldd ${packed}: ${soname} resolves to ${CMAKE_MATCH_1}, not the bundled ${copy}:\n${ldd_out}")
    endif()
  endforeach()
  message(STATUS "${packed}: RUNPATH has $ORIGIN; bundled and used by the loader: ${deps}")
endfunction()
