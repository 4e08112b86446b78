#!/usr/bin/env bash
# README command 1: install the Debian packages, build, and run the main job on the bundled sample data.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-packages.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
./build/bin/macrocon demo --out demo-out
