#!/bin/bash
# Quad-meshes the demo's cut regions and the whole body with QuadWild and checks that the quads
# follow the guides (tools/dev/quad_guide_metrics.py; docs/design.md §15):
#   quadwild_check.sh MACROCON QUADWILD_DIR OUT_DIR [metrics options...]
# MACROCON is the macrocon CLI; QUADWILD_DIR holds build/Build/bin/{quadwild,quad_from_patches}
# and src/config (the OUT_DIR of the QuadWild build recipe in README "Quad meshing with QuadWild").
# MACROCON_DEMO_ARGS adds options to `macrocon demo` (e.g. "--snap 0.1").
# Writes OUT_DIR/<region>.metrics.json and OUT_DIR/quadwild_check.json (all regions, seconds).
set -euo pipefail
macrocon=$(realpath "$1"); qw=$(realpath "$2"); out=$3; shift 3
here=$(cd "$(dirname "$0")" && pwd)
bin=$qw/build/Build/bin; cfg=$qw/src/config
for f in "$bin/quadwild" "$bin/quad_from_patches" "$cfg/prep_config/basic_setup.txt" "$cfg/main_config/flow_noalign_lemon.txt"; do
  [ -e "$f" ] || { echo "quadwild_check: $f is missing (give the QuadWild build folder)" >&2; exit 2; }
done
rm -rf "$out"; mkdir -p "$out"; out=$(realpath "$out")
"$macrocon" demo --out "$out" --cut-guides --whole-host ${MACROCON_DEMO_ARGS:-} > "$out/demo.log"
status=0; summary="{"
for name in eye_l_cut eye_r_cut mouth_cut nose_cut hand_r_cut body_whole; do
  start=$(date +%s%N)
  (cd "$out" && "$bin/quadwild" "$out/$name.obj" 2 "$out/$name.rosy" "$out/$name.sharp" "$cfg/prep_config/basic_setup.txt") \
    > "$out/$name.quadwild.log" 2>&1
  (cd "$qw/src" && "$bin/quad_from_patches" "$out/${name}_rem_p0.obj" 123 "$cfg/main_config/flow_noalign_lemon.txt") \
    >> "$out/$name.quadwild.log" 2>&1
  ms=$(( ($(date +%s%N) - start) / 1000000 )); seconds=$(printf "%d.%03d" $((ms / 1000)) $((ms % 1000)))
  rc=0
  /usr/bin/python3 "$here/quad_guide_metrics.py" "$out/$name.obj" "$out/$name.sharp" \
    "$out/${name}_rem_p0_123_quadrangulation_smooth.obj" --json "$out/$name.metrics.json" "$@" > /dev/null || rc=$?
  [ $rc -eq 0 ] || status=1
  /usr/bin/python3 -c "import json,sys; m=json.load(open(sys.argv[1])); print('%-11s %6d quads (%d not quads), distance %.3f, angle %.2f (tangent %.2f), near-guide quads under 30 degrees %d of %d, %s s %s' % (sys.argv[2], m['faces'], m['non_quad_faces'], m['distance_mean'], m['angle_mean'], m['tangent_angle_mean'], m['quads_near_guides_under_30'], m['quads_near_guides'], sys.argv[3], '; '.join(m['failed'])))" \
    "$out/$name.metrics.json" "$name" "$seconds"
  summary+="\"$name\": {\"seconds\": $seconds, \"metrics\": $(cat "$out/$name.metrics.json")},"
done
echo "${summary%,}}" > "$out/quadwild_check.json"
exit $status
