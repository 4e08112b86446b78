#!/usr/bin/env bash
# Installs the Debian packages listed in tools/debian-packages.txt (run as root).
set -euo pipefail
cd "$(dirname "$0")/.."
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends $(grep -v '^\s*#' tools/debian-packages.txt)
