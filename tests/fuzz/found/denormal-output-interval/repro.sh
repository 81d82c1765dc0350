#!/bin/sh
# Found by the fuzz test (classified `slow`: the run is busy and its time advances). An output interval of
# 1e-320 (denormal, >= 0 so accepted) forces every step onto an output time: dt = 1e-320 s, one frame per
# step (results.h5 and the rewritten results.xdmf grow by megabytes per second), 2e317 steps to the end, and
# the progress line prints an estimate of 3.9e+323 seconds as 300 digits. The same happens with
# `time.max_dt: 1e-320` or `time.fixed_dt: 1e-320`.
# Expected: exit 2 naming output.interval (scene.yaml:19, here the --set), e.g. "gives 2e+317 frames" - a bound on the
# number of steps/frames a run may need, like the generators' bound on the number of elements.
FSI=${1:-build/bin/fsi}; D=$(dirname "$0"); OUT=${TMPDIR:-/tmp}/fsi-found-interval
timeout 5 "$FSI" run "$D/../../seeds/scenes/disc-pressure.yaml" --out "$OUT" --set output.interval=1e-320 | tail -1 | cut -c1-160
echo "(stopped after 5 s by timeout)"; ls -l "$OUT"
