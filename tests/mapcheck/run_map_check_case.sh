#!/usr/bin/env bash
# Pre-flight check of a shipped coupled case (cases/coupled/NAME): in a scratch copy, makes the fluid mesh as the
# case's Allrun does (blockMesh, and createBaffles where the Allrun runs it), then runs
#   fsi map-check structure.yaml .:PATCH
# for every patch of the case's fsiCoupling function object. Each must map all points both ways, reproduce a
# linear field (both interfaces are planar and cover the same surface, so only round-off remains) and transfer
# force and moment conservatively; it prints the coupled run's settings (the same defaults) and names any that
# differ.
# Usage: run_map_check_case.sh NAME FSI WORK_DIR
set -uo pipefail
name=$1 fsi=$2 work=$3
src="$(cd "$(dirname "$0")/../../cases/coupled" && pwd)/$name"
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
fail() { echo "FAIL $name: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work" && cp -r "$src" "$work/" || fail "cannot copy $src"
cd "$work/$name" || exit 1
blockMesh > log.blockMesh 2>&1 || { tail -20 log.blockMesh; fail "blockMesh failed"; }
if grep -q '^[^#]*createBaffles' Allrun; then
  createBaffles -overwrite > log.createBaffles 2>&1 || { tail -20 log.createBaffles; fail "createBaffles failed"; }
fi
# The interface patches: `patches (...)` of the function object whose type is fsiCoupling.
patches=$(/usr/bin/python3 -c '
import re, sys
text = re.sub(r"//.*", "", open("system/controlDict").read())
m = re.search(r"type\s+fsiCoupling\s*;.*?patches\s*\(([^)]*)\)", text, re.S)
print(m.group(1) if m else "")')
[ -n "$patches" ] || fail "no fsiCoupling patches in system/controlDict"
for patch in $patches; do
  echo "== fsi map-check structure.yaml .:$patch"
  "$fsi" map-check structure.yaml ".:$patch" --json "map-check-$patch.json" | tee "map-check-$patch.log"
  rc=${PIPESTATUS[0]}
  [ $rc -eq 0 ] || fail "map-check on patch $patch exited with $rc"
  # its defaults are the coupled run's (coupledRunProjection(), the adapter's option table's): it says so
  grep -q "^settings: projection consistent, evaluation pointwise, quadratureLevel auto" "map-check-$patch.log" &&
    grep -q "(the coupled run's defaults" "map-check-$patch.log" ||
    fail "map-check does not print the coupled run's settings"
  "$fsi" map-check structure.yaml ".:$patch" --evaluation l2 --quadrature-level 1 > "map-check-$patch-l2.log" ||
    fail "map-check --evaluation l2 --quadrature-level 1 failed"
  grep -q "(not the coupled run's defaults: evaluation l2, quadratureLevel 1)" "map-check-$patch-l2.log" ||
    fail "map-check with other settings does not name them"
  /usr/bin/python3 - "map-check-$patch.json" <<'PY' || fail "map-check on patch $patch: errors too large"
import json, sys
r = json.load(open(sys.argv[1]))
ok = r["all_mapped"]
for d in r["directions"]:
    print(f'{d["source"]} -> {d["target"]}: unmapped nodes {d["unmapped_target_nodes"]}, linear max '
          f'{d["linear_error"]["max"]:.3e}, quadratic max {d["quadratic_error"]["max"]:.3e}, force '
          f'{d["conservative_force_error"]:.3e}, moment {d["conservative_moment_error"]:.3e}')
    ok = ok and d["unmapped_target_nodes"] == 0 and d["linear_error"]["max"] < 1e-9 \
        and d["conservative_force_error"] < 1e-12 and d["conservative_moment_error"] < 1e-9
sys.exit(0 if ok else 1)
PY
done
echo "PASS $name"
