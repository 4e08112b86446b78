# Runs `macrocon embed` twice (cut source, and source from a patch file) and checks the outputs.
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

function(check_run dir)
  foreach(f target.ply target.obj guides.obj source_guides.obj target.rosy summary.json)
    if(NOT EXISTS ${dir}/${f})
      message(FATAL_ERROR "${dir}: ${f} was not written")
    endif()
  endforeach()
  file(READ ${dir}/summary.json summary)
  string(JSON flips GET "${summary}" flips)
  string(JSON overlap GET "${summary}" overlap)
  string(JSON guides_out GET "${summary}" guides_out)
  string(JSON stop GET "${summary}" stop_reason)
  string(JSON nt GET "${summary}" target_vertices)
  message(STATUS "${dir}: flips ${flips}, overlap ${overlap}, guides out ${guides_out}, stop ${stop}")
  if(NOT flips EQUAL 0)
    message(FATAL_ERROR "${dir}: the map has ${flips} flipped triangles")
  endif()
  if(overlap LESS 0.5 OR guides_out LESS 1)
    message(FATAL_ERROR "${dir}: overlap ${overlap} / ${guides_out} guides out: the map did not land")
  endif()
  # The .rosy has one direction per target triangle; the OBJ has `l` lines.
  file(STRINGS ${dir}/target.rosy rosy LIMIT_COUNT 2)
  list(GET rosy 1 symmetry)
  if(NOT symmetry EQUAL 4)
    message(FATAL_ERROR "${dir}: target.rosy is not a 4-RoSy file")
  endif()
  file(STRINGS ${dir}/guides.obj lines REGEX "^l ")
  list(LENGTH lines nl)
  if(NOT nl EQUAL guides_out)
    message(FATAL_ERROR "${dir}: guides.obj has ${nl} lines, the summary says ${guides_out}")
  endif()
  file(READ ${dir}/target.ply header LIMIT 2000)
  foreach(attr source_uv_x source_mean_curvature source_ring outside)
    if(NOT header MATCHES "property float ${attr}")
      message(FATAL_ERROR "${dir}: target.ply lacks the attribute ${attr}")
    endif()
  endforeach()
endfunction()

run_checked(WHAT "macrocon embed" OUTPUT_VARIABLE out ERROR_VARIABLE err
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --source-radius 0.45 --samples 500 --seed 1 --out ${OUT}/cut --json)
# stderr is a pipe here: no progress bar (no carriage return) unless --progress asks for one.
string(FIND "${err}" "\r" cr)
if(NOT cr EQUAL -1)
  message(FATAL_ERROR "macrocon embed drew a progress bar into a pipe:\n${err}")
endif()
string(JSON stdout_flips GET "${out}" flips)
if(NOT stdout_flips EQUAL 0)
  message(FATAL_ERROR "--json printed flips ${stdout_flips}")
endif()
check_run(${OUT}/cut)
# The orientation evidence: both rigid scores (>= 0: both orientations are tried by default), the
# comparison flag and the level-0 energies (-1 unless compared).
string(JSON auto_reflected GET "${out}" reflected)
string(JSON auto_unreflected_score GET "${out}" alignment_score_unreflected)
string(JSON auto_reflected_score GET "${out}" alignment_score_reflected)
string(JSON auto_compared GET "${out}" orientation_compared)
string(JSON auto_e0 GET "${out}" level0_energy_unreflected)
string(JSON auto_e1 GET "${out}" level0_energy_reflected)
string(JSON auto_mode GET "${out}" orientation)
message(STATUS "auto: reflected ${auto_reflected}, rigid ${auto_unreflected_score} / ${auto_reflected_score}, "
               "compared ${auto_compared}, level 0 ${auto_e0} / ${auto_e1}")
if(NOT auto_mode STREQUAL "auto" OR auto_unreflected_score LESS 0 OR auto_reflected_score LESS 0)
  message(FATAL_ERROR "automatic run: orientation '${auto_mode}', rigid scores ${auto_unreflected_score} / ${auto_reflected_score}")
endif()
if(auto_compared AND (auto_e0 LESS_EQUAL 0 OR auto_e1 LESS_EQUAL 0))
  message(FATAL_ERROR "compared, but the level-0 energies are ${auto_e0} / ${auto_e1}")
