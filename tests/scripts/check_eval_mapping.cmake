# Driven by eval_mapping.tests.cmake: CLI = the macrocon executable, SHARED = the benchmark data.
include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)
run_checked(WHAT "eval-mapping" OUTPUT_VARIABLE out
  COMMAND ${CLI} eval-mapping --shared ${SHARED} --classes arm --pairs 2 --samples 300 --thesis-iterations 200
          --eval-vertices 40 --json --quiet)
string(JSON pairs GET "${out}" pairs)
if(NOT pairs EQUAL 2)
  message(FATAL_ERROR "expected 2 pairs, got ${pairs}: ${out}")
endif()
string(JSON method_count LENGTH "${out}" methods)
if(NOT method_count EQUAL 4)
  message(FATAL_ERROR "expected 4 methods: ${out}")
endif()
foreach(method macrocon rigid thesis proximity)
  foreach(scope "overall" "per_class;arm")
    string(JSON m GET "${out}" methods ${method} ${scope})
    foreach(key mean_eps100 within_0_05 flipped_triangles overlap seconds_median iterations_median)
      string(JSON v ERROR_VARIABLE missing GET "${m}" ${key})
      if(missing)
        message(FATAL_ERROR "${method} ${scope}: no ${key}: ${m}")
      endif()
    endforeach()
    string(JSON flips GET "${m}" flipped_triangles)
    string(JSON within GET "${m}" within_0_05)
    string(JSON overlap GET "${m}" overlap)
    string(JSON eps GET "${m}" mean_eps100)
    # proximity (closest points after ICP) is the users' baseline and may fold; the others may not.
    # Its overlap is 1 by construction, up to the rounding of the area sums.
    if(NOT flips EQUAL 0 AND NOT method STREQUAL "proximity")
      message(FATAL_ERROR "${method} ${scope}: ${flips} flipped triangles")
    endif()
    if(within LESS 0 OR within GREATER 1 OR NOT overlap GREATER 0 OR overlap GREATER 1.000001 OR NOT eps GREATER 0)
      message(FATAL_ERROR "${method} ${scope}: values out of range: ${m}")
    endif()
  endforeach()
  string(JSON per_count LENGTH "${out}" methods ${method} per_class)
  if(NOT per_count EQUAL 1)
    message(FATAL_ERROR "${method}: expected only the arm class: ${out}")
  endif()
endforeach()
# The target's resolution (mean edge / sqrt(area), x 100): present, positive, and well above 1
# on the coarse forearm strip (about 100 vertices in a patch of radius 1).
foreach(scope "overall" "per_class;arm")
  string(JSON edge ERROR_VARIABLE missing GET "${out}" target_edge_eps100 ${scope})
  if(missing OR NOT edge GREATER 5 OR NOT edge LESS 100)
    message(FATAL_ERROR "target_edge_eps100 ${scope}: expected a value in (5, 100): ${out}")
  endif()
endforeach()
string(JSON thesis_iterations GET "${out}" methods thesis overall iterations_median)
if(NOT thesis_iterations EQUAL 200)
  message(FATAL_ERROR "thesis ran ${thesis_iterations} iterations instead of 200")
endif()
message(STATUS "eval-mapping: ${out}")

# Bad options: a clear message and a non-zero status.
foreach(bad "--classes;elbow" "--method;newton" "--pairs;0" "--samples;-3" "--landmarks;0" "--noise;-1" "--density;0")
  run_checked(WHAT "eval-mapping ${bad}" EXPECT_FAILURE "error"
    COMMAND ${CLI} eval-mapping --shared ${SHARED} ${bad} --quiet)
endforeach()

# --flip-winding: the reversed target is repaired before anything is computed, so every number is
# the clean run's; --density 2 changes the target (and the numbers) but keeps the map flip-free.
set(options_clean "")
set(options_flip "--flip-winding")
set(options_dense "--density;2")
foreach(variant clean flip dense)
  run_checked(WHAT "eval-mapping ${options_${variant}}" OUTPUT_VARIABLE pert_out
    COMMAND ${CLI} eval-mapping --shared ${SHARED} --classes nose --pairs 1 --method macrocon --samples 300
            --eval-vertices 40 ${options_${variant}} --json --quiet)
  string(JSON eps_${variant} GET "${pert_out}" methods macrocon overall mean_eps100)
  string(JSON flips GET "${pert_out}" methods macrocon overall flipped_triangles)
  string(JSON described_${variant} GET "${pert_out}" perturbation)
  if(NOT flips EQUAL 0)
    message(FATAL_ERROR "eval-mapping ${variant}: ${flips} flipped triangles")
  endif()
