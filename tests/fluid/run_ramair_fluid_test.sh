#!/usr/bin/env bash
# The fluid side of the ram-air wing (cases/coupled/ramair-kt, docs/RAMAIR.md), run the way a user does: the
# case's tracked files copied out of the source tree, the build tree's fsi-env.sh sourced, ./Allrun with the
# shipped laminar CI settings (coarse mesh, rigid wing). Checks summary.json:
#   mesh   checkMesh reports "Mesh OK" (every test passed: snappyHexMesh's maxBoundarySkewness 4 keeps the
#          faces at the sharp trailing edge under checkMesh's skewness limit); the fluid patch `wing` has the
#          area of the STL it was snapped to within 1 %; the domain holds the fluid outside the wing
#          (cells > 10000, patch not empty)
#   flow   finite forces, lift > 0, CD > 0, CL within the plausibility band 0.35-1.2 x Helmbold's
#          low-aspect-ratio estimate (inviscid: a 15 % thick section's slope exceeds 2 pi by ~10 %, the low
#          Reynolds number (viscous decambering) lowers it to about half), and settled: CL and CD vary less
#          than 5 % over the last fifth of the steps
#   params an inflow angle of 4 deg turns U_inf, liftDir and dragDir; kOmegaSST writes k, omega, nut with
#          wall functions; mesh_motion laplacian selects displacementLaplacian; locationInMesh is outside
#   input  bad settings files stop Allrun with exit 2 and FILE:LINE before anything runs; a value that
#          looks like a shell command is refused and never executed
#   mirror mirror_mesh yes: every point of the mirrored mesh has its mirror image (the whole snapped mesh does
#          not), checkMesh OK, the wing's area; points off the plane, an unmerged plane, an off-centre wing
#          refused
# Exit 77 (ctest: skipped) when Debian's OpenFOAM binaries are not installed.
# Usage: run_ramair_fluid_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -uo pipefail
src=$1 build=$2 work=$3
. "$(dirname "$0")/ramair_test_case.sh"

# Bad settings: refused with the file and line, exit 2, nothing made.
bad() {
  local text=$1 expect=$2
  printf 'speed 10\n%s\n' "$text" > bad.settings
  ./Allrun -settings bad.settings > bad.log 2>&1
  local rc=$?
  [ $rc -eq 2 ] || { cat bad.log; fail "'$text': exit $rc, not 2"; }
  grep -qF "bad.settings:2:" bad.log || { cat bad.log; fail "'$text': no FILE:LINE in the message"; }
  grep -qF -- "$expect" bad.log || { cat bad.log; fail "'$text': the message lacks '$expect'"; }
  [ ! -e log.blockMesh ] && [ ! -d constant ] || fail "'$text': Allrun went on"
}
bad "sped 10" "did you mean 'speed'"
bad "nu -1" "outside"
bad "steps 2.5" "whole number"
bad "model kEpsilon" "laminar, kOmegaSST"
bad "angle nan" "must be a number"
bad 'courant $(touch${IFS}/tmp/ramair-injected)' "must be a number"
bad "courant 4 5" "expected 'key value'"
bad $'stl_bulge 0\ncoupled yes' "the structure's own surface"
bad "stl_deformed no-such-run" "no such run"
bad 'stl_deformed $(touch${IFS}/tmp/ramair-injected)' "letters, digits"
bad $'mesh_motion none\ncoupled yes' "mesh_motion none with coupled yes"
bad "load_relaxation 0" "outside"
bad "motion_diffusivity cubic" "quadratic, inverse, uniform"
bad "trailing_edge_tape yes" "trailing_edge_tape needs coupled yes"
bad "keep_side yes" "keep_side needs coupled yes"
bad "gap_correction maybe" "no, yes"
bad "smoothing_length 0.01" "smoothing_length needs coupled yes"
bad "smoothing_length -0.01" "outside"
bad "rigid_outer 3" "rigid_outer needs mesh_motion rigidfit"
bad $'rigid_outer 1\nmesh_motion rigidfit\nrigid_inner 2' "must be below rigid_outer"
bad "carry_after 20" "carry_after needs equilibrium_start carry"
bad "solver steady" "pimple, simple"
bad $'solver simple\ncoupled yes' "is for the rigid wing"
bad $'half_domain yes\ncoupled yes' "is for the rigid wing"
bad $'half_domain yes\nmirror_mesh yes' "exclude each other"
bad $'prism_layers yes\ncoupled yes' "is for the rigid wing"
bad $'wall_split 1\ncoupled yes' "needs courant <= 2"
bad $'wall_split 1\nprism_layers yes' "exclude each other"
bad 'wall_split 3' "wall_split"
[ ! -e /tmp/ramair-injected ] || fail "a settings value was executed"
rm -f bad.settings bad.log

