#!/usr/bin/env bash
# Configures and builds the project (Release) into ./build. Usage: scripts/build.sh [extra cmake args]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
"$root/scripts/install-deps.sh"
jobs="$(nproc 2>/dev/null || echo 2)"
# The build runs where it is used, so optimise for this CPU (about 1.4x on the force kernels, see
# docs/PERFORMANCE.md); FSI_NATIVE=OFF gives a portable binary.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFSI_NATIVE="${FSI_NATIVE:-ON}" "$@" >/dev/null
cmake --build build -j "$jobs"