endforeach()
if(NOT eps_clean STREQUAL eps_flip OR NOT described_flip STREQUAL "flip-winding")
  message(FATAL_ERROR "--flip-winding changed the map: ${eps_clean} vs ${eps_flip} (${described_flip})")
endif()
if(eps_clean STREQUAL eps_dense OR NOT described_dense STREQUAL "density 2")
  message(FATAL_ERROR "--density 2 did not change the target: ${eps_clean} vs ${eps_dense} (${described_dense})")
endif()

# --progress: the pair's log line above a bar that finishes; stdout stays the JSON alone.
run_checked(WHAT "eval-mapping --progress" OUTPUT_VARIABLE progress_out ERROR_VARIABLE progress_err
  COMMAND ${CLI} eval-mapping --shared ${SHARED} --classes nose --pairs 1 --method macrocon --samples 300
          --eval-vertices 40 --json --progress)
string(JSON progress_eps GET "${progress_out}" methods macrocon overall mean_eps100)
if(NOT progress_eps STREQUAL eps_clean OR NOT progress_err MATCHES "\rpairs \\[#+\\] 100% [0-9.]+ s\n"
   OR NOT progress_err MATCHES "pair 0")
  message(FATAL_ERROR "eval-mapping --progress: eps ${progress_eps} (clean ${eps_clean}); stderr:\n${progress_err}")
endif()

# The oracle diagnostic (ground-truth guidance channels): asked for explicitly, it must run, keep
# the map flip-free, and on the featureless forearm strip, where the descriptors leave the map
# sliding (macrocon ~7.3 mean eps x 100 on these two pairs, oracle ~4.0), land clearly closer.
run_checked(WHAT "eval-mapping --method macrocon,oracle,landmarks" OUTPUT_VARIABLE oracle_out
  COMMAND ${CLI} eval-mapping --shared ${SHARED} --classes arm --pairs 2 --method macrocon,oracle,landmarks --json --quiet)
string(JSON oracle_eps GET "${oracle_out}" methods oracle overall mean_eps100)
string(JSON plain_eps GET "${oracle_out}" methods macrocon overall mean_eps100)
string(JSON oracle_flips GET "${oracle_out}" methods oracle overall flipped_triangles)
if(NOT oracle_flips EQUAL 0 OR NOT oracle_eps LESS plain_eps OR NOT oracle_eps LESS 6)
  message(FATAL_ERROR "oracle: expected 0 flips and a lower mean eps x 100 than macrocon (and < 6): ${oracle_out}")
endif()
message(STATUS "eval-mapping oracle ${oracle_eps} vs macrocon ${plain_eps}")

# The landmarks method (guidance = distances from K true point pairs): flip-free, and K reaches it.
run_checked(WHAT "eval-mapping --method landmarks --landmarks 1" OUTPUT_VARIABLE one_out
  COMMAND ${CLI} eval-mapping --shared ${SHARED} --classes arm --pairs 2 --method landmarks --landmarks 1 --json --quiet)
string(JSON four_eps GET "${oracle_out}" methods landmarks overall mean_eps100)
string(JSON four_flips GET "${oracle_out}" methods landmarks overall flipped_triangles)
string(JSON one_eps GET "${one_out}" methods landmarks overall mean_eps100)
if(NOT four_flips EQUAL 0 OR four_eps EQUAL one_eps OR NOT four_eps GREATER 0)
  message(FATAL_ERROR "landmarks: expected 0 flips and a result that depends on --landmarks: 4 -> ${four_eps}, 1 -> ${one_eps}")
endif()
message(STATUS "eval-mapping landmarks: 4 -> ${four_eps}, 1 -> ${one_eps}")

# --cross-family (MakeHuman <-> ICT, scored on the semantic landmarks): restricted to the nose, two
# pairs (one each way), every method's summary present, the landmarks inside both patches found
# (bridge, tip, alae, subnasale at least), and the SDK's nose maps right side up and not grossly
# wrong (measured: median landmark eps x 100 about 3, 0 inverted landmark pairs).
run_checked(WHAT "eval-mapping --cross-family" OUTPUT_VARIABLE cross_out
  COMMAND ${CLI} eval-mapping --shared ${SHARED} --classes nose --pairs 1 --method macrocon,rigid,proximity
          --cross-family --json --quiet)
