# Driven by library_cli.tests.cmake: CLI, MESH (the MakeHuman sample body), WORK (scratch folder).
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(LIB ${WORK}/body.mclb)
set(RANGE 0:13378)  # the body group of the sample OBJ
# name|class|center|radius; one side only (the base mesh is mirror-symmetric).
set(entries "eye_l|eye|8021|0.6" "nose|nose|297|0.5" "mouth|mouth|537|0.65" "ear_l|ear|12222|0.5" "hand_l|hand|9865|1.3")

# Sets name, class, center, radius from "name|class|center|radius".
macro(split_entry entry)
  string(REPLACE "|" ";" fields "${entry}")
  list(GET fields 0 name)
  list(GET fields 1 class)
  list(GET fields 2 center)
  list(GET fields 3 radius)
endmacro()

# 1. build from command-line entries.
set(args library build --out ${LIB} --mesh ${MESH} --face-range ${RANGE} --vocabulary 32 --seed 3 --json)
foreach(e IN LISTS entries)
  split_entry("${e}")
  list(APPEND args --center-vertex ${center} --radius ${radius} --class ${class} --name ${name})
endforeach()
run_checked(OUTPUT_VARIABLE out ERROR_VARIABLE err COMMAND ${CLI} ${args} --progress)
message(STATUS "build: ${out}")
# --progress: both bars (patches over the entries, then retrieval) finish on stderr.
foreach(bar patches retrieval)
  if(NOT err MATCHES "\r${bar} \\[#+\\] 100% [0-9.]+ s\n")
    message(FATAL_ERROR "library build --progress drew no finished '${bar}' bar on stderr:\n${err}")
  endif()
endforeach()
string(JSON n GET "${out}" entries)
string(JSON rings GET "${out}" rings)
string(JSON k GET "${out}" vocabulary_size)
if(NOT n EQUAL 5 OR NOT rings EQUAL 1 OR k LESS 2 OR k GREATER 32)
  message(FATAL_ERROR "build reported ${n} entries, ${rings} rings, k = ${k}")
endif()

# 2. each entry's own region finds it first, at distance 0.
foreach(e IN LISTS entries)
  split_entry("${e}")
  run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} query
    --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex ${center} --radius ${radius} --top 3 --json)
  string(JSON hits LENGTH "${out}" hits)
  string(JSON first GET "${out}" hits 0 name)
  string(JSON d0 GET "${out}" hits 0 distance)
  string(JSON d1 GET "${out}" hits 1 distance)
  if(NOT hits EQUAL 3 OR NOT first STREQUAL name OR NOT d0 EQUAL 0 OR NOT d1 GREATER 0)
    message(FATAL_ERROR "query of ${name}: expected ${name} first at distance 0, got ${out}")
  endif()
  message(STATUS "query ${name}: first ${first}, next at ${d1}")
endforeach()

# --progress: the query's stage bar finishes on stderr; stdout keeps only the JSON.
run_checked(OUTPUT_VARIABLE out ERROR_VARIABLE err COMMAND ${CLI} query
  --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex 297 --radius 0.5 --json --progress)
if(NOT err MATCHES "\rquery \\[#+\\] 100% [0-9.]+ s\n" OR out MATCHES "\r")
  message(FATAL_ERROR "query --progress drew no finished bar on stderr (or wrote it to stdout):\n${err}")
endif()

# 3. info --json describes the library and every entry.
run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} library info --library ${LIB} --json)
string(JSON n GET "${out}" entries)
string(JSON listed LENGTH "${out}" entry_list)
string(JSON d GET "${out}" descriptor)
string(JSON name2 GET "${out}" entry_list 2 name)
string(JSON class2 GET "${out}" entry_list 2 class)
string(JSON verts2 GET "${out}" entry_list 2 vertices)
if(NOT n EQUAL 5 OR NOT listed EQUAL 5 OR NOT d STREQUAL "curv9" OR NOT name2 STREQUAL "mouth" OR
   NOT class2 STREQUAL "mouth" OR verts2 LESS 100)
  message(FATAL_ERROR "info --json: ${out}")
endif()

# 4. add an entry with the existing vocabulary: found at once; the file stays valid.
run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} library add
  --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex 131 --radius 1.05
  --class face --name face --author "Test Vendor" --licence CC0 --tag front --json)
string(JSON has GET "${out}" has_histogram)
string(JSON n GET "${out}" entries)
if(NOT has OR NOT n EQUAL 6)
  message(FATAL_ERROR "library add: ${out}")
endif()
run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} query
  --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex 131 --radius 1.05 --top 1 --json)
string(JSON first GET "${out}" hits 0 name)
if(NOT first STREQUAL "face")
  message(FATAL_ERROR "query of the added entry: ${out}")
endif()

