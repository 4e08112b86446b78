# Builds the wheel (library stripped with STRIP = CMAKE_STRIP), checks the bundled library
# (stripped, same mcon_ exports: packaged_library.cmake), its bundled runtime dependencies (libtbb,
# libz: present, stripped, licensed, found through RUNPATH $ORIGIN) and imports the package from it
# with an empty LD_LIBRARY_PATH, checking that the loader took the bundled copies. The wheel also
# carries the starter library (STARTER, byte-identical; macrocon.starter_library() returns it),
# the repository's LICENSE (in the package and the dist-info) and METADATA naming the licence;
# THIRD_PARTY_NOTICES.txt starts with the repository's THIRD_PARTY_NOTICES.
include(${CMAKE_CURRENT_LIST_DIR}/packaged_library.cmake)
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${PYTHON} ${SRC}/build_wheel.py --library ${LIB} --starter-library ${STARTER}
                        --out ${WORK}/dist "--strip=${STRIP}"
  OUTPUT_VARIABLE wheel RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the wheel failed")
endif()
file(ARCHIVE_EXTRACT INPUT ${wheel} DESTINATION ${WORK}/site)
# Licence, notices, starter library and METADATA.
execute_process(COMMAND ${CMAKE_COMMAND} -E tar tf ${wheel} OUTPUT_VARIABLE members RESULT_VARIABLE rc)
file(GLOB dist_info RELATIVE ${WORK}/site ${WORK}/site/macrocon-*.dist-info)
if(NOT rc EQUAL 0 OR NOT dist_info)
  message(FATAL_ERROR "${wheel}: not a readable zip with a dist-info folder:\n${members}")
endif()
get_filename_component(repo ${SRC}/../.. ABSOLUTE)
foreach(pair "macrocon/starter.mclb=${STARTER}" "macrocon/LICENSE=${repo}/LICENSE" "${dist_info}/LICENSE=${repo}/LICENSE")
  string(REGEX REPLACE "=.*$" "" member "${pair}")
  string(REGEX REPLACE "^[^=]*=" "" source "${pair}")
  string(FIND "${members}" "${member}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the wheel lacks ${member}:\n${members}")
  endif()
  file(SHA256 ${WORK}/site/${member} a)
  file(SHA256 ${source} b)
  if(NOT a STREQUAL b)
    message(FATAL_ERROR "the wheel's ${member} differs from ${source}")
  endif()
endforeach()
file(READ ${WORK}/site/${dist_info}/METADATA metadata)
foreach(line "License: Apache-2.0" "License-File: LICENSE" "Classifier: License :: OSI Approved :: Apache Software License")
  string(FIND "${metadata}" "\n${line}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${dist_info}/METADATA lacks '${line}':\n${metadata}")
  endif()
endforeach()
file(READ ${repo}/THIRD_PARTY_NOTICES source_notices)
file(READ ${WORK}/site/macrocon/THIRD_PARTY_NOTICES.txt wheel_notices)
string(LENGTH "${source_notices}" n)
string(SUBSTRING "${wheel_notices}" 0 ${n} head)
if(NOT head STREQUAL source_notices)
  message(FATAL_ERROR "the wheel's THIRD_PARTY_NOTICES.txt does not start with the repository's THIRD_PARTY_NOTICES")
endif()
get_filename_component(lib_name ${LIB} NAME)
if(NOT EXISTS ${WORK}/site/macrocon/${lib_name})
  message(FATAL_ERROR "the wheel lacks macrocon/${lib_name}")
endif()
macrocon_check_packaged_library(${WORK}/site/macrocon/${lib_name} ${LIB} "${STRIP}" "${READELF}" "${NM}")
# The bundled dependencies (build_wheel.py): the files ldd names for the built library, stripped,
# with RUNPATH $ORIGIN on the packaged library, licensed, and resolved by ldd to the wheel's copies.
set(pkg ${WORK}/site/macrocon)
macrocon_check_bundled_dependencies(${pkg} ${pkg}/${lib_name} ${LIB} ${pkg}/THIRD_PARTY_NOTICES.txt "${STRIP}" "${READELF}")
# build_wheel.py implements the bundling in Python; it must give the bytes the CMake rules of the
# NuGet package give (packaged_library.cmake), and no other shared library may be in the wheel.
macrocon_bundled_dependencies(${LIB} deps)
file(MAKE_DIRECTORY ${WORK}/expected)
macrocon_bundle_dependencies("${deps}" ${WORK}/expected ${WORK}/expected/THIRD_PARTY_NOTICES.txt "${STRIP}")
set(want_libs ${lib_name})
foreach(d ${deps} "THIRD_PARTY_NOTICES.txt=")
  string(REGEX REPLACE "=.*$" "" name "${d}")
  file(SHA256 ${WORK}/expected/${name} a)
  file(SHA256 ${pkg}/${name} b)
  if(NOT a STREQUAL b)
    message(FATAL_ERROR "the wheel's macrocon/${name} differs from the one packaged_library.cmake makes")
  endif()
  if(name MATCHES "[.]so")
    list(APPEND want_libs ${name})
  endif()
