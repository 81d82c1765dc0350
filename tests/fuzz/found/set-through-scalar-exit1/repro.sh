#!/bin/sh
# Found by the fuzz test (--set materials.film.wrinkling=~ after `materials` had become a scalar). A --set
# path that goes through a scalar value gives yaml-cpp's exception text and exit 1:
#   --set title.x=1                  error: yaml-cpp: error at line 1, column 8: operator[] call on a scalar (key: "x")
#   --set materials.film.young.x=1   error: yaml-cpp: error at line 3, column 33: operator[] call on a scalar ...
# Expected (docs/SCENES.md, --set): exit 2 naming the --set and the scene, e.g. "--set 'title.x=1': title is
# a scalar (line 1), it has no key 'x'".
FSI=${1:-build/bin/fsi}; D=$(dirname "$0"); SCENE=$D/../../seeds/scenes/disc-pressure.yaml
OUT=${TMPDIR:-/tmp}/fsi-found-set-scalar
"$FSI" run "$SCENE" --out "$OUT" --quiet --set title.x=1; echo "exit $?"
"$FSI" run "$SCENE" --out "$OUT" --quiet --set materials.film.young.x=1; echo "exit $?"
