#!/bin/sh
# Found by the fuzz test (a renamed key `triangles\xff`, `--set effects.nodal_forces=~`). A `pressure` or
# `nodal_forces` entry without its selector key (`triangles` / `nodes`), or with an empty value, gives
#   error: invalid node; first invalid key: "triangles"                          (exit 1)
# yaml-cpp's YAML::InvalidNode escapes the scene reader: no file, no line, exit 1 instead of 2.
# Expected: exit 2, "scene.yaml:9:3: effects.pressure: missing required key 'triangles'" (as for gravity).
FSI=${1:-build/bin/fsi}; D=$(dirname "$0"); OUT=${TMPDIR:-/tmp}/fsi-found-selector
"$FSI" run "$D/scene.yaml" --out "$OUT" --quiet; echo "exit $?"
"$FSI" run "$D/scene.yaml" --out "$OUT" --quiet --set 'effects={nodal_forces: {force: [0, 0, 1]}}'; echo "exit $?"
"$FSI" run "$D/scene.yaml" --out "$OUT" --quiet --set 'effects={nodal_forces: }'; echo "exit $?"
