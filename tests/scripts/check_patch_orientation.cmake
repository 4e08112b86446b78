# Runs `macrocon patch` on outward, inward and non-orientable meshes (see patch_orientation.tests.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

set(t 1.618033988749895)
set(v "v -1 ${t} 0\nv 1 ${t} 0\nv -1 -${t} 0\nv 1 -${t} 0\nv 0 -1 ${t}\nv 0 1 ${t}\nv 0 -1 -${t}\nv 0 1 -${t}\n")
string(APPEND v "v ${t} 0 -1\nv ${t} 0 1\nv -${t} 0 -1\nv -${t} 0 1\n")
# The 20 outward faces (1-based), as a b c.
set(faces "1 12 6;1 6 2;1 2 8;1 8 11;1 11 12;2 6 10;6 12 5;12 11 3;11 8 7;8 2 9;4 10 5;4 5 3;4 3 7;4 7 9;4 9 10;5 10 6;3 5 12;7 3 11;9 7 8;10 9 2")
set(outward "${v}")
set(inward "${v}")
foreach(f ${faces})
  string(REPLACE " " ";" abc "${f}")
  list(GET abc 0 a)
  list(GET abc 1 b)
  list(GET abc 2 c)
  string(APPEND outward "f ${a} ${b} ${c}\n")
  string(APPEND inward "f ${a} ${c} ${b}\n")
endforeach()
file(WRITE ${OUT}/outward.obj "${outward}")
file(WRITE ${OUT}/inward.obj "${inward}")

run_checked(WHAT "patch of the outward icosahedron" OUTPUT_VARIABLE out_a
  COMMAND ${CLI} patch --mesh ${OUT}/outward.obj --center-vertex 0 --radius 1.5 --json)
run_checked(WHAT "patch of the inward icosahedron" OUTPUT_VARIABLE out_b
  COMMAND ${CLI} patch --mesh ${OUT}/inward.obj --center-vertex 0 --radius 1.5 --json)
string(JSON reoriented_a GET "${out_a}" orientation reoriented_triangles)
string(JSON reoriented_b GET "${out_b}" orientation reoriented_triangles)
string(JSON turned_b GET "${out_b}" orientation outward_turned_components)
string(JSON closed_b GET "${out_b}" orientation closed_components)
if(NOT reoriented_a EQUAL 0 OR NOT reoriented_b EQUAL 20 OR NOT turned_b EQUAL 1 OR NOT closed_b EQUAL 1)
  message(FATAL_ERROR "orientation report wrong: outward ${out_a}\ninward ${out_b}")
endif()
foreach(key vertices faces max_geodesic_distance radius)
  string(JSON a GET "${out_a}" ${key})
  string(JSON b GET "${out_b}" ${key})
  if(NOT a STREQUAL b)
    message(FATAL_ERROR "the inward mesh gave another patch (${key}: ${a} vs ${b})")
  endif()
endforeach()

# A Moebius strip: 8 quads around a circle, the last joined with a half twist.
file(WRITE ${OUT}/moebius.obj "v 0.700000 0.000000 -0.000000\nv 1.300000 0.000000 0.000000\nv 0.511122 0.511122 -0.114805\nv 0.903091 0.903091 0.114805\nv 0.000000 0.787868 -0.212132\nv 0.000000 1.212132 0.212132\nv -0.625927 0.625927 -0.277164\nv -0.788286 0.788286 0.277164\nv -1.000000 0.000000 -0.300000\nv -1.000000 0.000000 0.300000\nv -0.788286 -0.788286 -0.277164\nv -0.625927 -0.625927 0.277164\nv -0.000000 -1.212132 -0.212132\nv -0.000000 -0.787868 0.212132\nv 0.903091 -0.903091 -0.114805\nv 0.511122 -0.511122 0.114805\nf 1 3 4\nf 1 4 2\nf 3 5 6\nf 3 6 4\nf 5 7 8\nf 5 8 6\nf 7 9 10\nf 7 10 8\nf 9 11 12\nf 9 12 10\nf 11 13 14\nf 11 14 12\nf 13 15 16\nf 13 16 14\nf 15 2 1\nf 15 1 16\n")
run_checked(WHAT "patch of a Moebius strip" EXPECT_FAILURE "MCON_ERROR_NON_ORIENTABLE|not orientable.*cut the surface"
  COMMAND ${CLI} patch --mesh ${OUT}/moebius.obj --center-vertex 0 --radius 0.5 --json)
