#!/usr/bin/python3
"""The CI-size check of rung 2 of the fluid validation ladder (studies/wing/wing_polar.py, docs/AERODYNAMICS.md):
the rigid wing without arc on the coarse mesh, steady, half domain, at two angles of attack. Checks against
references that do not come from this code:
  solver   a steady answer: SIMPLE met its residual control (initial residuals p 1e-5, U, k, omega 1e-6), or the
           forces moved less than 0.1 % over the last fifth of the iterations with the p residual below 1e-4
  slope    the lift slope between the two angles against Helmbold's low-aspect-ratio lifting line (a0 = 2 pi per
           radian, the aspect ratio of the projected planform): within 0.70-1.05 of it. The band is the coarse
           mesh's (docs/AERODYNAMICS.md: the coarse wall-function mesh reads the slope 15-25 % low, the finer
           meshes within 10 %); a slope that collapses, as the bulged wing's did, or a sign error fails
  y+       the mean y+ on the wing within a factor 2 of the flat-plate estimate for the first cell centre (half the
           finest cell): u_tau = U sqrt(Cf/2), Cf = 0.0576 Re_c^-0.2 (turbulent flat plate, averaged over the chord)
  half     the half domain holds the half wing: the wing patch's area is half the STL's within 1 %
Usage: test_wing_polar.py SOURCE_DIR BUILD_DIR WORK_DIR. Exit 77 (skipped) without Debian's OpenFOAM.
"""
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

src, build, work = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
if shutil.which("simpleFoam") is None:
    print("SKIP: simpleFoam not found (OpenFOAM is not installed)")
    sys.exit(77)
if work.exists():
    shutil.rmtree(work)
work.mkdir(parents=True)
out, js = work / "runs", work / "wing_polar.json"
alphas = (2.0, 8.0)
rc = subprocess.run(["/usr/bin/python3", str(src / "studies/wing/wing_polar.py"), "--variants", "flat", "--levels",
                     "coarse", "--alpha=" + ",".join(f"{a:g}" for a in alphas), "--iterations", "400",
                     "--out", str(out), "--json", str(js),
                     "--env", str(build / "share/fsi/fsi-env.sh")]).returncode
if rc != 0:
    print(f"FAIL: wing_polar.py exited {rc}")
    sys.exit(1)
pts = {p["alpha_deg"]: p for p in json.loads(js.read_text())["points"]}
bad = []
for a in alphas:
    p = pts.get(a)
    if p is None:
        bad.append(f"no point at alpha {a:g}")
        continue
    print(f"alpha {a:g}: CL {p['CL']:.4f} CD {p['CD']:.4f} Cm {p['Cm']:.4f}, {p['iterations']} iterations, "
          f"converged {p['converged']}, y+ {p['y_plus']}")
    if not p["converged"]:
        bad.append(f"alpha {a:g}: not converged in {p['iterations']} iterations (SIMPLE's residual control not met, "
                   "and the forces still moving by 0.1 % over the last fifth or the p residual above 1e-4)")
if not bad:
    p0, p1 = pts[alphas[0]], pts[alphas[1]]
    slope = (p1["CL"] - p0["CL"]) / math.radians(alphas[1] - alphas[0])
    ar = p0["aspect_ratio"]
    k = 2 * math.pi / (math.pi * ar)
    helmbold = 2 * math.pi / (math.sqrt(1 + k * k) + k)
    print(f"lift slope {slope:.3f}/rad, Helmbold {helmbold:.3f}/rad (AR {ar:.3f}): ratio {slope / helmbold:.3f}")
    if not 0.70 <= slope / helmbold <= 1.05:
        bad.append(f"lift slope {slope:.3f}/rad is {slope / helmbold:.3f} x Helmbold's, outside 0.70-1.05")
    re_c, u = 15.0 * 1.0 / 1.5e-5, 15.0
    cf = 0.0576 * re_c ** -0.2
    y_est = 0.5 * p0["wall_cell_m"] * u * math.sqrt(cf / 2) / 1.5e-5
    ym = p0["y_plus"]["mean"] if p0["y_plus"] else float("nan")
    print(f"mean y+ {ym:.1f}, flat-plate estimate {y_est:.1f} at the first cell centre ({p0['wall_cell_m']:.4g} m cells)")
    if not 0.5 * y_est <= ym <= 2 * y_est:
        bad.append(f"mean y+ {ym:.1f} is not within a factor 2 of the flat-plate estimate {y_est:.1f}")
    for a in alphas:
        case = out / "flat" / "coarse" / f"a{a:g}"
        m = json.loads((case / "summary.json").read_text())["mesh"]
        if not abs(m["area_relative_difference"]) < 0.01:
            bad.append(f"alpha {a:g}: the wing patch ({m['wing_patch_area']:.4f} m^2) is not half the STL's area "
                       f"({m['stl_area']:.4f} m^2) within 1 %")
for b in bad:
    print("FAIL:", b)
print("PASS study.wing-polar" if not bad else "FAIL study.wing-polar")
sys.exit(1 if bad else 0)