endforeach()
file(GLOB have_libs RELATIVE ${pkg} ${pkg}/*.so ${pkg}/*.so.*)
list(SORT have_libs)
list(SORT want_libs)
if(NOT have_libs STREQUAL want_libs)
  message(FATAL_ERROR "the wheel's shared libraries are ${have_libs}, expected ${want_libs}")
endif()
# Load test: a fresh interpreter with an empty LD_LIBRARY_PATH and no MACROCON_LIBRARY imports the
# package from the extracted wheel and queries the version. Every bundled dependency that the bare
# interpreter had not mapped already (python3 itself links libz) must then be mapped from the
# wheel's folder, not from /usr/lib: /proc/self/maps shows which file the loader took.
set(sonames "")
foreach(d ${deps})
  string(REGEX REPLACE "=.*$" "" soname "${d}")
  string(APPEND sonames "'${soname}',")
endforeach()
set(probe [=[
import os, sys
def mapped():
    with open('/proc/self/maps') as f:
        return {l.split()[-1] for l in f if '/' in l}
before = mapped()
import macrocon
pkg = os.path.realpath(os.path.dirname(macrocon.__file__))
assert pkg == os.path.realpath(sys.argv[1]), pkg
print('version', '.'.join(map(str, macrocon.version())))
starter = macrocon.starter_library()
assert starter == os.path.join(pkg, 'starter.mclb'), starter
print('starter library', starter)
after = mapped()
bundled = 0
for soname in (@sonames@):
    if any(os.path.basename(p) == soname or os.path.basename(os.path.realpath(p)).startswith(soname) for p in before):
        print('preloaded by the interpreter:', soname)
        continue
    hits = sorted(p for p in after if os.path.basename(p) == soname or os.path.basename(os.path.realpath(p)).startswith(soname))
    assert hits == [os.path.join(pkg, soname)], (soname, hits)
    print('loaded from the wheel:', hits[0])
    bundled += 1
assert bundled > 0, 'no bundled dependency was loaded from the wheel'
]=])
string(CONFIGURE "${probe}" probe @ONLY)
file(WRITE ${WORK}/probe.py "${probe}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=MACROCON_LIBRARY --unset=MACROCON_STARTER_LIBRARY --unset=LD_PRELOAD LD_LIBRARY_PATH= PYTHONPATH=${WORK}/site
  ${PYTHON} ${WORK}/probe.py ${pkg}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "version [0-9]+[.][0-9]+[.][0-9]+")
  message(FATAL_ERROR "importing from the wheel failed (exit ${rc}):\n${out}\n${err}")
endif()
message(STATUS "wheel ${wheel} imports with LD_LIBRARY_PATH empty:\n${out}")

# The documented offline install (README "Python wheel"): pip from Debian's python3-pip into a venv
# of Debian's interpreter (python3-venv; --system-site-packages for Debian's numpy), --no-index,
# then import from the venv with no MACROCON_LIBRARY: the library, the starter library and the
# licence metadata come from the installed wheel. Missing pip or venv fails the test with a message.
execute_process(COMMAND ${PYTHON} -m pip --version RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PYTHON} -m pip does not run (Debian package python3-pip, tools/debian-packages.txt): "
                      "cannot check the documented `pip install` of the wheel")
endif()
execute_process(COMMAND ${PYTHON} -m venv --system-site-packages ${WORK}/venv RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PYTHON} -m venv failed (Debian package python3-venv, tools/debian-packages.txt): ${err}")
endif()
execute_process(COMMAND ${WORK}/venv/bin/python -m pip install --no-index --no-deps --disable-pip-version-check ${wheel}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pip install ${wheel} into a venv failed:\n${out}\n${err}")
endif()
set(venv_probe [=[
import os, sys, importlib.metadata as md
import macrocon
pkg = os.path.dirname(os.path.realpath(macrocon.__file__))
assert pkg.startswith(os.path.realpath(sys.prefix)), (pkg, sys.prefix)
assert os.path.dirname(os.path.realpath(macrocon.library_path())) == pkg, macrocon.library_path()
assert macrocon.starter_library() == os.path.join(pkg, 'starter.mclb'), macrocon.starter_library()
assert md.metadata('macrocon')['License'] == 'Apache-2.0'
print('venv import', '.'.join(map(str, macrocon.version())), macrocon.starter_library())
]=])
file(WRITE ${WORK}/venv_probe.py "${venv_probe}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=MACROCON_LIBRARY --unset=MACROCON_STARTER_LIBRARY --unset=PYTHONPATH
  --unset=LD_PRELOAD LD_LIBRARY_PATH= ${WORK}/venv/bin/python ${WORK}/venv_probe.py
  WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "importing the pip-installed wheel from the venv failed (exit ${rc}):\n${out}\n${err}")
endif()
message(STATUS "pip install --no-index into a venv: ${out}")