# 5. the same library from a spec file gives the same bytes as from the command line.
set(spec "{\"mesh\": \"${MESH}\", \"face_range\": \"${RANGE}\", \"entries\": [")
set(sep "")
foreach(e IN LISTS entries)
  split_entry("${e}")
  string(APPEND spec "${sep}{\"center_vertex\": ${center}, \"radius\": ${radius}, \"class\": \"${class}\", \"name\": \"${name}\"}")
  set(sep ", ")
endforeach()
string(APPEND spec "]}")
file(WRITE ${WORK}/spec.json "${spec}")
run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} library build
  --out ${WORK}/from_spec.mclb --spec ${WORK}/spec.json --vocabulary 32 --seed 3)
list(REMOVE_AT args 0 1 2 3)  # "library build --out LIB"
run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} library build --out ${WORK}/again.mclb ${args})
file(SHA256 ${WORK}/from_spec.mclb h1)
file(SHA256 ${WORK}/again.mclb h2)
if(NOT h1 STREQUAL h2)
  message(FATAL_ERROR "a spec file and the same command-line entries gave different libraries")
endif()

# 6. names with control characters are printed escaped by info and query (never raw: an ESC
# sequence in an entry name must not drive the terminal); --json gives them back exactly.
string(ASCII 27 esc)
set(evil "evil${esc}[2J\nname")
file(COPY_FILE ${LIB} ${WORK}/evil.mclb)
run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} library add
  --library ${WORK}/evil.mclb --mesh ${MESH} --face-range ${RANGE} --center-vertex 297 --radius 0.5
  --class "nose\tclass" --name "${evil}")
set(escaped "evil\\x1b[2J\\nname")
run_checked(OUTPUT_VARIABLE info COMMAND ${CLI} library info --library ${WORK}/evil.mclb)
run_checked(OUTPUT_VARIABLE hits COMMAND ${CLI} query
  --library ${WORK}/evil.mclb --mesh ${MESH} --face-range ${RANGE} --center-vertex 297 --radius 0.5 --top 2)
foreach(shown IN ITEMS info hits)
  string(FIND "${${shown}}" "${esc}" raw)
  string(FIND "${${shown}}" "${escaped}" found)
  string(FIND "${${shown}}" "nose\\tclass" class_found)
  if(NOT raw EQUAL -1 OR found EQUAL -1 OR class_found EQUAL -1)
    message(FATAL_ERROR "${shown}: the entry name is not printed escaped as '${escaped}':\n${${shown}}")
  endif()
endforeach()
run_checked(OUTPUT_VARIABLE out COMMAND ${CLI} library info --library ${WORK}/evil.mclb --json)
string(JSON last GET "${out}" entry_list 6 name)
if(NOT last STREQUAL evil)
  message(FATAL_ERROR "info --json does not give the name back exactly: ${out}")
endif()

# 7. errors: non-zero exit and a message on stderr.
run_checked(EXPECT_FAILURE "INVALID_LIBRARY" COMMAND ${CLI} library info --library ${MESH})
run_checked(EXPECT_FAILURE "MCON_ERROR_IO" COMMAND ${CLI} query
  --library ${WORK}/missing.mclb --mesh ${MESH} --center-vertex 1 --radius 0.5)
run_checked(EXPECT_FAILURE "unknown option" COMMAND ${CLI} library build --out ${WORK}/x.mclb --bogus 1)
run_checked(EXPECT_FAILURE "needs --class" COMMAND ${CLI} library build
  --out ${WORK}/x.mclb --mesh ${MESH} --face-range ${RANGE} --center-vertex 297 --radius 0.5)
run_checked(EXPECT_FAILURE "not a vertex" COMMAND ${CLI} query
  --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex 99999999 --radius 0.5)
# Out-of-range integers are errors, not clamped to LONG_MAX (which made a huge --top valid).
run_checked(EXPECT_FAILURE "--center-vertex is out of range" COMMAND ${CLI} query
  --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex 99999999999999999999999 --radius 0.5)
run_checked(EXPECT_FAILURE "--top is out of range" COMMAND ${CLI} query
  --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex 297 --radius 0.5 --top 18446744073709551617)
run_checked(EXPECT_FAILURE "--radius is out of range" COMMAND ${CLI} query
  --library ${LIB} --mesh ${MESH} --face-range ${RANGE} --center-vertex 297 --radius 1e999)
# Entries are cut in parallel; a failing one is named (index, name, center, radius) in the error.
run_checked(EXPECT_FAILURE "entry 1 'bad' \\(center vertex 99999999, radius 0.5\\): --center-vertex 99999999 is not a vertex"
  COMMAND ${CLI} library build --out ${WORK}/x.mclb --mesh ${MESH} --face-range ${RANGE}
  --center-vertex 297 --radius 0.5 --class nose --center-vertex 99999999 --radius 0.5 --class eye --name bad
  --center-vertex 537 --radius 0.65 --class mouth)
if(EXISTS ${WORK}/x.mclb)
  message(FATAL_ERROR "a failed build left a file behind")
endif()
file(REMOVE_RECURSE ${WORK})