string(JSON cross_pairs GET "${cross_out}" cross_family pairs)
string(JSON case_count LENGTH "${cross_out}" cross_family cases)
if(NOT cross_pairs EQUAL 2 OR NOT case_count EQUAL 2)
  message(FATAL_ERROR "--cross-family: expected 2 nose pairs: ${cross_out}")
endif()
foreach(method macrocon rigid proximity)
  foreach(scope "overall" "per_class;nose")
    string(JSON m GET "${cross_out}" cross_family methods ${method} ${scope})
    foreach(key pairs mean_eps100 landmark_mean_eps100 median_eps100 gross_failures orientation_errors seconds_median)
      string(JSON v ERROR_VARIABLE missing GET "${m}" ${key})
      if(missing)
        message(FATAL_ERROR "--cross-family ${method} ${scope}: no ${key}: ${m}")
      endif()
    endforeach()
    string(JSON eps GET "${m}" mean_eps100)
    if(NOT eps GREATER 0)
      message(FATAL_ERROR "--cross-family ${method} ${scope}: mean_eps100 must be positive: ${m}")
    endif()
  endforeach()
endforeach()
foreach(k 0 1)
  string(JSON landmarks GET "${cross_out}" cross_family cases ${k} landmarks)
  if(landmarks LESS 5)
    message(FATAL_ERROR "--cross-family case ${k}: only ${landmarks} landmarks inside both noses: ${cross_out}")
  endif()
endforeach()
string(JSON gross GET "${cross_out}" cross_family methods macrocon overall gross_failures)
string(JSON wrong GET "${cross_out}" cross_family methods macrocon overall orientation_errors)
if(NOT gross EQUAL 0 OR NOT wrong EQUAL 0)
  message(FATAL_ERROR "--cross-family: the nose maps should be right: ${cross_out}")
endif()
# Each SDK map carries its candidate confidence signals, and the summary their ROC AUC (null here:
# no gross failure among two right noses).
foreach(k 0 1)
  string(JSON score GET "${cross_out}" cross_family cases ${k} methods macrocon signals matching_score)
  string(JSON overlap GET "${cross_out}" cross_family cases ${k} methods macrocon signals overlap)
  if(NOT score GREATER 0 OR score GREATER 1 OR NOT overlap GREATER 0 OR overlap GREATER 1)
    message(FATAL_ERROR "--cross-family case ${k}: signals out of [0, 1]: ${cross_out}")
  endif()
endforeach()
string(JSON auc_type TYPE "${cross_out}" cross_family methods macrocon signal_roc_auc matching_score)
if(NOT auc_type STREQUAL "NULL")
  message(FATAL_ERROR "--cross-family: an AUC without a gross failure must be null: ${cross_out}")
endif()
message(STATUS "eval-mapping --cross-family nose: ${cross_out}")

# The 3D-aligned start (macrocon-frame, and frame-rigid = that start alone) on the two forearm
# pairs (one mirrored): the start alone already lands about where the full map does (measured 7.5
# and 7.4 mean eps x 100, macrocon 7.3; a start of the wrong orientation scores about 25 on the
# forearm), and the map stays flip-free.
run_checked(WHAT "eval-mapping --method macrocon,macrocon-frame,frame-rigid" OUTPUT_VARIABLE frame_out
  COMMAND ${CLI} eval-mapping --shared ${SHARED} --classes arm --pairs 2 --method macrocon,macrocon-frame,frame-rigid
          --json --quiet)
string(JSON frame_eps GET "${frame_out}" methods macrocon-frame overall mean_eps100)
string(JSON frame_flips GET "${frame_out}" methods macrocon-frame overall flipped_triangles)
string(JSON free_eps GET "${frame_out}" methods macrocon overall mean_eps100)
string(JSON start_eps GET "${frame_out}" methods frame-rigid overall mean_eps100)
if(NOT frame_flips EQUAL 0 OR NOT frame_eps LESS 12 OR NOT start_eps LESS 12 OR NOT start_eps GREATER 0)
  message(FATAL_ERROR "macrocon-frame: expected 0 flips and mean eps x 100 below 12 for the map and its start: ${frame_out}")
endif()
message(STATUS "eval-mapping macrocon-frame ${frame_eps} vs macrocon ${free_eps} (frame start ${start_eps})")