start=$(date +%s)
./Allrun || fail "Allrun failed"
echo "Allrun: $(($(date +%s) - start)) s"
/usr/bin/python3 - <<'PY'
import json, math, sys
s = json.load(open("summary.json"))
m, f, e = s["mesh"], s["flow"], s["estimate"]
bad = []
print(f"cells {m['cells']}, checkMesh ok {m['ok']}, failed {m['failed']}, max skewness {m['max_skewness']}")
print(f"wing patch area {m['wing_patch_area']:.5f} m^2, STL {m['stl_area']:.5f} m^2, {100 * m['area_relative_difference']:+.3f} %")
print(f"CL {f['CL']:.4f}, CD {f['CD']:.4f}, estimate {e['CL']:.4f} (ratio {f['CL_over_estimate']:.3f}); "
      f"spread over the last fifth: CL {100 * f['CL_spread_last_fifth']:.2f} %, CD {100 * f['CD_spread_last_fifth']:.2f} %; "
      f"{f['steps']} steps, {f.get('wall_s_per_step', float('nan')):.3f} s per step")
if not (m["ok"] and m["failed_checks"] == 0):
    bad.append("checkMesh does not report the mesh OK")
if m["cells"] < 10000 or m["wing_faces"] == 0:
    bad.append("the mesh does not hold the fluid around the wing")
if not abs(m["area_relative_difference"]) < 0.01:
    bad.append("the wing patch's area differs from the STL's by 1 % or more")
if not f["finite"]:
    bad.append("non-finite force coefficients")
if not (f["CL"] > 0 and f["CD"] > 0):
    bad.append("no lift or no drag")
if not (0.35 <= f["CL_over_estimate"] <= 1.2):
    bad.append("CL outside 0.35-1.2 x the lifting-line estimate")
if not (f["CL_spread_last_fifth"] < 0.05 and f["CD_spread_last_fifth"] < 0.05):
    bad.append("CL or CD not settled (5 % over the last fifth of the steps)")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
rc=$?

# The parameters reach the dictionaries: an inflow angle turns U, the lift and drag directions and the
# wake box; kOmegaSST adds k, omega, nut with wall functions; mesh_motion laplacian selects the motion solver.
mkdir -p variant && printf 'speed 15\nangle 4\nmodel kOmegaSST\nnu 1.5e-5\nmesh_motion laplacian\n' > variant.settings
/usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" write variant.settings constant/triSurface/wing.stl variant > /dev/null &&
  /usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" fields variant || fail "the variant's dictionaries were not written"
/usr/bin/python3 - <<'PY' || rc=1
import json, math, re, sys
r = json.load(open("variant/constant/fluidSettings.json"))
a = math.radians(4)
ctrl = open("variant/system/controlDict").read()
def vec(name, text):
    return [float(x) for x in re.search(name + r"\s+\(([^)]*)\)", text).group(1).split()]
bad = []
if max(abs(x - y) for x, y in zip(vec("liftDir", ctrl), (-math.sin(a), 0, math.cos(a)))) > 1e-8:
    bad.append("liftDir is not normal to the inclined stream")
if max(abs(x - y) for x, y in zip(vec("dragDir", ctrl), (math.cos(a), 0, math.sin(a)))) > 1e-8:
    bad.append("dragDir is not along the inclined stream")
u = vec("freestreamValue uniform", open("variant/0/U").read())
if max(abs(x - 15 * y) for x, y in zip(u, (math.cos(a), 0, math.sin(a)))) > 1e-6:
    bad.append(f"U_inf {u} is not 15 m/s at 4 deg")
for f, wall in (("k", "kqRWallFunction"), ("omega", "omegaWallFunction"), ("nut", "nutUSpaldingWallFunction")):
    try:
        if wall not in open(f"variant/0/{f}").read():
            bad.append(f"0/{f} has no {wall} on the wing")
    except OSError:
        bad.append(f"no 0/{f} for kOmegaSST")
if "kOmegaSST" not in open("variant/constant/turbulenceProperties").read():
    bad.append("turbulenceProperties does not select kOmegaSST")
