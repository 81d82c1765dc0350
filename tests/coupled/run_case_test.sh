#!/usr/bin/env bash
# Runs a coupled case (cases/coupled/NAME) the way a user does: copied out of the source tree, after sourcing
# the build tree's fsi-env.sh, with its Allrun. Checks its summary.json: the run reached its end time, the
# interface force is the same on the fluid and structure sides (< 1e-6 relative, every window), every
# quantity marked `check: true` in reference.yaml lies within the span of the published values widened by its
# tolerance, and the case's physical `checks` (momentum balance, mesh quality; see summarize.py) pass.
# With CLOTH=porous in the environment (the round canopy only) the case's constant/cloth is switched to its
# porous entry (the adapter's fsiPorousWall) and the summary must report an outward flow through the cloth.
# With REMESH_AT=T (the round canopy only) system/remeshing asks for a new mesh at t = T: the summary must list
# exactly that one (round_canopy.remeshes), its stage1/ must hold the case before it (a ParaView case: mesh,
# fields at T, stage1.foam), and the structure must go on from its state (the skirt radius moves less than
# 1 mm across the new mesh: one window moves it about 0.25 mm).
# Usage: [CLOTH=porous] [REMESH_AT=T] run_case_test.sh NAME BUILD_DIR WORK_DIR [END_TIME]
set -uo pipefail
name=$1 build=$2 work=$3 end=${4:-}
cloth=${CLOTH:-}
remesh_at=${REMESH_AT:-}
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
if [ -n "$remesh_at" ]; then
  sed -i "s|^remeshAt 0; |remeshAt $remesh_at; |" system/remeshing
  grep -q "^remeshAt $remesh_at; " system/remeshing || { echo "FAIL: could not set remeshAt in system/remeshing"; exit 1; }
fi
./Allclean
./Allrun $end || { echo "FAIL: Allrun failed"; exit 1; }
want=${end:-$(foamDictionary -entry endTime -value system/controlDict)}
/usr/bin/python3 - "$want" "$cloth" "$remesh_at" <<'PY'
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
if sys.argv[3]:
    # the forced new mesh: one, at its time, the case before it kept, the structure continuous across it
    at = float(sys.argv[3])
    rem = s.get("round_canopy", {}).get("remeshes", [])
    print(f"new meshes: {json.dumps(rem, indent=1)}")
    if len(rem) != 1 or abs(rem[0]["time"] - at) > 1e-6:
        print(f"FAIL: not one new mesh at t = {at} s")
        ok = False
    else:
        e, stage = rem[0], rem[0]["stage"]
        need = [f"{stage}/{stage}.foam", f"{stage}/constant/polyMesh/faces", f"{stage}/{e['time']:g}/U",
                f"{stage}/{e['time']:g}/uniform/fsiStructure.h5", f"{stage}/system/controlDict"]
        missing = [f for f in need if not os.path.exists(f)]
        if missing:
            print(f"FAIL: the case before the new mesh is incomplete: {missing} missing")
            ok = False
        if not e.get("skirt_radius_jump", 1.0) < 1e-3:
            print(f"FAIL: the skirt radius jumps by {e.get('skirt_radius_jump')} m across the new mesh (limit 1 mm)")
            ok = False
sys.exit(0 if ok else 1)
PY
rc=$?
[ $rc -eq 0 ] && echo "PASS $name" || echo "FAIL $name"
exit $rc
