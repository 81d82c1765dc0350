#!/usr/bin/env bash
# The coupled ram-air wing (cases/coupled/ramair-kt with coupled.settings: the main job's run, docs/RAMAIR.md),
# run the way a user does: the case's tracked files copied out of the source tree, the build's fsi-env.sh
# sourced, ./Allrun -settings coupled.settings. Checks summary.json and the outputs against references that
# do not come from this code:
#   coupling     every window ran; the interface force is the same on the fluid and the structure side
#                (< 1e-6 relative, every window: the transfer is conservative)
#   symmetry     wing, lines and inflow are mirror-symmetric: the side force stays below 1 % of the lift and
#                the left and right lines' tensions within 3 % of each other (a lateral instability, as seen
#                with 300 pseudo-steps per window, breaks both)
#   flow         lift settled like the rigid wing's (< 5 % over the last fifth of the windows); CL on the loaded
#                canopy's projected area within 0.35-1.2 x Helmbold's low-aspect-ratio estimate at the flown
#                attitude (the rigid wing's band, fluid.ramair-kt); L/D of the canopy between 3 and 20
#                (published ram-air wings: 3-6 with lines and payload, the closed canopy alone higher)
#   trim         the issue's static balance: at the end the supports' reaction equals the applied load (flow,
#                ram pressure, line drag) within 1 % of it, and the wing has stopped swinging: the summary's
#                trim_reached (its criterion in summary.json), the centre section's angle of attack changing by
#                less than 0.25 deg over the last fifth of the windows (check_ramair_wing.py)
#   wing         the engineer's numbers (summary.json's wing, tests/fluid/check_ramair_wing.py): the confluence
#                point's cable forces (elastic + viscous) balance the anchor's reaction to 1e-9, CD system = CD canopy + CD lines with the line
#                drag recomputed from the deformed lines, the design ribs' angle = the generator's incidence,
#                tan(glide) = CD/CL, the wing patch's pressure + shear = the interface lift, the pitching moment
#                = forceCoeffs' CmPitch moved to its CofR, the summary's error against the converged answer
#                (docs/data/ramair_convergence.json: the inputs the study ran must be the case's), the wing plots
#   mesh         checkMesh on the mesh as the canopy left it: no failed check but skewness (the faces at the
#                sharp trailing edge, docs/RAMAIR.md)
#   outputs      summary.md, the plots and the canopy's picture exist, are PNGs and are not blank; ParaView
#                files exist
# Reported, not asserted (docs/RAMAIR.md: not met yet): the moment agreement (the two surfaces' gap).
# Exit 77 (ctest: skipped) without Debian's OpenFOAM binaries. With FSI_MAIN_JOB_RESULTS=DIR (CI's fresh root,
# after scripts/main.sh DIR) the checks run on that finished main-job run instead of a new serial one.
# Usage: run_ramair_coupled_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -uo pipefail
src=$1 build=$2 work=$3
. "$(dirname "$0")/ramair_test_case.sh"

start=$(date +%s)
if [ -n "${FSI_MAIN_JOB_RESULTS:-}" ]; then
  # The main job (scripts/main.sh: Allrun.parallel with the same coupled.settings) already ran this case on
  # this machine: check its results instead of running it a second time (CI's fresh root, issue 33 item 0).
  [ -f "$FSI_MAIN_JOB_RESULTS/summary.json" ] || fail "FSI_MAIN_JOB_RESULTS=$FSI_MAIN_JOB_RESULTS has no summary.json"
  for f in coupled.settings structure.yaml; do
    cmp -s "$FSI_MAIN_JOB_RESULTS/$f" "$f" ||
      fail "$FSI_MAIN_JOB_RESULTS/$f differs from the source tree's: not the main job of this commit"
  done
  cd "$FSI_MAIN_JOB_RESULTS" || exit 1
  echo "checking the main job's run in $PWD (FSI_MAIN_JOB_RESULTS) instead of running the case again"
else
  ./Allrun -settings coupled.settings || fail "Allrun failed"
  echo "Allrun: $(($(date +%s) - start)) s"