endif()
if(NOT auto_compared AND (NOT auto_e0 EQUAL -1 OR NOT auto_e1 EQUAL -1))
  message(FATAL_ERROR "not compared, but the level-0 energies are ${auto_e0} / ${auto_e1}")
endif()

# The flip: the orientation opposite to the automatic call, forced; no comparison, no flips.
if(auto_reflected)
  set(flip preserve)
else()
  set(flip reverse)
endif()
run_checked(WHAT "macrocon embed --orientation ${flip}" OUTPUT_VARIABLE out ERROR_VARIABLE err
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --source-radius 0.45 --samples 500 --seed 1 --orientation ${flip}
          --out ${OUT}/flip --json --progress)
# --progress draws the map's bar on stderr even into a pipe, redrawn in place up to 100 %, and
# leaves stdout (the JSON) alone.
if(NOT err MATCHES "\rmap \\[#+\\] 100% [0-9.]+ s\n")
  message(FATAL_ERROR "macrocon embed --progress drew no finished bar on stderr:\n${err}")
endif()
if(out MATCHES "\r")
  message(FATAL_ERROR "macrocon embed --progress wrote the bar to stdout")
endif()
string(JSON flip_reflected GET "${out}" reflected)
string(JSON flip_compared GET "${out}" orientation_compared)
string(JSON flip_flips GET "${out}" flips)
string(JSON flip_mode GET "${out}" orientation)
string(JSON flip_unreflected_score GET "${out}" alignment_score_unreflected)
if((flip_reflected AND auto_reflected) OR (NOT flip_reflected AND NOT auto_reflected) OR flip_compared
   OR NOT flip_flips EQUAL 0 OR NOT flip_mode STREQUAL flip)
  message(FATAL_ERROR "--orientation ${flip}: reflected ${flip_reflected} (auto ${auto_reflected}), compared "
                      "${flip_compared}, flips ${flip_flips}, orientation '${flip_mode}'")
endif()
if(NOT flip_unreflected_score STREQUAL auto_unreflected_score)
  message(FATAL_ERROR "the same seed scored the rigid candidates differently: ${flip_unreflected_score} vs ${auto_unreflected_score}")
endif()
run_checked(WHAT "a bad --orientation" EXPECT_FAILURE "--orientation must be auto, preserve or reverse"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.5
          --orientation sideways --out ${OUT}/bad)

run_checked(WHAT "macrocon patch"
  COMMAND ${CLI} patch --mesh ${MESH} --center-vertex 297 --radius 0.45 --out ${OUT}/nose.ply)
run_checked(WHAT "macrocon embed with a patch file" ERROR_VARIABLE err
  COMMAND ${CLI} embed --source ${OUT}/nose.ply --target ${MESH} --center-vertex 297 --radius 0.55 --samples 500
          --out ${OUT}/entry --progress --quiet)
string(FIND "${err}" "\r" cr)
if(NOT cr EQUAL -1)
  message(FATAL_ERROR "macrocon embed --progress --quiet drew a progress bar (--quiet must win):\n${err}")
endif()
check_run(${OUT}/entry)

# Bad input fails with a message, not a crash.
# Every command checks a vertex or face number in one place, and the message gives the valid range.
run_checked(WHAT "a bad --center-vertex" EXPECT_FAILURE "--center-vertex 99999999 is not a vertex of the surface: the file has vertices 0\\.\\.[0-9]+ \\(numbers count from 0\\)"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 99999999 --radius 0.5
          --out ${OUT}/bad)
run_checked(WHAT "a bad --source-center-vertex" EXPECT_FAILURE "--source-center-vertex -3 is not a vertex of the surface: the file has vertices 0\\.\\."
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.5
          --source-center-vertex -3 --out ${OUT}/bad)
run_checked(WHAT "patch: a bad --center-vertex" EXPECT_FAILURE "--center-vertex 99999999 is not a vertex of the surface: the file has vertices 0\\.\\."
  COMMAND ${CLI} patch --mesh ${MESH} --center-vertex 99999999 --radius 0.5 --out ${OUT}/bad.ply)
