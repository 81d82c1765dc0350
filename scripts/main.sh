#!/usr/bin/env bash
# README command 1 (the main job): install dependencies, build (Release), build a ram-air parafoil from its
# design parameters and inflate it structure-only (ram pressure inside, a Cp field outside, line drag, lines
# anchored) to its static state with progress on screen, write its meshes for Gmsh/snappyHexMesh, plot it,
# and say where the results are. (The coupled ram-air run is not here yet: docs/PARAFOIL.md.)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
"$root/scripts/build.sh"
case_dir="$root/cases/structure/parafoil-kt-inflation"
out="${1:-$root/results/parafoil-kt-inflation}"
"$root/build/bin/fsi" generate "$case_dir/scene.yaml" --out "$out/mesh"
"$root/build/bin/fsi" run "$case_dir/scene.yaml" --out "$out"
"$root/build/bin/fsi" plot "$out"
echo
echo "Done. Results: $out/results.xdmf  (ParaView: File > Open, pick the Xdmf3 reader; colour by"
echo "principal_stress_major or wrinkle_state). Probes (anchor force, line and brake tensions, pitch, volume)"
echo "and statistics: $out/summary.json. The design shape: $out/mesh/wing.msh (Gmsh, with its sets) and"
echo "$out/mesh/wing.stl (the outer surface). Plots and a picture: $out/plots/ (energy, probes, structure)."
