#!/bin/sh
# Found by the fuzz test (`--set ''`, an empty override: exit 114). Command-line errors end with CLI11's own
# exit codes, outside the documented set (0, 2 bad input, 3, 4, 130; 1 other errors):
#   fsi run SCENE --out DIR --set=        exit 114 ("--set: 1 required TEXT missing")
#   fsi run                               exit 106 (missing arguments)
#   fsi map-check a b --tolerance x       exit 104 (not a number)
#   fsi frobnicate                        exit 106 (unknown subcommand)
# Expected: exit 2 (bad input) with the usage message.
FSI=${1:-build/bin/fsi}; D=$(dirname "$0"); SCENE=$D/../../seeds/scenes/disc-pressure.yaml
"$FSI" run "$SCENE" --out "${TMPDIR:-/tmp}/fsi-found-cli" --quiet --set= 2>/dev/null; echo "exit $?"
"$FSI" run 2>/dev/null; echo "exit $?"
"$FSI" map-check a b --tolerance x 2>/dev/null; echo "exit $?"
"$FSI" frobnicate 2>/dev/null; echo "exit $?"