file(WRITE ${OUT}/lonely.obj "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 5 5 5\nf 1 2 3\nf 2 4 3\n")
run_checked(WHAT "patch: an unreferenced --center-vertex" EXPECT_FAILURE "--center-vertex 4 is not a vertex of the surface: no kept face uses it"
  COMMAND ${CLI} patch --mesh ${OUT}/lonely.obj --center-vertex 4 --radius 0.5 --out ${OUT}/bad.ply)
run_checked(WHAT "patch: a bad --center-triangle" EXPECT_FAILURE "--center-triangle 99999999 is not a face of the surface: the kept faces are numbered 0\\.\\.[0-9]+"
  COMMAND ${CLI} patch --mesh ${MESH} --center-triangle 99999999 --radius 0.5 --out ${OUT}/bad.ply)

# Landmarks: two clicked pairs on the nose (MakeHuman is exactly mirror-symmetric: 6974 <-> 198 and
# 7120 <-> 359 are mirror images, at different angles around the tip 297). Pairing each with
# itself keeps the map plain; pairing each with its mirror image must make it reflected, which
# no rotation about the tip can satisfy.
foreach(case "plain;6974:6974,7120:7120;OFF" "mirror;6974:198,7120:359;ON")  # string(JSON) gives booleans as ON/OFF
  list(GET case 0 name)
  list(GET case 1 pairs)
  list(GET case 2 want)
  run_checked(WHAT "macrocon embed --landmarks ${pairs}" OUTPUT_VARIABLE lm_out
    COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
            --source-center-vertex 297 --source-radius 0.45 --samples 500 --seed 1 --landmarks ${pairs}
            --out ${OUT}/landmarks_${name} --json)
  string(JSON lm_reflected GET "${lm_out}" reflected)
  string(JSON lm_count GET "${lm_out}" landmarks)
  string(JSON lm_flips GET "${lm_out}" flips)
  if(NOT lm_reflected STREQUAL want OR NOT lm_count EQUAL 2 OR NOT lm_flips EQUAL 0)
    message(FATAL_ERROR "--landmarks ${pairs}: reflected ${lm_reflected} (want ${want}), landmarks ${lm_count}, "
                        "flips ${lm_flips}")
  endif()
endforeach()
run_checked(WHAT "a landmark outside the target patch" EXPECT_FAILURE "target vertex 5 is not a vertex of the target patch"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --landmarks 6974:5 --out ${OUT}/bad)
run_checked(WHAT "a malformed --landmarks" EXPECT_FAILURE "expects S:T pairs"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --landmarks 6974-5 --out ${OUT}/bad)
run_checked(WHAT "a whole mesh as --source without --source-center-vertex"
  EXPECT_FAILURE "is not a disk patch .*give --source-center-vertex M"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55 --out ${OUT}/bad)
# Every command that takes a vertex or face number says that numbers count from 0.
foreach(command embed patch query library)
  run_checked(OUTPUT_VARIABLE help COMMAND ${CLI} ${command} --help)
  if(NOT help MATCHES "numbers count from 0: vertex 0 is the file's first vertex")
    message(FATAL_ERROR "macrocon ${command} --help does not say that numbers count from 0:\n${help}")
  endif()
endforeach()

# Arguments (CLI11): `help CMD [SUB]` equals `CMD [SUB] --help` and ends with the generated option
# list; the command list goes to stdout on --help / help; --opt=value is --opt value; an option twice,
# a value that is missing (the next word is an option) or an unknown option is refused by name.
run_checked(OUTPUT_VARIABLE help_patch COMMAND ${CLI} help patch)
run_checked(OUTPUT_VARIABLE dash_help_patch COMMAND ${CLI} patch --mesh x.obj --help)
if(NOT help_patch STREQUAL dash_help_patch
   OR NOT help_patch MATCHES "Options:\n(.*\n)*  --radius R +geodesic radius in mesh units\n"
   OR NOT help_patch MATCHES "  --no-fill")
  message(FATAL_ERROR "macrocon help patch lacks the generated option list, or differs from patch --help:\n${help_patch}")
endif()
run_checked(OUTPUT_VARIABLE help_build COMMAND ${CLI} help library build)
if(NOT help_build MATCHES "  --max-snap-distance " OR NOT help_build MATCHES "  --center-vertex N")
  message(FATAL_ERROR "macrocon help library build lacks its entry options:\n${help_build}")
