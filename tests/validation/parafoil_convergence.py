#!/usr/bin/env python3
"""Structure resolution study of the Kalro-Tezduyar-like parafoil (cases/structure/parafoil-kt-inflation).

Runs the case at three structure resolutions (chordwise points x span divisions per cell, the element size
shrinking by a constant ratio), and checks what must converge:
  - the area-weighted mean principal stress of the skin, and the stress resultant at mid-cell: the changes
    between levels shrink (observed order > 0), the Richardson estimate of the limit is reported;
  - the membrane's normal equilibrium at mid-cell (Young-Laplace, laplace probe): (N:b)/p approaches 1.
The largest principal stress is reported too but not required to converge: the suspension lines end at
single nodes, point forces on a membrane whose stress grows like F/(2 pi r t) towards the point, so the
largest element stress grows as the elements next to an attachment shrink (docs/VALIDATION.md).

Usage: parafoil_convergence.py FSI_EXECUTABLE OUT_DIR [--table FILE.md]
Exit 0 when every check passes, 1 otherwise, 2 on bad usage.
"""
import json
import math
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASE = ROOT / "cases" / "structure" / "parafoil-kt-inflation" / "scene.yaml"
# (chordwise points, span divisions per cell): h shrinks by about 1.5 per level.
LEVELS = [(20, 4), (30, 6), (45, 9)]
# The mid-cell node of the centre cell's upper skin at x/c = 0.45 (design shape, bulge 0.25), 3 rings.
AT = "nodes: {nearest: [0.44, 0.193, 0.17], among: wing/upper}, triangles: wing/upper, rings: 3"
PROBES = {
    "bulge_ratio": "{type: laplace, %s, quantity: ratio}" % AT,
    "bulge_tension": "{type: laplace, %s, quantity: tension, direction: [0, 1, 0]}" % AT,
}


def run(fsi, out, chordwise, span):
    d = out / f"c{chordwise}_s{span}"
    cmd = [fsi, "run", str(CASE), "--out", str(d), "--quiet",
           "--set", f"meshes.wing.generator.chordwise_points={chordwise}",
           "--set", f"meshes.wing.generator.span_divisions={span}", "--set", "output.interval=0"]
    for name, spec in PROBES.items():
        cmd += ["--set", f"probes.{name}={spec}"]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        print(r.stdout[-3000:])
        raise SystemExit(f"FAIL: {' '.join(cmd)} exited {r.returncode}")
    s = json.loads((d / "summary.json").read_text())
    p = s["probes"]
    p["triangles"] = s["stats"]["membrane_elements"]
    p["wall"] = s["stats"].get("wall_seconds", float("nan"))
    return p


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    fsi, out = sys.argv[1], pathlib.Path(sys.argv[2])
    table = pathlib.Path(sys.argv[4]) if len(sys.argv) > 4 and sys.argv[3] == "--table" else None
    out.mkdir(parents=True, exist_ok=True)
    rows = [run(fsi, out, c, s) for c, s in LEVELS]
    keys = ["skin_stress_mean", "bulge_tension", "bulge_ratio", "skin_stress_max"]
    lines = ["| chordwise × span div. | triangles | mean principal stress [Pa] | mid-cell spanwise N [N/m] "
             "| (N:b)/p mid-cell | max principal stress [Pa] |",
             "|---|---|---|---|---|---|"]
    for (c, s), r in zip(LEVELS, rows):
        lines.append(f"| {c} × {s} | {r['triangles']} | {r['skin_stress_mean']:.4g} | {r['bulge_tension']:.4g} "
                     f"| {r['bulge_ratio']:.4f} | {r['skin_stress_max']:.4g} |")
    print("\n".join(lines))
    failures = 0
    for k in ["skin_stress_mean", "bulge_tension"]:
        a, b, c = (r[k] for r in rows)
        d1, d2 = abs(b - a), abs(c - b)
        ok = d2 < d1
        order = math.log(d1 / d2) / math.log(1.5) if d2 > 0 and d1 > 0 else float("inf")
        limit = c + (c - b) / (1.5 ** order - 1) if math.isfinite(order) and order > 0 else c
        print(f"{k}: changes {d1:.4g} -> {d2:.4g}, observed order {order:.2f}, Richardson limit {limit:.4g}"
              f"  {'ok' if ok else 'FAIL (not converging)'}")
        lines.append(f"\n{k}: changes between levels {d1:.4g} → {d2:.4g}, observed order {order:.2f}, "
                     f"Richardson estimate of the limit {limit:.4g}")
        failures += 0 if ok else 1
    e = [abs(r["bulge_ratio"] - 1) for r in rows]
    ok = e[2] < e[0]
    print(f"laplace (N:b)/p - 1 at mid-cell: {e[0]:.3g}, {e[1]:.3g}, {e[2]:.3g}  {'ok' if ok else 'FAIL'}")
    failures += 0 if ok else 1
    if table:
        table.write_text("\n".join(lines) + "\n")
    print("all checks passed" if failures == 0 else f"{failures} check(s) failed")
    return 0 if failures == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
