#!/usr/bin/env bash
# Regenerates packaging/abi/libmacrocon.abi from build/ (only with a deliberate ABI release or a
# major version bump; note it in CHANGELOG.md).
set -euo pipefail
cd "$(dirname "$0")/.."
lib=$(readlink -f build/lib/libmacrocon.so)
abidw --headers-dir include/macrocon --out-file packaging/abi/libmacrocon.abi "$lib"
echo "baseline written from $lib"
