#!/usr/bin/env bash
# README command 2: install dependencies, build, run the whole test suite through ctest.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
"$root/scripts/build.sh"
jobs="$(nproc 2>/dev/null || echo 2)"
ctest --test-dir build --output-on-failure -j "$jobs" "$@"
