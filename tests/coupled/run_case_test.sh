#!/usr/bin/env bash
# Runs a coupled case (cases/coupled/NAME) the way a user does: copied out of the source tree, after sourcing
# the build tree's fsi-env.sh, with its Allrun. Checks its summary.json: the run reached its end time, the
# interface force is the same on the fluid and structure sides (< 1e-6 relative, every window), every
# quantity marked `check: true` in reference.yaml lies within the span of the published values widened by its
# tolerance, and the case's physical `checks` (momentum balance, mesh quality; see summarize.py) pass.
# With CLOTH=porous in the environment (the round canopy only) the case's constant/cloth is switched to its
# porous entry (the adapter's fsiPorousWall) and the summary must report an outward flow through the cloth.
# Usage: [CLOTH=porous] run_case_test.sh NAME BUILD_DIR WORK_DIR [END_TIME]
set -uo pipefail
name=$1 build=$2 work=$3 end=${4:-}
cloth=${CLOTH:-}
src="$(cd "$(dirname "$0")/../../cases/coupled" && pwd)"
rm -rf "$work" && mkdir -p "$work"
cp -r "$src/$name" "$work/"
unset FSI_SHARE_DIR
. "$build/share/fsi/fsi-env.sh"
cd "$work/$name" || exit 1
if [ "$cloth" = porous ]; then
  sed -i -e 's|^clothU { type movingWallVelocity;|// &|' -e 's|^// *\(clothU { type fsiPorousWall;\)|\1|' constant/cloth
  grep -q "^clothU { type fsiPorousWall;" constant/cloth && ! grep -q "^clothU { type movingWallVelocity;" constant/cloth ||
    { echo "FAIL: could not switch constant/cloth to the porous entry"; exit 1; }
fi
./Allclean
./Allrun $end || { echo "FAIL: Allrun failed"; exit 1; }
want=${end:-$(foamDictionary -entry endTime -value system/controlDict)}
/usr/bin/python3 - "$want" "$cloth" <<'PY'
import glob, json, os, sys
s = json.load(open("summary.json"))
# every time directory is a real one (fields), none a leftover of a repeated coupling step
stray = [d for d in glob.glob("[0-9]*") if os.path.isdir(d) and not os.path.exists(os.path.join(d, "U"))]
if stray:
    print("time directories without fields:", stray)
    sys.exit(1)
print(json.dumps(s, indent=1))
end = float(sys.argv[1])
reached = s["end_time"] is not None and abs(s["end_time"] - end) < 1e-9 * max(1.0, end)
if not reached:
    print(f"the run ended at {s['end_time']}, not {end}")
ok = reached and s["interface_force_relative_difference"] < 1e-6 and s["all_checks_within_tolerance"]
# the adapter's conserveMoment (default): the structure's loads carry the fluid's moment too
moment = s.get("interface_moment_relative_difference")
if moment is None or not moment < 1e-6:
    print(f"interface moment fluid vs structure {moment}: not within 1e-6")
    ok = False
for k in ("momentum_balance", "mesh_quality"):
    if k in s:
        print(f"{k}: {s[k]}")
for k, v in s["results"].items():
    print(f"{k}: {v['value']} at t = {v['time']} (accepted {v['accepted_range']}, check {v['check']}, within {v['within']})")
if sys.argv[2] == "porous":
    # the porous cloth passes air: a flow through it (round_canopy_summary.py's cloth block), a positive
    # fraction below one of the flow the mouth faces (continuity: what leaves through the cloth came in there)
    cloth = s.get("round_canopy", {}).get("cloth", {})
    frac = cloth.get("flow_over_mouth_flow")
    print(f"porous cloth: {cloth}")
    if cloth.get("a") is None or frac is None or not 0.0 < frac < 1.0:
        print("FAIL: no porous cloth with a flow through it below the mouth's")
        ok = False
sys.exit(0 if ok else 1)
PY
rc=$?
[ $rc -eq 0 ] && echo "PASS $name" || echo "FAIL $name"
exit $rc
