#!/usr/bin/python3
"""Writes a coupled scaling case for issue 16: a flat membrane interface of about N fluid points.

Usage: make_case.py N RANKS CASE_DIR [--windows W] [--projection P] [--threads T]

The fluid is a thin box x, y in [0, 1], z in [0, 0.1]: n x n x 2 cells with n = round(sqrt(N)) - 1, so the
floor z = 0 -- the coupled patch `membrane` -- has (n + 1)^2 points; inlet x = 0, outlet x = 1, slip sides
and top, a uniform stream of 1 m/s, laminar (nu = 1e-3). Two cells across the thickness keep the fluid's
cost per interface point small, which is the point of the case: it is the adapter and the master-rank
structure that are measured. The step is Courant 0.5 on the patch's cells (dt = 0.5 dx / U), so the
structure's subcycles per window stay about the same at every N.

The structure is the same film as cases/coupled/inflated-patch-3d (E t = 5e4 N/m, clamped edges, 50 Pa
cushion) on a rectangle generator of m x m squares, pattern cross (2 m^2 + 2 m + 1 nodes, 4 m^2 triangles),
m = round(0.7 n): about as many nodes as the fluid patch has points, and not matching it.

Projection: `auto` unless --projection says otherwise. Threads: the structure's `solver: {threads: T}` on the
master rank (default 1), which it uses while the fluid waits for it (docs/PERFORMANCE.md "Threads").
Coupling: staggered (one fluid solve per window), so every window is one gather, one structure window and
one scatter. RANKS = 1: serial; 2 or 4: system/decomposeParDict splits the patch in 2 (y) or 2 x 2.
The case's Allrun sources the project's case functions (cases/coupled/case-functions.sh).
"""
import argparse
import math
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TEMPLATE = os.path.join(HERE, "template")
U = 1.0
HEIGHT = 0.1
LAYERS = 2


def positive_int(text, what, low, high):
    try:
        v = int(float(text))
    except ValueError:
        sys.exit(f"make_case.py: {what} must be a whole number, not '{text}'")
    if v != float(text) or not low <= v <= high:
        sys.exit(f"make_case.py: {what} must be a whole number in [{low}, {high}], got {text}")
    return v


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("N", help="fluid points on the coupled patch, about (100 .. 4e6)")
    ap.add_argument("RANKS", help="1, 2 or 4")
    ap.add_argument("CASE_DIR", help="the case to write (must not exist)")
    ap.add_argument("--windows", default="4", help="coupling windows (1 .. 100, default 4)")
    ap.add_argument("--projection", default="auto", choices=["auto", "consistent", "dual", "lumped"],
                    help="the adapter's projection option (default auto: dual above 5000 fluid points, the "
                    "variant docs/PERFORMANCE.md recommends on large interfaces; the adapter's own default is "
                    "consistent)")
    ap.add_argument("--threads", default="1", help="the structure's OpenMP threads on the master rank (1 .. 64)")
    a = ap.parse_args()
    N = positive_int(a.N, "N", 100, 4_000_000)
    ranks = positive_int(a.RANKS, "RANKS", 1, 4)
    if ranks == 3:
        sys.exit("make_case.py: RANKS must be 1, 2 or 4, got 3")
    windows = positive_int(a.windows, "--windows", 1, 100)
    threads = positive_int(a.threads, "--threads", 1, 64)
    if os.path.exists(a.CASE_DIR):
        sys.exit(f"make_case.py: {a.CASE_DIR} exists; remove it or choose another folder")

    n = max(4, round(math.sqrt(N)) - 1)
    m = max(2, round(0.7 * n))
    dx = 1.0 / n
    dt = 0.5 * dx / U
    shutil.copytree(TEMPLATE, a.CASE_DIR)
    case = a.CASE_DIR
    # Numerics and fluid properties: those of cases/coupled/inflated-patch-3d, not a copy kept here.
    patch3d = os.path.join(HERE, "..", "..", "cases", "coupled", "inflated-patch-3d")
    for rel in ("system/fvSchemes", "system/fvSolution", "constant/transportProperties",
                "constant/turbulenceProperties"):
        shutil.copy(os.path.join(patch3d, rel), os.path.join(case, rel))

    def write(rel, text):
        with open(os.path.join(case, rel), "w") as f:
            f.write(text)

    write("system/blockMeshDict", f"""FoamFile {{ version 2.0; format ascii; class dictionary; object blockMeshDict; }}
// Written by bench/adapter-scale/make_case.py: {n} x {n} x {LAYERS} cells, {(n + 1) ** 2} points on `membrane`.
convertToMeters 1;
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 {HEIGHT}) (1 0 {HEIGHT}) (1 1 {HEIGHT}) (0 1 {HEIGHT}));
blocks (hex (0 1 2 3 4 5 6 7) ({n} {n} {LAYERS}) simpleGrading (1 1 1));
boundary
(
  inlet {{ type patch; faces ((0 4 7 3)); }}
  outlet {{ type patch; faces ((1 2 6 5)); }}
  membrane {{ type wall; faces ((0 3 2 1)); }}
  sides {{ type wall; faces ((0 1 5 4) (3 7 6 2)); }}
  top {{ type wall; faces ((4 5 6 7)); }}
);
""")
    end = windows * dt
    write("system/controlDict.values", f"""// Written by bench/adapter-scale/make_case.py (N = {N}, {ranks} rank(s), {windows} windows).
deltaT {dt:.10g};
endTime {end:.10g};
writeInterval {windows};
projection {a.projection};
""")
    write("structure.yaml", f"""title: adapter scaling case, {(n + 1) ** 2} fluid points, {m} x {m} cross squares
# Written by bench/adapter-scale/make_case.py. The film of cases/coupled/inflated-patch-3d.
materials:
  film: {{type: membrane, young: 5.0e7, poisson: 0.3, thickness: 1.0e-3, density: 1000}}
meshes:
  patch:
    generator: {{type: rectangle, size: [1, 1], divisions: [{m}, {m}], center: [0.5, 0.5, 0], pattern: cross}}
    material: film
constraints:
  - {{nodes: patch/boundary, fix: all}}
effects:
  pressure: {{triangles: patch, value: 50, function: {{type: smooth_step, duration: 0.2}}}}
  mass_damping: {{alpha: 10}}
coupling: {{interface: patch}}
solver: {{threads: {threads}}}
output:
  fields: [displacement]
""")
    split = {1: "(1 1 1)", 2: "(1 2 1)", 4: "(2 2 1)"}[ranks]
    write("system/decomposeParDict", f"""FoamFile {{ version 2.0; format ascii; class dictionary; object decomposeParDict; }}
// Written by bench/adapter-scale/make_case.py: the cut(s) run through the membrane patch.
numberOfSubdomains {ranks};
method simple;
coeffs {{ n {split}; }}
""")
    print(f"{case}: {n} x {n} x {LAYERS} cells, {(n + 1) ** 2} fluid points, structure {m} x {m} cross "
          f"({2 * m * m + 2 * m + 1} nodes, {4 * m * m} triangles), dt {dt:.4g} s, {windows} windows, {ranks} rank(s), {threads} structure thread(s)")


if __name__ == "__main__":
    main()
