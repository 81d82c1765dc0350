#!/bin/sh
# Found by the fuzz test (truncated scenes, deleted lines). A key whose value is empty (YAML null) gives
#   error: .../scene.yaml: probes.p: missing required key 'type'               (exit 2, no line)
# The same for `effects: {gravity: }`, `mass_damping:`, `time:`, `constraints: [{symmetry: }]`, a generator
# without keys, `meshes:` ("meshes: at least one mesh is needed", no line; `meshes: {}` has its line).
# Expected: the line of the key (scene.yaml:10) like every other reader error.
FSI=${1:-build/bin/fsi}; D=$(dirname "$0")
"$FSI" run "$D/scene.yaml" --out "${TMPDIR:-/tmp}/fsi-found-null" --quiet; echo "exit $?"
