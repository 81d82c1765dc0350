#!/usr/bin/env python3
"""Canopy design study (issue 33, after rung 2c): which cut of the cells and how many cells keep the inflated
ram-air canopy a wing — its planform, the thickness of its cells and the spacing of its ribs — before any
flow is computed on it.

Each variant is the main job's canopy (cases/coupled/ramair-kt/structure.yaml: span 3 m, chord 1 m, NACA
4415, R/b = 1, the same lines and rig) with the generator's `cells`, `bulge` (the cut) and `ribs` overridden,
inflated to a still state by damped explicit dynamics (2 s, the main job's damping) under the ram pressure q inside and a section's Cp outside
(studies/wing/canopy_design_scene.yaml). Measured from the structure's own nodes (the generator builds
each span station's section rotated by the arc angle s/R; the nodes are found by that angle):

  planform     the upper skin projected on the x-y plane, over the design's flat-panel planform
  t/c          at every station, the greatest distance between upper and lower skin normal to the deformed
               chord, in the station's own arc plane, over the deformed chord (design: 15 % at the ribs; at
               mid-cell 15 % + the cut's two sagittas)
  rib spacing  the distance between neighbouring ribs' crests (the section's highest point) over the design's
  tip draw     how far the tip's trailing edge moved inboard (m)

Why this matters (derivation in docs/AERODYNAMICS.md, "Canopy design"): cut through the middle of a cell, the
inside pressure pushes the two halves apart with p h per unit chord (h the cell's thickness there) and the two
skins pull them together with 2 T = 2 p r (r the cloth's spanwise radius). A cell is in spanwise balance on its
own only when r = h / 2 — when its cloth is a circle's arc as wide as the cell is thick; wider cells are held
open by the lines' spread and the arc's hoop tension, or they draw the ribs together. Cells as wide as the main
job's (0.375 m against 0.15 m of rib) therefore need that outside support everywhere along the chord.

Usage: canopy_design.py [--out DIR] [--collect]   (runs every variant, then writes docs/data/canopy_design.json
and docs/img/canopy_design.png; --collect only re-reads finished runs)
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCENE = os.path.join(HERE, "canopy_design_scene.yaml")
FSI = os.path.join(ROOT, "build", "bin", "fsi")
SPAN, R_ARC, DIVISIONS = 3.0, 3.0, 2

# name: (cells, bulge, ribs)
VARIANTS = {
    "c8_b25": (8, 0.25, "all"),
    "c8_b10": (8, 0.10, "all"),
    "c8_b05": (8, 0.05, "all"),
    "c16_b25": (16, 0.25, "all"),
    "c16_b10": (16, 0.10, "all"),
    "c16_b10_alt": (16, 0.10, "alternate"),
}
# measured here against the static state of dynamic relaxation (c8_b25): the same to ...


def run(name, out):
    cells, bulge, ribs = VARIANTS[name]
    d = os.path.join(out, name)
    cmd = [FSI, "run", SCENE, "-o", d, "--quiet", "--set", f"meshes.wing.generator.cells={cells}",
           "--set", f"meshes.wing.generator.bulge={bulge}", "--set", f"meshes.wing.generator.ribs={ribs}"]
    t = time.time()
    subprocess.run(cmd, check=True)
    return d, time.time() - t


def self_supported_cell(width, bulge, thickness):
    """The closed form of a cell held by its own ribs only (no spanwise pull from lines or arc): the cloth of the
    cut (a circular arc of sagitta bulge * width over the chord `width`, length l) takes the shape in which the
    cut's two halves balance, p h = 2 p r: a circle's arc of radius r = h / 2 with h = thickness + 2 sagitta,
    i.e. r cos(theta) = thickness / 2 with l = 2 r theta. Returns the rib spacing over the design width and the
    cell's thickness at its middle (m); a cut already that full (r <= h / 2) keeps the design width."""
    s = bulge * width
    if s <= 0:
        return 0.0, thickness  # flat cloth: no circle of finite radius spans it; the ribs close up
    rad = (width ** 2 / 4 + s ** 2) / (2 * s)
    length = 2 * rad * math.asin(width / (2 * rad))
    if rad <= thickness / 2 + s:
        return 1.0, thickness + 2 * s
    lo, hi = 1e-9, math.pi / 2  # l cos(theta) / (2 theta) falls from +inf to 0 on (0, pi/2]
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if length * math.cos(mid) / (2 * mid) > thickness / 2 else (lo, mid)
    theta = 0.5 * (lo + hi)
    r = length / (2 * theta)
    return 2 * r * math.sin(theta) / width, 2 * r


