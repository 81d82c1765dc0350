#!/bin/sh
# Found by the fuzz test (a density mutated to 1e-320). The density passes the reader's "> 0" check, the
# lumped masses underflow to 0 and the run stops with
#   error: node 6 of mesh 'disc' belongs to no element and has no mass          (exit 2)
# which is wrong (the node belongs to elements) and names neither the file nor the key.
# Expected: exit 2 naming scene.yaml:3, materials.film.density (e.g. "too small: the masses underflow").
FSI=${1:-build/bin/fsi}; D=$(dirname "$0")
"$FSI" run "$D/scene.yaml" --out "${TMPDIR:-/tmp}/fsi-found-density" --quiet; echo "exit $?"
