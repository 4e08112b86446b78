# Runs `macrocon demo --out OUT` and requires exit status 0 and every result file, non-empty.
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${OUT})
run_checked(WHAT "macrocon demo" OUTPUT_VARIABLE out ERROR_VARIABLE err COMMAND ${CLI} demo --out ${OUT})
message(STATUS "${out}${err}")
foreach(region eye_l mouth nose hand_r)
  foreach(file ${region}.ply ${region}.obj ${region}.rosy ${region}_guides.obj)
    if(NOT EXISTS ${OUT}/${file})
      message(FATAL_ERROR "macrocon demo did not write ${file}")
    endif()
    file(SIZE ${OUT}/${file} size)
    if(size EQUAL 0)
      message(FATAL_ERROR "macrocon demo wrote an empty ${file}")
    endif()
  endforeach()
  # The guides file holds at least one transferred polyline.
  file(STRINGS ${OUT}/${region}_guides.obj lines REGEX "^l ")
  list(LENGTH lines n)
  if(n EQUAL 0)
    message(FATAL_ERROR "no polyline was transferred onto ${region}")
  endif()
endforeach()

# QuadWild's files at <base>: every extension written, one .rosy direction per OBJ face, more than
# <min_faces> faces and at least <min_sharp> feature edges; the face count goes to <faces_var>.
function(check_quadwild_files base extensions min_faces min_sharp faces_var)
  get_filename_component(name ${base} NAME)
  foreach(ext ${extensions})
    if(NOT EXISTS ${base}.${ext})
      message(FATAL_ERROR "macrocon demo did not write ${name}.${ext}")
    endif()
  endforeach()
  file(STRINGS ${base}.obj faces REGEX "^f ")
  list(LENGTH faces nf)
  file(STRINGS ${base}.rosy rosy LIMIT_COUNT 1)
  file(STRINGS ${base}.sharp sharp LIMIT_COUNT 1)
  if(NOT rosy EQUAL nf OR nf LESS_EQUAL min_faces OR sharp LESS min_sharp)
    message(FATAL_ERROR "${name}: ${nf} OBJ faces (more than ${min_faces} expected), .rosy for ${rosy}, "
                        "${sharp} feature edges (at least ${min_sharp} expected)")
  endif()
  set(${faces_var} ${nf} PARENT_SCOPE)
endfunction()

# --cut-guides: QuadWild's three files per region, agreeing with each other (one direction per
# OBJ face, a non-empty .sharp of guide edges).
run_checked(WHAT "macrocon demo --cut-guides" OUTPUT_VARIABLE out COMMAND ${CLI} demo --out ${OUT}/cut --cut-guides)
message(STATUS "${out}")
foreach(region eye_l mouth nose hand_r)
  check_quadwild_files(${OUT}/cut/${region}_cut "obj;rosy;sharp" 0 10 faces)
endforeach()

# --snap reaches the cut (a smaller snap leaves more crossings off the vertices: more triangles);
# out of [0, 0.45], or without a cut, it is refused.
run_checked(WHAT "macrocon demo --cut-guides --snap 0.1" COMMAND ${CLI} demo --out ${OUT}/snap --cut-guides --snap 0.1)
file(STRINGS ${OUT}/cut/eye_l_cut.obj default_faces REGEX "^f ")
file(STRINGS ${OUT}/snap/eye_l_cut.obj snap_faces REGEX "^f ")
list(LENGTH default_faces n_default)
list(LENGTH snap_faces n_snap)
if(NOT n_snap GREATER n_default)
  message(FATAL_ERROR "--snap 0.1 did not change the cut: eye_l_cut has ${n_snap} faces, ${n_default} at the default")
endif()
run_checked(EXPECT_FAILURE "--snap must be in \\[0, 0.45\\]" COMMAND ${CLI} demo --out ${OUT}/snap --cut-guides --snap 0.5)
run_checked(EXPECT_FAILURE "--snap needs --cut-guides or --whole-host" COMMAND ${CLI} demo --out ${OUT}/snap --snap 0.1)
# --fair-passes reaches the cut: with 0 the chains keep the cut's positions (same faces, other
# vertex positions); out of [0, 100], or without a cut, it is refused.
run_checked(WHAT "macrocon demo --cut-guides --fair-passes 0" COMMAND ${CLI} demo --out ${OUT}/unfaired --cut-guides --fair-passes 0)
file(STRINGS ${OUT}/cut/nose_cut.obj faired_faces REGEX "^f ")
file(STRINGS ${OUT}/unfaired/nose_cut.obj unfaired_faces REGEX "^f ")
if(NOT faired_faces STREQUAL unfaired_faces)
  message(FATAL_ERROR "--fair-passes 0 changed the triangles of nose_cut.obj (fairing only moves vertices)")
endif()
file(READ ${OUT}/cut/nose_cut.obj faired_text)
file(READ ${OUT}/unfaired/nose_cut.obj unfaired_text)
if(faired_text STREQUAL unfaired_text)
  message(FATAL_ERROR "--fair-passes 0 did not change nose_cut.obj: fairing moved no vertex by default")
endif()
run_checked(EXPECT_FAILURE "--fair-passes must be 0" COMMAND ${CLI} demo --out ${OUT}/snap --cut-guides --fair-passes 101)
run_checked(EXPECT_FAILURE "--fair-passes needs --cut-guides or --whole-host" COMMAND ${CLI} demo --out ${OUT}/snap --fair-passes 2)

# --whole-host: every region's guides (and the other eye's) in one mesh of the whole body: more
# faces than the body's 26,756 triangles, one direction per face, the five regions' guide edges.
run_checked(WHAT "macrocon demo --whole-host" OUTPUT_VARIABLE out COMMAND ${CLI} demo --out ${OUT}/whole --whole-host)
message(STATUS "${out}")
check_quadwild_files(${OUT}/whole/body_whole "obj;rosy;sharp;quadwild.json" 26756 500 faces)
if(NOT out MATCHES "whole body: 5 regions' guides cut in")
  message(FATAL_ERROR "demo --whole-host did not combine the five regions:\n${out}")
endif()