endif()
foreach(form "--help" "help")
  run_checked(OUTPUT_VARIABLE top_help COMMAND ${CLI} ${form})
  if(NOT top_help MATCHES "  embed +re-embed" OR NOT top_help MATCHES "  help +")
    message(FATAL_ERROR "macrocon ${form} does not list the commands on stdout:\n${top_help}")
  endif()
endforeach()
run_checked(WHAT "--opt=value" OUTPUT_VARIABLE eq_out
  COMMAND ${CLI} patch --mesh=${MESH} --center-vertex=297 --radius=0.3 --json)
string(JSON eq_vertices GET "${eq_out}" vertices)
run_checked(OUTPUT_VARIABLE space_out COMMAND ${CLI} patch --mesh ${MESH} --center-vertex 297 --radius 0.3 --json)
string(JSON space_vertices GET "${space_out}" vertices)
if(NOT eq_vertices EQUAL space_vertices OR eq_vertices LESS 10)
  message(FATAL_ERROR "--opt=value gave ${eq_vertices} vertices, --opt value ${space_vertices}")
endif()
run_checked(WHAT "an option twice" EXPECT_FAILURE "option '--radius' given twice"
  COMMAND ${CLI} patch --mesh ${MESH} --center-vertex 297 --radius 0.3 --radius 0.4)
run_checked(WHAT "a missing value" EXPECT_FAILURE "option '--center-vertex' needs a value"
  COMMAND ${CLI} patch --mesh ${MESH} --center-vertex --radius 0.3)
run_checked(WHAT "an unknown option" EXPECT_FAILURE "unknown option '--radious' \\(--help lists the options\\)"
  COMMAND ${CLI} patch --mesh ${MESH} --center-vertex 297 --radious 0.3)
run_checked(WHAT "a stray word" EXPECT_FAILURE "not expected: stray"
  COMMAND ${CLI} patch --mesh ${MESH} stray --center-vertex 297 --radius 0.3)
run_checked(WHAT "a stray word after a negative value" EXPECT_FAILURE "not expected: stray"
  COMMAND ${CLI} patch --mesh ${MESH} --center-vertex 297 --radius 0.3 --snap -0.1 stray)

# Up hints: both meshes +y up (the file's axes); the summary says so and the map stays flip-free.
# A zero vector, a malformed one and a lone --source-up are refused by name.
run_checked(WHAT "macrocon embed --up" OUTPUT_VARIABLE up_out
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --source-radius 0.45 --samples 500 --seed 1 --up 0,1,0 --out ${OUT}/up --json)
string(JSON up_hints GET "${up_out}" up_hints)
string(JSON up_flips GET "${up_out}" flips)
if(NOT up_hints OR NOT up_flips EQUAL 0)
  message(FATAL_ERROR "--up: up_hints ${up_hints}, flips ${up_flips}")
endif()
run_checked(WHAT "a zero --up" EXPECT_FAILURE "source_up: the up vector must not be zero"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --up 0,0,0 --out ${OUT}/bad)
run_checked(WHAT "a malformed --up" EXPECT_FAILURE "--up expects X,Y,Z"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --up 0,1 --out ${OUT}/bad)
run_checked(WHAT "--source-up alone" EXPECT_FAILURE "--source-up and --target-up go together"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --source-up 0,1,0 --out ${OUT}/bad)

# --cut-guides: the cut patch for QuadWild. Its OBJ, .rosy and .sharp agree with each other and
# with the summary: one direction per cut triangle, one feature line per guide edge, and every
# guide of target_cut_guides.obj is a chain of edges of target_cut.obj.
run_checked(WHAT "macrocon embed --cut-guides" OUTPUT_VARIABLE cut_out
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --source-radius 0.45 --samples 500 --seed 1 --cut-guides --out ${OUT}/cut_guides --json)
check_run(${OUT}/cut_guides)
foreach(f target_cut.obj target_cut.ply target_cut.sharp target_cut.rosy target_cut_guides.obj)
  if(NOT EXISTS ${OUT}/cut_guides/${f})
    message(FATAL_ERROR "--cut-guides: ${f} was not written")
  endif()
