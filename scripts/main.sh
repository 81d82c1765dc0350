#!/usr/bin/env bash
# README command 1 (the main job): install dependencies, build (Release), then the coupled ram-air wing
# (cases/coupled/ramair-kt with coupled.settings, docs/RAMAIR.md): the canopy generated from its design
# parameters, the flow meshed around it (blockMesh + snappyHexMesh), a rigid-wing start, then pimpleFoam on
# 2 ranks coupled to the canopy (ram pressure inside, the flow outside, lines anchored) until it settles.
# Progress on screen; at the end the summary table (lift, drag, CL, CD, L/D, pitch, anchor force and
# moments, line tensions, fabric stresses), PNG plots and a picture of the canopy, and the ParaView files.
# Usage: scripts/main.sh [RESULTS_DIR]   (default results/ramair-kt; an earlier run there is replaced)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
t0=$SECONDS
"$root/scripts/build.sh"
out="${1:-$root/results/ramair-kt}"
case $out in /*) ;; *) out="$PWD/$out" ;; esac
if [ -e "$out" ]; then
  [ -f "$out/Allrun" ] || { echo "main.sh: $out exists and is not a ram-air case folder: give another folder" >&2; exit 2; }
  echo "main.sh: replacing the earlier run in $out"
  rm -rf "$out"
fi
mkdir -p "$out"
for f in $(cd cases/coupled/ramair-kt && ls); do cp "cases/coupled/ramair-kt/$f" "$out/"; done
unset FSI_SHARE_DIR
# shellcheck disable=SC1091
. "$root/build/share/fsi/fsi-env.sh"
echo "main.sh: set-up and build took $((SECONDS - t0)) s; the coupled ram-air wing runs in $out"
(cd "$out" && ./Allrun.parallel -settings coupled.settings)
echo
echo "Done in $((SECONDS - t0)) s. The numbers: $out/summary.json (and the table above). Plots and the canopy's"
echo "picture: $out/plots/. ParaView: $out/ramair-kt.foam (the flow; Reconstructed case) and"
echo "$out/structure/results.xdmf (the canopy: colour by principal_stress_major). Logs: $out/log.*."
echo "Structure-only examples (airbag, sphere, the parafoil inflation): README, 'Structure-only runs'."