fi
/usr/bin/python3 - <<'PY'
import glob, json, math, os, sys
s = json.load(open("summary.json"))
c, e, mf = s["coupled"], s["estimate"], s.get("mesh_final", {})
steps = s["settings"]["steps"]
bad = []
def check(ok, what):
    if not ok:
        bad.append(what)
lift = c["history"]["Fz_fluid"]
tail = lift[-max(2, len(lift) // 5):]
spread = (max(tail) - min(tail)) / abs(lift[-1])
print(f"windows {c['windows']}, force fluid/structure {c['force_fluid_vs_structure_max_relative']:.2e}, "
      f"equilibrium {c['equilibrium_relative']:.2e}, lift spread over the last fifth {100 * spread:.2f} %")
we = s["wing"]["estimate"]
print(f"CL {c['CL']:.4f} (loaded area {we['CL_canopy_deformed_area']:.4f}; Helmbold at the flown attitude {we['CL_estimate']:.4f}, "
      f"ratio {we['CL_over_estimate']:.3f}), CD {c['CD']:.4f}, L/D {c['L_over_D']:.2f}, "
      f"side {c['side_N']:.4f} N, lines left/right {c['lines_left_sum_N']:.3f} / {c['lines_right_sum_N']:.3f} N")
check(c["windows"] == steps, f"{c['windows']} windows, not {steps}")
check(c["force_fluid_vs_structure_max_relative"] < 1e-6, "fluid and structure interface forces differ by 1e-6 or more")
check((c["moment_fluid_vs_structure_max_relative"] or 1.0) < 1e-6,
      "fluid and structure interface moments differ by 1e-6 or more (conserveMoment)")
check(abs(c["lines_left_sum_N"] - c["lines_right_sum_N"]) < 0.03 * c["lines_left_sum_N"], "left and right lines differ by 3 % or more")
check(abs(c["side_N"]) < 0.01 * abs(c["lift_N"]), "side force of 1 % of the lift or more")
check(spread < 0.05, "lift not settled (5 % over the last fifth)")
print(f"trim: balance {100 * c['equilibrium_relative']:.2f} %, centre section angle of attack "
      f"{s['wing']['section_alpha']['centre_deg']:.2f} deg")
check(c["equilibrium_relative"] < 0.01, "supports and applied load differ by 1 % or more at the end")
check(all(math.isfinite(x) for x in c["fluid_force_N"]), "non-finite forces")
check(0.35 <= we["CL_over_estimate"] <= 1.2, "CL outside 0.35-1.2 x Helmbold's estimate at the flown attitude")
check(3 <= c["L_over_D"] <= 20, "L/D outside 3-20")
check(mf.get("ok") or mf.get("only_skewness"), f"checkMesh of the moved mesh fails {mf.get('failed')}")
print(f"moved mesh: max skewness {mf.get('max_skewness')}, non-orthogonality {mf.get('max_non_orthogonality')}; "
      f"moment fluid/structure {c['moment_fluid_vs_structure_max_relative']:.2e}; "
      f"stress max/mean {c['stress_max_over_mean']:.2f}")
check(os.path.exists("summary.md"), "no summary.md")
def png_ok(path):
    """A PNG with something drawn: its pixels are not all one colour (standard deviation > 1 %)."""
    import matplotlib.image
    try:
        with open(path, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                return False
        return float(matplotlib.image.imread(path)[..., :3].std()) > 0.01
    except (OSError, ValueError, SyntaxError):
        return False
for name in ("interface_force.png", "iterations.png", "probes.png", "structure.png"):
    check(png_ok(os.path.join("plots", name)), f"plots/{name} missing, not a PNG or blank")
check(os.path.exists("structure/results.xdmf") and glob.glob("*.foam"), "ParaView files missing")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
rc=$?
# the main job's case: its summary must state its error against the converged answer of its own inputs
FSI_EXPECT_CONVERGED_REFERENCE=1 /usr/bin/python3 "$src/tests/fluid/check_ramair_wing.py" . || rc=1
[ $rc -eq 0 ] && echo "PASS ramair-kt coupled" || echo "FAIL ramair-kt coupled"
exit $rc