endforeach()
string(JSON cut_triangles GET "${cut_out}" cut triangles)
string(JSON cut_edges GET "${cut_out}" cut guide_edges)
string(JSON cut_angle GET "${cut_out}" cut min_angle_created_degrees)
string(JSON traced_ratio GET "${cut_out}" guide_turning traced_ratio)
string(JSON qw_command GET "${cut_out}" quadwild_commands 0)
if(NOT qw_command MATCHES "^quadwild target_cut.obj 2 target_cut.rosy target_cut.sharp ")
  message(FATAL_ERROR "--cut-guides: the summary's QuadWild command is '${qw_command}'")
endif()
message(STATUS "--cut-guides: ${cut_triangles} triangles, ${cut_edges} guide edges, smallest angle made ${cut_angle}, "
               "turning ratio (traced / source) ${traced_ratio}")
file(STRINGS ${OUT}/cut_guides/target_cut.sharp sharp)
list(GET sharp 0 sharp_count)
file(STRINGS ${OUT}/cut_guides/target_cut.rosy rosy LIMIT_COUNT 1)
file(STRINGS ${OUT}/cut_guides/target_cut.obj faces REGEX "^f ")
list(LENGTH faces nf)
if(NOT sharp_count EQUAL cut_edges OR NOT rosy EQUAL cut_triangles OR NOT nf EQUAL cut_triangles OR cut_edges LESS 10)
  message(FATAL_ERROR "--cut-guides: .sharp ${sharp_count} edges (summary ${cut_edges}), .rosy ${rosy} and OBJ ${nf} "
                      "faces (summary ${cut_triangles} triangles)")
endif()
if(cut_angle LESS_EQUAL 1)
  message(FATAL_ERROR "--cut-guides made a sliver: smallest angle ${cut_angle} degrees")
endif()
# Every guide edge is a mesh edge.
set(mesh_edges "")
foreach(face IN LISTS faces)
  string(REGEX MATCHALL "[0-9]+" ids "${face}")
  list(GET ids 0 a)
  list(GET ids 1 b)
  list(GET ids 2 c)
  foreach(pair "${a};${b}" "${b};${c}" "${c};${a}")
    list(GET pair 0 p)
    list(GET pair 1 q)
    if(p LESS q)
      list(APPEND mesh_edges "${p}-${q}")
    else()
      list(APPEND mesh_edges "${q}-${p}")
    endif()
  endforeach()
endforeach()
file(STRINGS ${OUT}/cut_guides/target_cut_guides.obj chains REGEX "^l ")
set(checked 0)
foreach(chain IN LISTS chains)
  string(REGEX MATCHALL "[0-9]+" ids "${chain}")
  list(LENGTH ids n)
  math(EXPR last "${n} - 2")
  foreach(i RANGE 0 ${last})
    math(EXPR j "${i} + 1")
    list(GET ids ${i} p)
    list(GET ids ${j} q)
    if(p LESS q)
      set(e "${p}-${q}")
    else()
      set(e "${q}-${p}")
    endif()
    list(FIND mesh_edges "${e}" found)
    if(found LESS 0)
      message(FATAL_ERROR "--cut-guides: guide step ${e} is not an edge of target_cut.obj")
    endif()
    math(EXPR checked "${checked} + 1")
  endforeach()
endforeach()
if(checked LESS 10)
  message(FATAL_ERROR "--cut-guides: only ${checked} guide steps in target_cut_guides.obj")
endif()
run_checked(WHAT "--snap without --cut-guides" EXPECT_FAILURE "--snap needs --cut-guides"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --snap 0.2 --out ${OUT}/bad)
run_checked(WHAT "--fair-passes without --cut-guides" EXPECT_FAILURE "--fair-passes needs --cut-guides"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --fair-passes 2 --out ${OUT}/bad)
run_checked(WHAT "--fair-passes out of range" EXPECT_FAILURE "--fair-passes must be 0"
  COMMAND ${CLI} embed --source ${MESH} --target ${MESH} --center-vertex 297 --radius 0.55
          --source-center-vertex 297 --cut-guides --fair-passes -1 --out ${OUT}/bad)
