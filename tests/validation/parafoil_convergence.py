#!/usr/bin/env python3
"""Structure resolution study of the Kalro-Tezduyar-like parafoil (cases/structure/parafoil-kt-inflation).

Runs the case at three structure resolutions (chordwise points x span divisions per cell, the element size
shrinking by 1.5 per level) and checks that the canopy's global answers converge: the changes between levels
shrink for the trim (chord pitch), the anchor force and moment, the enclosed volume and the largest line
tension. Reported, not checked (docs/VALIDATION.md explains why): the area-weighted mean and the largest
principal skin stress, the spanwise resultant and the Young-Laplace ratio (N:b)/p at mid-cell. The skin is
partly wrinkled (tension fields as wide as the elements, so stresses move with the mesh) and the largest
stresses sit where lines end at single nodes or where ribs meet the leading edge (point loads on a
membrane: singular), so element stresses do not converge at these resolutions.

Usage: parafoil_convergence.py FSI_EXECUTABLE OUT_DIR [--table FILE.md] [--reuse]
(--reuse: take a level's OUT_DIR/*/summary.json from an earlier run instead of running it again)
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


def run(fsi, out, chordwise, span, reuse):
    d = out / f"c{chordwise}_s{span}"
    cmd = [fsi, "run", str(CASE), "--out", str(d), "--quiet",
           "--set", f"meshes.wing.generator.chordwise_points={chordwise}",
           "--set", f"meshes.wing.generator.span_divisions={span}", "--set", "output.interval=0"]
    for name, spec in PROBES.items():
        cmd += ["--set", f"probes.{name}={spec}"]
    r = None if reuse and (d / "summary.json").exists() else subprocess.run(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r is not None and r.returncode != 0:
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
    args = sys.argv[3:]
    reuse = "--reuse" in args
    table = pathlib.Path(args[args.index("--table") + 1]) if "--table" in args else None
    out.mkdir(parents=True, exist_ok=True)
    rows = [run(fsi, out, c, s, reuse) for c, s in LEVELS]
    lines = ["| chordwise × span div. | triangles | pitch [°] | anchor F_x [N] | anchor M_y [N·m] | volume [m³] "
             "| max line T [N] | mean stress [MPa] | max skin stress [MPa] | mid-cell N [N/m] | (N:b)/p | wall [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (c, s), r in zip(LEVELS, rows):
        lines.append(f"| {c} × {s} | {r['triangles']} | {r['chord_pitch_angle']:.4f} | {r['anchor_force_x']:.4f} "
                     f"| {r['anchor_moment_y']:.4f} | {r['enclosed_volume']:.5f} | {r['line_tension_max']:.4f} "
                     f"| {r['skin_stress_mean'] / 1e6:.4f} | {r['skin_stress_max'] / 1e6:.3f} "
                     f"| {r['bulge_tension']:.3f} | {r['bulge_ratio']:.3f} | {r['wall']:.0f} |")
    print("\n".join(lines))
    failures = 0
    for k in ["chord_pitch_angle", "anchor_force_x", "anchor_moment_y", "enclosed_volume", "line_tension_max"]:
        a, b, c = (r[k] for r in rows)
        d1, d2 = abs(b - a), abs(c - b)
        ok = d2 < d1
        order = math.log(d1 / d2) / math.log(1.5) if d2 > 0 and d1 > 0 else float("inf")
        limit = c + (c - b) / (1.5 ** order - 1) if math.isfinite(order) and order > 0 else c
        msg = (f"{k}: changes {d1:.4g} -> {d2:.4g}, observed order {order:.2f}, Richardson limit {limit:.6g}")
        print(f"{msg}  {'ok' if ok else 'FAIL (not converging)'}")
        lines.append(f"\n{msg}")
        failures += 0 if ok else 1
    if table:
        table.write_text("\n".join(lines) + "\n")
    print("all checks passed" if failures == 0 else f"{failures} check(s) failed")
    return 0 if failures == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
