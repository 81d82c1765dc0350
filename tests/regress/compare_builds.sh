#!/usr/bin/env bash
# Bit-identity of two builds on the structure cases (a refactoring's evidence; issue 36's "results
# bit-identical"): every cases/structure/*/*.yaml scene but reference.yaml, run for 0.02 s of until_static time
# (whole for the others) with the fsi binary A and the fsi binary B, then h5diff of each pair of results.h5.
# Prints one line per scene and exits 1 if any differs or a run is missing.
# Usage: tests/regress/compare_builds.sh FSI_A FSI_B WORK_DIR
#   e.g. a worktree of the old commit built into /tmp/old:  compare_builds.sh /tmp/old/build/bin/fsi build/bin/fsi /tmp/cmp
set -u
abs() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
a=$(abs "$1") b=$(abs "$2") work=$(abs "$3")
src="$(cd "$(dirname "$0")/../.." && pwd)/cases/structure"
command -v h5diff > /dev/null || { echo "h5diff not found (apt-get install hdf5-tools)"; exit 2; }
run() {  # run BIN OUT
  for d in "$src"/*/; do
    local c; c=$(basename "$d")
    for s in "$d"*.yaml; do
      local n; n=$(basename "$s" .yaml)
      [ "$n" = reference ] && continue
      local sets=()
      grep -q "until_static" "$s" && sets=(--set time.until_static.max_time=0.02)
      (cd "$d" && timeout 600 "$1" run "$s" -o "$2/$c-$n" -q "${sets[@]}" > "$2/$c-$n.log" 2>&1)
    done
  done
}
rm -rf "$work" && mkdir -p "$work/a" "$work/b"
run "$a" "$work/a"
run "$b" "$work/b"
bad=0
for d in "$work"/a/*/; do
  c=$(basename "$d")
  if [ ! -f "$d/results.h5" ] || [ ! -f "$work/b/$c/results.h5" ]; then
    echo "$c: results.h5 missing"; bad=1; continue
  fi
  if h5diff -q "$d/results.h5" "$work/b/$c/results.h5" > /dev/null 2>&1; then
    echo "$c: identical"
  else
    echo "$c: DIFFERS"; bad=1
  fi
done
exit $bad