def measure(d, cells):
    """The shape's numbers from the first and last frames. Nodes are found by their design position (the
    structure renumbers them): the generator places a section point at arc angle phi on the circle of radius
    R + Yr about (y, z) = (0, -R), so every design node has phi = atan2(y, z + R) exactly and the section's own
    'up' coordinate Yr = |(y, z + R)| - R."""
    with h5py.File(os.path.join(d, "results.h5"), "r") as f:
        steps = sorted(f["steps"].values(), key=lambda g: float(g.attrs["time"]))
        x = steps[-1]["coordinates"][()]
        max_speed = float(np.linalg.norm(steps[-1]["velocity"][()], axis=1).max())
        x0 = steps[0]["coordinates"][()] - steps[0]["displacement"][()]
        tris = f["mesh/triangles"][()]
    s = json.load(open(os.path.join(d, "summary.json")))
    phi_all = np.arctan2(x0[:, 1], x0[:, 2] + R_ARC)
    in_tri = np.unique(tris)
    key = np.round(phi_all[in_tri], 9)
    phis = np.unique(key)
    stations = cells * DIVISIONS + 1
    if len(phis) != stations:
        raise SystemExit(f"{d}: {len(phis)} arc stations among the triangles' nodes, expected {stations}")
    members = [in_tri[key == p] for p in phis]
    tc, tc0, alpha, crest = [], [], [], []
    for phi, idx in zip(phis, members):
        up = np.array([0.0, math.sin(phi), math.cos(phi)])
        le, te = idx[np.argmin(x0[idx, 0])], idx[np.argmax(x0[idx, 0])]
        crest.append(idx[np.argmax(x0[idx] @ up)])
        out = []
        for pts in (x, x0):
            p = np.stack([pts[idx, 0], pts[idx] @ up], axis=1)  # (x, along the station's up) in its arc plane
            a, b = np.array([pts[le, 0], pts[le] @ up]), np.array([pts[te, 0], pts[te] @ up])
            chord = float(np.linalg.norm(b - a))
            u = (b - a) / chord
            sc, h = (p - a) @ u, (p - a) @ np.array([-u[1], u[0]])
            edges = np.linspace(0, chord, 41)
            thick = max((h[(sc >= lo) & (sc < hi)].ptp() for lo, hi in zip(edges[:-1], edges[1:])
                         if ((sc >= lo) & (sc < hi)).sum() >= 2), default=0.0)
            out.append((thick / chord, math.degrees(math.atan2(a[1] - b[1], b[0] - a[0]))))
        tc.append(out[0][0]), tc0.append(out[1][0]), alpha.append(out[0][1])
    width = SPAN / cells
    spacing = [float(np.linalg.norm(x[crest[j + DIVISIONS]] - x[crest[j]]) / np.linalg.norm(x0[crest[j + DIVISIONS]] - x0[crest[j]]))
               for j in range(0, stations - 1, DIVISIONS)]
    # planform: half the closed skin's projected area on x-y (triangles across two stations: no rib)
    skin = np.array([t for t in tris if len(set(np.round(phi_all[t], 9))) > 1])

    def area(pts):
        a, b, c = pts[skin[:, 0], :2], pts[skin[:, 1], :2], pts[skin[:, 2], :2]
        return 0.5 * float(0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])).sum())

    tip = members[-1]
    te_tip = tip[np.argmax(x0[tip, 0])]
    return {
        "cells": cells, "cell_width_m": width,
        "kinetic_energy_J": s["stats"].get("kinetic_energy"), "max_speed_m_s": max_speed,
        "skin_folds": s["probes"]["skin_folds"],
        "planform_over_design": area(x) / area(x0),
        "station_span_m": [float(R_ARC * p) for p in phis],
        "tc": tc, "tc_design": tc0, "chord_angle_deg": alpha,
        "rib_spacing_over_design": spacing,
        "tip_te_inboard_m": float(abs(x0[te_tip, 1]) - abs(x[te_tip, 1])),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "studies-out", "design"))
    ap.add_argument("--collect", action="store_true")
    a = ap.parse_args()
    rows = {}
    for name, (cells, bulge, ribs) in VARIANTS.items():
        d = os.path.join(a.out, name)
        secs = None
        if not a.collect:
            d, secs = run(name, a.out)
        m = measure(d, cells)
        m.update({"bulge": bulge, "ribs": ribs, "wall_seconds": secs})
        # the centre cell (least held by the lines' spread) against the self-supported closed form, at the
        # section's greatest thickness (NACA 4415: 0.15 c) where the generator's bulge is full
        sp, h = self_supported_cell(SPAN / cells, bulge, 0.15)
        c_mid = len(m["tc"]) // 2 + (DIVISIONS // 2 if cells % 2 == 0 else 0)
        m["centre_cell"] = {"rib_spacing": m["rib_spacing_over_design"][cells // 2], "tc": m["tc"][c_mid],
                            "closed_form_rib_spacing": sp, "closed_form_tc": h}
        rows[name] = m
        mid = [m["tc"][j] for j in range(1, len(m["tc"]), DIVISIONS)]
        print(f"{name:12s} planform {m['planform_over_design']:.3f}  mid-cell t/c {min(mid):.3f}-{max(mid):.3f} "
              f"(design {m['tc_design'][1]:.3f})  rib spacing {min(m['rib_spacing_over_design']):.3f}-"
              f"{max(m['rib_spacing_over_design']):.3f}  tip TE inboard {m['tip_te_inboard_m']*100:.1f} cm  "
              f"folds {m['skin_folds']:.0f}  max speed {m['max_speed_m_s']:.3f} m/s")
        cc = m["centre_cell"]
        print(f"{'':12s} centre cell: rib spacing {cc['rib_spacing']:.3f} (closed form {cc['closed_form_rib_spacing']:.3f}), "
              f"t/c {cc['tc']:.3f} (closed form {cc['closed_form_tc']:.3f})")
    doc = {"what": "static inflation of the main job's canopy with the cut (bulge), cell count and line ribs "
                   "varied: planform, cell thickness, rib spacing (studies/wing/canopy_design.py)",
           "command": "/usr/bin/python3 studies/wing/canopy_design.py",
           "scene": "studies/wing/canopy_design_scene.yaml", "date": time.strftime("%Y-%m-%d"),
           "variants": rows}
    json.dump(doc, open(os.path.join(ROOT, "docs", "data", "canopy_design.json"), "w"), indent=1)
    plot(rows, os.path.join(ROOT, "docs", "img", "canopy_design.png"))


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for i, (name, m) in enumerate(rows.items()):
        ys = np.array(m["station_span_m"])
        col = f"C{i}"
        ax[0].plot(ys[1::DIVISIONS], m["tc"][1::DIVISIONS], "-o", ms=3, color=col,
                   label=f"{name}: planform {m['planform_over_design']:.2f} of the design's")
        ax[0].axhline(m["centre_cell"]["closed_form_tc"], color=col, lw=0.8, ls="--")
        ribs = ys[::DIVISIONS]
        ax[1].plot(0.5 * (ribs[1:] + ribs[:-1]), m["rib_spacing_over_design"], "-o", ms=3, color=col, label=name)
        ax[1].plot([0], [m["centre_cell"]["closed_form_rib_spacing"]], "x", ms=9, color=col)
    ax[0].axhline(0.15, color="k", lw=0.8, ls=":")
    ax[0].set_xlabel("span station s (m, along the arc)")
    ax[0].set_ylabel("t/c of the inflated mid-cell section")
    ax[0].set_title("mid-cell thickness (ribs: 0.15); dashed: self-supported cell")
    ax[0].legend(fontsize=7)
    ax[1].axhline(1.0, color="k", lw=0.8, ls=":")
    ax[1].set_xlabel("cell centre s (m)")
    ax[1].set_ylabel("rib spacing / design (at the crests)")
    ax[1].set_title("ribs drawn together; x: self-supported cell")
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    sys.exit(main())
