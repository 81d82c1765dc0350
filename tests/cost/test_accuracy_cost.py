#!/usr/bin/env python3
"""ctest cost.accuracy_cost: runs studies/cost/accuracy_cost.py --quick into WORK and checks what it produced —
the document with a table per knob, non-blank plots — and that the measured errors behave as theory says:
second-order mesh convergence (Hencky from differences, sphere against its closed form, the projection's
consistent and dual variants), second order in the safety factor (central differences), lower order for the
lumped projection, smaller errors at tighter dynamic-relaxation tolerances, static answers that do not
depend on the mass; coupled (added-mass drum against its exact answer): first order in the fluid step,
smaller iteration errors at tighter tolerances, the staggered scheme stable below its added-mass limit and
unstable far above it. Usage: test_accuracy_cost.py FSI COUPLING_DRIVER WORK"""
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
fsi, driver, work = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
res_file = work / "accuracy_cost.json"
subprocess.run(["/usr/bin/python3", str(ROOT / "studies/cost/accuracy_cost.py"), "--quick", "--fsi", str(fsi), "--coupling-driver",
                str(driver), "--out",
                str(work), "--json", str(res_file)], check=True)

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def within(x, lo, hi):
    return x == x and lo <= x <= hi


# The document: a section and a table row per measured level, for every knob.
doc = (work / "ACCURACY_COST.md").read_text()
res = json.loads(res_file.read_text())
for heading in ("## Mesh refinement", "### Hencky", "### Pressurised sphere", "### Square airbag",
                "## Time integration: safety factor", "## Time integration: selective mass scaling",
                "## Static answers by dynamic relaxation", "## Projection between non-matching meshes",
                "## Coupled knobs: fluid step", "## Coupled knobs on the sail"):
    check(heading in doc, f"document has '{heading}'")
# The sail's rows, where studies/sail/sail_knobs.py --docs stored them: every variant's row in the document.
sail_data = ROOT / "docs/data/sail_knobs.json"
if sail_data.exists():
    for r in json.loads(sail_data.read_text())["rows"]:
        check(f"| {r['variant']} (" in doc, f"sail knobs: row for {r['variant']}")
check(doc.count("what you buy") >= 6 and doc.count("× the time") >= 20, "document has computed 'what you buy' words")
for study in res["mesh"]:
    for r in study["rows"]:
        check(f"| {r['level']} | {r['elements']} |" in doc, f"{study['name']}: table row for level {r['level']}")

# Plots: present, not blank (a plot has axes, lines and text on a white background).
for name in ("mesh", "time", "dr", "projection", "coupled"):
    png = work / "img" / f"accuracy_cost_{name}.png"
    if not png.exists():
        check(False, f"{png.name} exists")
        continue
    img = mpimg.imread(png)[..., :3]
    grey = img.mean(axis=2)
    dark = float((grey < 0.6).mean())
    check(img.shape[0] > 200 and img.shape[1] > 300 and grey.std() > 0.05 and dark > 0.005,
          f"{png.name} is not blank ({img.shape[1]}x{img.shape[0]}, {100 * dark:.1f} % dark pixels)")

# Mesh refinement. Hencky: near second order against the exact solution of the continuum problem
# (studies/common/hencky_reference.py) and from three successive differences (which needs no reference).
h = next(s for s in res["mesh"] if s["name"] == "hencky")
p = h["difference_orders"][-1]
check(within(p, 1.5, 2.5), f"hencky: observed order from differences {p:.2f} in [1.5, 2.5]")
check(all(within(o, 1.5, 2.5) for o in h["orders"]),
      f"hencky: orders against the exact GL/SVK solution {h['orders']} in [1.5, 2.5]")
# Sphere: against the exact closed form of the same continuum model, every halving near second order.
s = next(s for s in res["mesh"] if s["name"] == "sphere")
e = [r["error"] for r in s["rows"]]
orders = [math.log(a / b) / math.log(2) for a, b in zip(e, e[1:])]
check(all(within(o, 1.5, 2.5) for o in orders), f"sphere: orders against the closed form {orders} in [1.5, 2.5]")

# Safety factor: central differences are second order in the step, the step proportional to the factor.
saf = res["safety"]
check(all(within(o, 1.7, 2.3) for o in saf["orders"]), f"safety: observed orders {saf['orders']} in [1.7, 2.3]")
# Static answers (safety, mass scaling) do not depend on the step or the mass; the transient does.
ms = res["mass_scaling"]
static = [r["error"] for r in saf["static_rows"]] + [r["static_error"] for r in ms["rows"]] + \
         [r["error"] for r in ms["sphere"]["rows"]]
check(max(static) < 1e-4, f"static answers independent of step and mass: largest change {max(static):.1e} < 1e-4")
check(ms["rows"][-1]["error"] > 100 * ms["rows"][0]["error"],
      "mass scaling changes the transient (error > 100× the unscaled run's)")
check(all(r["added"] > 0 for r in ms["rows"][1:]) and ms["rows"][0]["added"] == 0, "mass scaling adds mass")

# Dynamic relaxation: a tighter tolerance gives a smaller error, for each method.
for m in {r["method"] for r in res["dr"]["rows"]}:
    rows = [r for r in res["dr"]["rows"] if r["method"] == m and r["converged"]]
    check(len(rows) >= 2 and rows[-1]["ew"] < rows[0]["ew"],
          f"DR {m}: error at ε = {rows[-1]['eps']:.0e} below that at {rows[0]['eps']:.0e}")

# Projection: consistent and dual second order, lumped clearly lower (first order on irregular meshes).
o = res["projection"]["orders"]
for v in ("consistent", "dual"):
    check(all(within(x, 1.7, 2.3) for x in o[v]), f"projection {v}: orders {o[v]} in [1.7, 2.3]")
check(all(x < 1.6 for x in o["lumped"]), f"projection lumped: orders {o['lumped']} < 1.6")
check(all(r["unmapped"] == 0 for r in res["projection"]["rows"]), "projection: every quadrature point mapped")
q = res["projection"]["quadrature"]
check(q[-1]["error"] <= q[0]["error"], "quadrature: the finest level is not less accurate than level 1")

# Coupled, the added-mass drum: the monolithic reference equals the exact free acceleration (checks the
# problem), the lagged added-mass acceleration makes the window error first order, tighter tolerances give
# smaller iteration errors, staggered is stable at m_a/m_s = 0.1 (< 1/3) and blows up at 5.
cp = res["coupled"]
check(abs(cp["monolithic"] / cp["exact"] - 1) < 1e-6, "coupled: monolithic run equals the exact answer to 1e-6")
check(all(within(o, 0.8, 1.3) for o in cp["window_orders"]), f"coupled: window orders {cp['window_orders']} in [0.8, 1.3]")
for acc in {r["acceleration"] for r in cp["tolerances"]}:
    e = [r["error"] for r in cp["tolerances"] if r["acceleration"] == acc]
    check(all(a > b for a, b in zip(e, e[1:])), f"coupled {acc}: iteration error falls with the tolerance {e}")
stag = {r["added_mass"]: r for r in cp["schemes"] if r["scheme"] == "staggered"}
check(stag[0.1]["finite"] and stag[0.1]["error"] < 0.01, "coupled: staggered stable and accurate at m_a/m_s = 0.1")
check(not stag[5.0]["finite"], "coupled: staggered unstable at m_a/m_s = 5")

if failures:
    sys.exit(f"{len(failures)} check(s) failed:\n  " + "\n  ".join(failures))
print("all checks passed")
