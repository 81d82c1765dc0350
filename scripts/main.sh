#!/usr/bin/env bash
# README command 1 (the main job): install dependencies, build (Release), run the square airbag
# (structure-only, prescribed pressure) with progress on screen, plot it, and say where the results are.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
"$root/scripts/build.sh"
out="${1:-$root/results/airbag}"
"$root/build/bin/fsi" run "$root/cases/structure/airbag/scene.yaml" --out "$out"
"$root/build/bin/fsi" plot "$out"
echo
echo "Done. Results: $out/results.xdmf  (ParaView: File > Open, pick the Xdmf3 reader; colour by"
echo "wrinkle_state or principal_stress_major). Probes and statistics: $out/summary.json"
echo "Plots and a picture of the inflated airbag: $out/plots/ (energy.png, probes.png, structure.png)"