if "displacementLaplacian" not in open("variant/constant/dynamicMeshDict").read():
    bad.append("mesh_motion laplacian did not select displacementLaplacian")
loc, lo, hi = r["locationInMesh"], r["wing"]["min"], r["wing"]["max"]
if all(lo[i] <= loc[i] <= hi[i] for i in range(3)):
    bad.append("locationInMesh lies within the wing's bounds")
for b in bad:
    print("FAIL:", b)
print("variant (angle 4, kOmegaSST, laplacian):", "ok" if not bad else "FAILED")
sys.exit(1 if bad else 0)
PY
# write_variant NAME TEXT: the dictionaries of the settings TEXT (NAME.settings) written into NAME/
write_variant() {
  mkdir -p "$1" && printf '%s' "$2" > "$1.settings"
  /usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" write "$1.settings" constant/triSurface/wing.stl "$1" > /dev/null ||
    fail "$1: the dictionaries were not written"
}
# carry_after N: the adapter carries the equilibrium pseudo-motion from N steps' time on.
write_variant carry $'speed 15\ncoupled yes\nequilibrium_start carry\ncarry_after 30\n'
/usr/bin/python3 - <<'PY' || rc=1
import json, re, sys
dt, d = json.load(open("carry/constant/fluidSettings.json"))["derived"]["deltaT"], open("carry/system/controlDict").read()
m = re.search(r"equilibriumStart carry;\s*equilibriumCarryFrom ([-+0-9.eE]+);", d)
ok = m is not None and abs(float(m.group(1)) - 30 * dt) < 1e-9 * 30 * dt
print(f"carry_after 30: equilibriumCarryFrom {m.group(1) if m else None} for deltaT {dt:.6g} s:", "ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
PY
# mesh_motion rigidfit: libfsiFoam's motion solver with the distances in chords; a ramp reaching the far field
# is refused naming the key.
write_variant rigidfit $'speed 15\nmesh_motion rigidfit\nrigid_inner 0.5\nrigid_outer 3\n'
/usr/bin/python3 - <<'PY' || rc=1
import json, re, sys
c = json.load(open("rigidfit/constant/fluidSettings.json"))["wing"]["chord"]
d = open("rigidfit/constant/dynamicMeshDict").read()
got = {k: float(re.search(k + r"\s+([-+0-9.eE]+);", d).group(1)) for k in ("innerDistance", "outerDistance")}
ok = ("motionSolver fsiRigidFitDisplacementLaplacian;" in d and "libfsiFoam.so" in d and "patches (wing);" in d
      and abs(got["innerDistance"] - 0.5 * c) < 1e-5 and abs(got["outerDistance"] - 3 * c) < 1e-5)
print(f"rigidfit: {got} for the chord {c:.5g} m:", "ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
PY
# with mirror_mesh yes the same ramp is accepted: the plane y = 0 of the half box is no far field
write_variant rigidfit-mirror $'speed 15\nmesh_motion rigidfit\nrigid_inner 0.5\nrigid_outer 3\nmirror_mesh yes\n'
grep -q "motionSolver fsiRigidFitDisplacementLaplacian;" rigidfit-mirror/constant/dynamicMeshDict ||
  fail "mirror_mesh yes with rigidfit: no rigid-fit motion solver"
printf 'speed 15\nmesh_motion rigidfit\nrigid_outer 40\n' > rigidfit.settings
/usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" write rigidfit.settings constant/triSurface/wing.stl rigidfit > rigidfit.log 2>&1 &&
  fail "rigid_outer 40 (past the far field) accepted"
grep -q "rigid_outer 40 chords reaches the far field" rigidfit.log || { cat rigidfit.log; fail "rigid_outer 40: no message naming the key"; }

# mirror_mesh yes: the half mesh snapped and mirrored. Every point's mirror image about y = 0 is a point of
# the mesh (the whole snapped mesh above is not mirror-symmetric: the measure can fail), checkMesh OK, the
# patch `mirror` gone, the wing patch's area the STL's within 1 %. A half mesh with a point off the plane and
# an unmerged plane are refused; a wing off the plane y = 0 is refused.
mkdir -p mirror && for f in $case_files; do cp "$src/$f" mirror/; done
(cd mirror && printf 'mirror_mesh yes\n' >> laminar-ci.settings && ./Allrun -mesh-only > run.log 2>&1) ||
  { tail -20 mirror/run.log; fail "mirror_mesh yes: Allrun -mesh-only failed"; }
/usr/bin/python3 - <<'PY' || rc=1
import json, sys
sys.path.insert(0, __import__("os").environ["FSI_SHARE_DIR"])
import ramair_fluid as rf
def asymmetric(case):
    pts, _, _, _ = rf.read_patch(case, "wing")
    size = max(abs(x) for p in pts for x in p)
    key = lambda p: tuple(round(x / (1e-9 * size)) for x in p)
    have = {key(p) for p in pts}
    return len(pts), sum(1 for p in pts if key((p[0], -p[1], p[2])) not in have)
bad = []
n_whole, off_whole = asymmetric(".")
n_mirror, off_mirror = asymmetric("mirror")
print(f"points without a mirror image about y = 0: whole snapped mesh {off_whole} of {n_whole}, "
      f"mirrored mesh {off_mirror} of {n_mirror}")
if off_mirror != 0:
    bad.append("the mirrored mesh is not mirror-symmetric")
if off_whole == 0:
    bad.append("the whole snapped mesh is mirror-symmetric too: the measure cannot tell them apart")
m = json.load(open("mirror/summary.json"))["mesh"]
print(f"mirrored: cells {m['cells']}, checkMesh ok {m['ok']}, wing patch {100 * m['area_relative_difference']:+.3f} % "
      f"of the STL's area")
if not (m["ok"] and m["failed_checks"] == 0):
    bad.append("checkMesh does not report the mirrored mesh OK")
if not abs(m["area_relative_difference"]) < 0.01:
    bad.append("the mirrored wing patch's area differs from the STL's by 1 % or more")
if "mirror" in open("mirror/constant/polyMesh/boundary").read():
    bad.append("the emptied patch 'mirror' is still in the boundary file")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
# The checks around mirrorMesh refuse what they exist for: a half mesh (the background box alone) with a
# point moved off the plane, and a plane whose faces were not merged.
rm -rf mirror/constant/polyMesh && (cd mirror && blockMesh > log.blockMesh.half 2>&1) || fail "blockMesh (half box) failed"
/usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" mirror-finish mirror > mirror.log 2>&1 &&
  fail "mirror-finish accepted a plane with its faces"
grep -q "left [0-9]* faces of the patch 'mirror' unmerged" mirror.log || { cat mirror.log; fail "mirror-finish: no message"; }
/usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" mirror-check mirror > mirror.log 2>&1 || { cat mirror.log; fail "mirror-check refused the flat box"; }
/usr/bin/python3 - <<'PY' || fail "could not move a point of the plane"
import re
f = "mirror/constant/polyMesh/points"
t = open(f).read()
# the first point of the half box is a corner on the plane y = 0: move it off
m = re.compile(r"\(([-0-9.e+]+) ([-0-9.e+]+) ([-0-9.e+]+)\)").search(t, t.index("}"))
assert float(m.group(2)) == 0.0, m.group(0)
open(f, "w").write(t[:m.start()] + f"({m.group(1)} 1e-4 {m.group(3)})" + t[m.end():])
PY
/usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" mirror-check mirror > mirror.log 2>&1 &&
  fail "mirror-check accepted a point off the plane"
grep -q "point 0 of the patch 'mirror' (face [0-9]*) lies at y = 0.0001, off the mirror plane" mirror.log ||
  { cat mirror.log; fail "mirror-check: no message naming the point"; }
/usr/bin/python3 - <<'PY' || fail "could not write a shifted STL"
t = open("constant/triSurface/wing.stl").read().split("\n")
out = []
for line in t:
    w = line.split()
    if w and w[0] == "vertex":
        line = f"vertex {w[1]} {float(w[2]) + 0.01} {w[3]}"
    out.append(line)
open("shifted.stl", "w").write("\n".join(out))
PY
printf 'speed 15\nmirror_mesh yes\n' > mirror.settings
/usr/bin/python3 "$FSI_SHARE_DIR/ramair_fluid.py" write mirror.settings shifted.stl shifted > mirror.log 2>&1 &&
  fail "mirror_mesh yes accepted a wing off the plane y = 0"
grep -q "mirror_mesh yes needs a wing symmetric about y = 0" mirror.log || { cat mirror.log; fail "shifted wing: no message"; }

[ $rc -eq 0 ] && echo "PASS ramair-kt fluid" || echo "FAIL ramair-kt fluid"
exit $rc
