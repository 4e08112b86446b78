#!/usr/bin/env bash
# README command 2: build (if needed) and run every test, twice: a Release build and an
# AddressSanitizer + UndefinedBehaviorSanitizer build. Exits non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${MACROCON_JOBS:-$(nproc)}"
run_suite() {
  local dir="$1"; shift
  cmake -S . -B "$dir" -G Ninja "$@"
  cmake --build "$dir" -j "$jobs"
  (cd "$dir" && ctest --output-on-failure -j "$jobs" --timeout 1800)
}
run_suite build -DCMAKE_BUILD_TYPE=Release
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# -Werror gates the Release build above; here GCC 12's sanitizer instrumentation can raise
# false-positive diagnostics (-Wmaybe-uninitialized, -Wstringop-overflow), so this build checks
# run-time behaviour only.
run_suite build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMACROCON_SANITIZE=ON -DMACROCON_WERROR=OFF
