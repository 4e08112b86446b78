#!/usr/bin/env bash
# Runs every libFuzzer target (tests/fuzz, docs/fuzzing.md) for SECONDS each, one after another,
# and prints per target the last progress line (#N DONE cov: ...) and the final stats.
#   tools/fuzz.sh SECONDS [TARGET...]
# Environment: FUZZ_BUILD (default build/fuzz), FUZZ_CXX (default clang++-14), FUZZ_GENERATOR
# (default Ninja). The corpus each run grows stays in $FUZZ_BUILD/corpus; findings go to
# $FUZZ_BUILD/artifacts and make the script exit non-zero.
set -euo pipefail
if [[ $# -lt 1 || ! $1 =~ ^[0-9]+$ ]]; then
  echo "usage: $0 SECONDS [TARGET...]" >&2
  exit 2
fi
seconds=$1
shift
root=$(cd "$(dirname "$0")/.." && pwd)
build=${FUZZ_BUILD:-$root/build/fuzz}
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  targets=(library_loader_fuzzer mesh_reader_fuzzer field_reader_fuzzer capi_fuzzer)
fi
status=0
for target in "${targets[@]}"; do
  echo "== $target (${seconds}s)"
  log=$(mktemp)
  rc=0
  cmake -DSOURCE_DIR="$root/tests/fuzz" -DBINARY_DIR="$build" -DCXX="${FUZZ_CXX:-clang++-14}" \
    -DGENERATOR="${FUZZ_GENERATOR:-Ninja}" -DSECONDS="$seconds" -DFUZZ_TARGET="$target" \
    -P "$root/tests/scripts/run_fuzz.cmake" >"$log" 2>&1 || rc=$?
  if [[ $rc -eq 0 ]]; then
    grep -E "libFuzzer" "$log" | sed 's/^-- //'
  else
    cat "$log"
    echo "== $target FAILED"
    status=1
  fi
  rm -f "$log"
done
exit $status
