#!/usr/bin/python3
"""Rung 2 of the fluid validation ladder (issue 33, docs/AERODYNAMICS.md): the rigid ram-air wing of
cases/coupled/ramair-kt in steady symmetric flow, CL, CD and Cm against the angle of attack, on several meshes,
for the wing without arc, with the arc, and with the bulged cells the coupled canopy flies.

Every point is a copy of the case (its tracked files) in OUT/<variant>/<level>/a<alpha>, run by its own Allrun
with a settings file written here: kOmegaSST at Re 1e6 as rans.settings, `solver simple` (steady: simpleFoam),
`half_domain yes` (the half y >= 0 with a symmetry plane), `resolution LEVEL`, `angle` = alpha - incidence.
The structure.yaml of a variant changes only the generator's arc_radius (0: no arc) and the fluid's skin its
bulge (stl_bulge). Each finished point is appended to the JSON at once, so a cut-off study keeps what it did.

  /usr/bin/python3 studies/wing/wing_polar.py --variants flat,arc,bulged --levels coarse,medium \\
      --alpha=-2,2,6,10 [--out DIR] [--iterations N] [--json docs/data/wing_polar.json] [--collect]
  /usr/bin/python3 studies/wing/wing_polar.py --plot [--json ...]      (docs/img/wing_polar.png)

The reference: Helmbold's low-aspect-ratio lifting line with a0 = 2 pi per radian, on the aspect ratio of the
projected planform, times the arc factor (1 + sin(2 eps)/(2 eps))/2 with eps the half-arc angle b/(2R) for the
arced variants (ram-air-data.md). The slope is fitted, so no zero-lift angle enters the comparison; the plot's
estimate lines start from thin-aerofoil theory's -4.15 deg (rung 1 measured -3.72 deg for NACA 4415).
"""
import argparse
import datetime
import json
import math
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
sys.path.insert(0, str(ROOT / "studies/common"))
from case_variants import structure_with  # noqa: E402 (the case's structure.yaml with values changed)
sys.path.insert(0, str(ROOT / "studies/wing"))
from section_geometry import shape_report  # noqa: E402
CASE = ROOT / "cases/coupled/ramair-kt"
ENV = ROOT / "build/share/fsi/fsi-env.sh"
INCIDENCE = 6.0  # structure.yaml's generator incidence [deg]: the centre section's chord to the x axis

# variant: (generator changes, stl_bulge, what it is)
VARIANTS = {
    "flat": ({"arc_radius": 0}, 0.0, "no arc (flat span), flat panels between the ribs"),
    "arc": ({}, 0.0, "the arc R/b = 1, flat panels"),
    "bulged": ({}, 0.25, "the arc R/b = 1, the cells bulged by a quarter of their width (the coupled canopy's skin)"),
    "bulged16": ({"cells": 16}, 0.25, "the arc R/b = 1, 16 cells (half as wide) bulged by a quarter of their width: "
                                      "the same bulge ratio, half the bulge"),
    "bulged10": ({}, 0.10, "the arc R/b = 1, the cells bulged by a tenth of their width (the cloth 2.6 % wider than the "
                           "rib spacing, against 15.9 % at a quarter): how much of the lift the bulge costs"),
    "trimmed": ({}, -1.0, "the canopy as a coupled run left it (--deformed RUN: its structure/ folder), the design's "
                          "skin moved to the run's last frame; alpha from its centre rib's chord"),
    "trimmed_own": ({}, -1.0, "the trimmed canopy (as `trimmed`) on the structure's own facets (stl_chordwise_points "
                              "and stl_span_divisions 0: 20 chordwise points, 2 span divisions per cell), the skin "
                              "the coupled run's fluid mesh is snapped to"),
    "inflated16": ({"cells": 16, "rigging_angle": 6}, 0.25, "16 cells cut at a quarter of their width (the cut whose cloth is a circle "
                                        "as wide as the cell is thick: studies/wing/canopy_design.py), inflated "
                                        "(--deformed RUN: the design study's c16_b25 run, rigged at 6 deg as it), alpha from its centre rib"),
}
# variants whose skin is a run's last frame (--deformed)
DEFORMED = {"trimmed", "trimmed_own", "inflated16"}
# variants whose fluid skin is the structure's own sampling (the coupled run's), not the finer 60 x 6
OWN_SAMPLING = {"trimmed_own"}
# the skin's sections the report states (y of the centre rib, the centre cell's middle, a tip cell's middle)
STATIONS = {"centre_rib": 0.0, "centre_cell": 0.1875, "tip_cell": 1.3}

SETTINGS = """# written by studies/wing/wing_polar.py: rung 2, the rigid wing in steady symmetric flow
speed 15
nu 1.5e-5
rho 1.225
model kOmegaSST
turbulence_intensity 0.005
viscosity_ratio 10
mesh_motion none
half_domain yes
"""


def tracked_case_files():
    out = subprocess.run(["git", "-C", str(ROOT), "ls-files", "cases/coupled/ramair-kt"], capture_output=True,
                         text=True, check=True).stdout.split()
    if not out:
        sys.exit("wing_polar: no tracked files in cases/coupled/ramair-kt")
    return [ROOT / f for f in out]


def y_plus(case):
    """min, max and area-weighted mean y+ on the wing at the last iteration (postProcessing/yPlus)."""
    base = Path(case) / "postProcessing" / "yPlus"
    files = sorted(base.glob("*/yPlus.dat"))
    if not files:
        return None
    last = None
    for line in files[-1].read_text().splitlines():
        w = line.split()
        if w and not line.startswith("#") and len(w) >= 5 and w[1] == "wing":
            last = w
    return None if last is None else {"min": float(last[2]), "max": float(last[3]), "mean": float(last[4])}


def layer_coverage(case):
    """prism_layers: snappyHexMesh's overall layer thickness on the wing as a percentage of the asked-for one
    (its last table in log.snappyHexMesh); None without layers."""
    text = (Path(case) / "log.snappyHexMesh").read_text(errors="replace")
    m = re.findall(r"^wing\s+\d+\s+([\d.]+)\s+([\d.eE+-]+)\s+([\d.]+)\s*$", text, re.M)
    return float(m[-1][2]) if m and "Layers added" in text else None


def residuals(case, log="log.simpleFoam"):
    """The last iteration's initial residuals of Ux, p, k, omega and whether SIMPLE met its residualControl."""
    text = (Path(case) / log).read_text(errors="replace")
    res = {}
    for m in re.finditer(r"Solving for (\w+), Initial residual = ([\d.eE+-]+)", text[-20000:]):
        res[m.group(1)] = float(m.group(2))
    return res, "SIMPLE solution converged" in text


def case_dir(out, variant, level, alpha, solver, wall="functions"):
    return (Path(out) / variant / level / (f"a{alpha:g}" + ("" if solver == "simple" else "-pimple")
                                          + ("" if wall == "functions" else f"-{wall}")))


def symmetric_source(deformed, folder):
    """A copy of the run's last frame (results.h5: its mesh and that frame only) with the displacement made
    mirror-symmetric about y = 0 (the mean of each node's and its mirror node's, the y component odd): the half
    domain with a symmetry plane needs a symmetric skin, and a coupled run's canopy is symmetric only to the
    unsteady flow's asymmetry (reported as the largest change)."""
    import h5py
    import numpy as np
    src = Path(deformed)
    src = src / "results.h5" if src.is_dir() else src
    dst = folder / "source" / "results.h5"
    dst.parent.mkdir(parents=True, exist_ok=True)
    with h5py.File(src, "r") as f, h5py.File(dst, "w") as g:
        last = sorted(f["steps"])[-1]
        for k, v in f.attrs.items():
            g.attrs[k] = v
        f.copy("mesh", g)
        frame = g.create_group(f"steps/{last}")
        for k, v in f[f"steps/{last}"].attrs.items():
            frame.attrs[k] = v
        x, u = f[f"steps/{last}/coordinates"][()], f[f"steps/{last}/displacement"][()]
        ref = x - u
        key = {tuple(np.round(r, 6)): i for i, r in enumerate(ref)}
        mirror = np.array([key.get(tuple(np.round(r * [1, -1, 1], 6)), -1) for r in ref])
        if (mirror < 0).any():
            raise SystemExit(f"wing_polar: {src}: {int((mirror < 0).sum())} nodes have no mirror node about y = 0")
        us = 0.5 * (u + u[mirror] * [1, -1, 1])
        frame["displacement"] = us
        frame["coordinates"] = ref + us
    return dst, float(np.abs(us - u).max())


def shape(out, variant, env, deformed=None):
    """The variant's fluid skin, made once in OUT/<variant>/shape with the case's fsi generate arguments (the
    design's, or moved to the --deformed run's last frame), and its sections (section_geometry): what its angles
    of attack are measured from."""
    folder = Path(out) / variant / "shape"
    report = folder / "shape.json"
    if report.exists():
        return json.loads(report.read_text())
    folder.mkdir(parents=True, exist_ok=True)
    changes, bulge, _ = VARIANTS[variant]
    (folder / "structure.yaml").write_text(structure_with((CASE / "structure.yaml").read_text(), changes,
                                                          f"{CASE}/structure.yaml"))
    args = [] if variant in OWN_SAMPLING else ["--set", "meshes.wing.generator.chordwise_points=60", "--set",
                                               "meshes.wing.generator.span_divisions=6"]
    if bulge >= 0:
        args += ["--set", f"meshes.wing.generator.bulge={bulge:g}"]
    rep = {}
    if deformed:
        deformed, rep["symmetrised_by_m"] = symmetric_source(deformed, folder)
    for name, extra in (("design", []), ("skin", ["--deformed", str(deformed)] if deformed else [])):
        cmd = ["bash", "-c", '. "$0" && exec fsi generate structure.yaml --out "$1" "${@:2}"', str(env), name] + args + extra
        subprocess.run(cmd, cwd=folder, check=True, stdout=subprocess.DEVNULL)
        rep[name] = shape_report(folder / name / "wing.stl", STATIONS)
    # alpha of the centre rib: the incidence plus how far the skin's centre rib turned from the design's, both
    # measured the same way (section_geometry)
    rep["incidence_deg"] = INCIDENCE + rep["skin"]["centre_rib"]["chord_angle_deg"] - rep["design"]["centre_rib"]["chord_angle_deg"]
    rep["deformed_from"] = str(deformed) if deformed else None
    rep["stl_deformed"] = str(deformed) if deformed else None
    report.write_text(json.dumps(rep, indent=1) + "\n")
    return rep


def run_point(out, variant, level, alpha, iterations, env, solver="simple", courant=2.0, flow_time=2.0,
              wall="functions", deformed=None):
    changes, bulge, _ = VARIANTS[variant]
    geo = shape(out, variant, env, deformed)
    incidence, deformed = geo["incidence_deg"], geo["stl_deformed"]
    case = case_dir(out, variant, level, alpha, solver, wall)
    if (case / "summary.json").exists():
        return case, 0.0
    if case.exists():
        subprocess.run(["rm", "-rf", str(case)], check=True)
    case.mkdir(parents=True)
    for f in tracked_case_files():
        text = f.read_bytes()
        if f.name == "structure.yaml":
            text = structure_with(text.decode(), changes, f"{CASE}/structure.yaml").encode()
        (case / f.name).write_bytes(text)
        os.chmod(case / f.name, f.stat().st_mode)
    if solver == "simple":
        run = f"solver simple\nsteps {iterations}\n"
    else:
        # time-accurate: Courant `courant` on the finest wing cell, `flow_time` seconds of flow (the mean is taken
        # over the second half); 2 outer correctors per step
        h = 1.0 / 2 ** {"coarse": 5, "medium": 6, "fine": 7, "wake": 5}[level]
        steps = math.ceil(flow_time / (courant * h / 15.0))
        run = f"solver pimple\ncourant {courant:g}\nouter_correctors 2\nsteps {steps}\n"
    (case / "polar.settings").write_text(
        SETTINGS + f"resolution {level}\nangle {alpha - incidence:.6g}   # alpha {alpha:g} deg at the centre chord\n"
        + (f"stl_deformed {deformed}\n" if deformed else "")
        + ("stl_chordwise_points 0\nstl_span_divisions 0\n" if variant in OWN_SAMPLING else "") + f"stl_bulge {bulge:g}\nprism_layers {'yes' if wall == 'layers' else 'no'}\n"
        f"wall_split {2 if wall == 'split' else 0}\n" + (f"wall_layers 3\n" if wall == "layers3" else "") + run)
    t0 = time.time()
    # The environment of the build (--env); the arguments are a list, nothing here passes through a shell but
    # the fixed `source` line (the file's path is its $0).
    cmd = ["bash", "-c", '. "$0" && exec ./Allrun -settings polar.settings', str(env)]
    # the log beside the case (Allrun refuses a folder with log.* files in it)
    with open(case.parent / f"{case.name}.log", "w") as log:
        rc = subprocess.run(cmd, cwd=case, stdout=log, stderr=subprocess.STDOUT).returncode
    if rc != 0:
        print(f"wing_polar: {case} failed (exit {rc}); see {case}.log", file=sys.stderr)
        return None, time.time() - t0
    return case, time.time() - t0


def collect(case, variant, level, alpha, wall_s, solver="simple", wall="functions"):
    s = json.loads((Path(case) / "summary.json").read_text())
    fl, rec = s["flow"], json.loads((Path(case) / "constant/fluidSettings.json").read_text())
    res, converged = residuals(case, "log.simpleFoam" if solver == "simple" else "log.pimpleFoam")
    d = rec["derived"]
    # The mean over the last fifth of the iterations: the answer of a converged run, and for a run whose forces
    # still oscillate (separated flow that a steady solver cannot settle) the mean with its spread as the
    # uncertainty; both the last value and the mean are kept.
    h = fl["history"]
    # steady: the last fifth of the iterations; time-accurate: the second half of the flow time
    tail = max(2, len(h["CL"]) // (5 if solver == "simple" else 2))
    mean = {k: sum(h[k][-tail:]) / tail for k in ("CL", "CD")}
    cm = fl["CmPitch"]
    return {"variant": variant, "level": level, "alpha_deg": alpha, "solver": solver, "wall": wall, "CL": mean["CL"], "CD": mean["CD"],
            "CL_last": fl["CL"], "CD_last": fl["CD"],
            "CL_min_last_fifth": min(h["CL"][-tail:]), "CL_max_last_fifth": max(h["CL"][-tail:]),
            "Cm": cm, "CL_spread_last_fifth": fl["CL_spread_last_fifth"],
            "CD_spread_last_fifth": fl["CD_spread_last_fifth"], "iterations": fl["steps"],
            "residuals": res, "residual_control_met": converged,
            # steady: SIMPLE met its residual control, or the forces stopped moving (0.1 % over the last fifth
            # of the iterations) with the pressure residual below 1e-4
            "converged": (converged or (fl["CL_spread_last_fifth"] < 1e-3 and fl["CD_spread_last_fifth"] < 1e-3
                                        and res.get("p", 1.0) < 1e-4)) if solver == "simple" else None,
            "averaged_over": "last fifth of the iterations" if solver == "simple" else
                             f"second half of {fl['time']:.3g} s of flow ({tail} steps)", "cells": s["mesh"]["cells"],
            "cells_whole_wing": 2 * s["mesh"]["cells"], "y_plus": y_plus(case), "wall_s": round(wall_s, 1),
            "Aref_m2": d["Aref"], "aspect_ratio": d["aspect_ratio"], "span_projected_m": d["span_projected"],
            "wall_cell_m": d["h_wing"], "layer_coverage_percent": layer_coverage(case)}


def store(path, rows):
    data = json.loads(Path(path).read_text()) if Path(path).exists() else {}
    old = data.get("points", [])
    key = lambda r: (r["variant"], r["level"], r["alpha_deg"], r.get("solver", "simple"), r.get("wall", "functions"))
    new = {key(r): r for r in old}
    for r in rows:
        new[key(r)] = r
    data.update({
        "what": "rigid ram-air wing (cases/coupled/ramair-kt's canopy), steady kOmegaSST, Re 1e6, half domain with "
                "a symmetry plane; CL, CD, Cm on the projected planform area of the whole wing (Aref_m2), Cm about "
                "the centre chord's quarter point, pitch up positive",
        "variants": {k: v[2] for k, v in VARIANTS.items()},
        "alpha_is": "the centre section's chord line to the free stream [deg] (incidence 6 + inflow angle)",
        "command": "/usr/bin/python3 studies/wing/wing_polar.py " + " ".join(sys.argv[1:]),
        "machine": f"{platform.node()} ({os.cpu_count()} cores)", "date": datetime.date.today().isoformat(),
        "points": sorted(new.values(), key=lambda r: (r["variant"], r["level"], r.get("solver", "simple"),
                                                      r["alpha_deg"]))})
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(json.dumps(data, indent=1) + "\n")


def helmbold(ar, arc_half_angle):
    a0 = 2 * math.pi
    k = a0 / (math.pi * ar)
    slope = a0 / (math.sqrt(1 + k * k) + k)
    if arc_half_angle > 0:
        e = arc_half_angle
        slope *= 0.5 * (1 + math.sin(2 * e) / (2 * e))
    return slope


def fit_slope(points):
    """Least-squares CL = a (alpha - alpha0) over the points; (a per rad, alpha0 deg)."""
    n = len(points)
    if n < 2:
        return None, None
    xs = [math.radians(p["alpha_deg"]) for p in points]
    ys = [p["CL"] for p in points]
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    a = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return a, math.degrees(mx - my / a)


def plot(path, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = json.loads(Path(path).read_text())
    pts = data["points"]
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.8))
    styles = {"coarse": "o-", "medium": "s--", "fine": "^:"}
    colours = COLOURS
    for v in VARIANTS:
        for lvl, solver, wall in [(lv, so, wa) for lv in styles for so in ("simple", "pimple")
                                  for wa in ("functions", "layers", "split", "layers3")]:
            sel = sorted([p for p in pts if p["variant"] == v and p["level"] == lvl
                          and p.get("solver", "simple") == solver and p.get("wall", "functions") == wall],
                         key=lambda p: p["alpha_deg"])
            if not sel:
                continue
            lab = (f"{v}, {lvl}" + (", time-averaged" if solver == "pimple" else "")
                   + {"layers": ", prism layers", "split": ", wall cells split twice",
                      "layers3": ", 3 layers on the wall cell"}.get(wall, ""))
            a = [p["alpha_deg"] for p in sel]
            # error bars: the range over the last fifth of the iterations where the steady solver did not settle
            lo = [p["CL"] - p.get("CL_min_last_fifth", p["CL"]) for p in sel]
            hi = [p.get("CL_max_last_fifth", p["CL"]) - p["CL"] for p in sel]
            if wall == "layers3" and v not in ("bulged",):
                continue  # the layered rows of the other skins: plot_layers
            col = {"layers": "C2", "layers3": "k"}.get(wall, colours[v])
            fmt = {"split": "D-.", "layers3": "s:"}.get(wall, styles[lvl])
            ax[0].errorbar(a, [p["CL"] for p in sel], yerr=[lo, hi], fmt=fmt, color=col, label=lab,
                           capsize=3, mfc="none" if lvl != "coarse" else None)
            ax[1].plot([p["CD"] for p in sel], [p["CL"] for p in sel], fmt, color=col, label=lab)
            ax[2].plot(a, [p["Cm"] for p in sel], fmt, color=col, label=lab)
    ar = next((p["aspect_ratio"] for p in pts if p["variant"] == "flat"), 3.0)
    alpha0 = data.get("alpha0_section_deg", -4.15)
    al = [-4 + 0.5 * i for i in range(33)]
    for name, eps, c in (("Helmbold, no arc", 0.0, "C0"), ("Helmbold x arc factor", 0.5, "C1")):
        a = helmbold(ar, eps)
        ax[0].plot(al, [a * math.radians(x - alpha0) for x in al], ":", color=c, lw=1, label=f"{name} ({a:.2f}/rad)")
    ax[0].set(xlabel="alpha, centre chord [deg]", ylabel="CL (projected area)", title="lift")
    ax[1].set(xlabel="CD", ylabel="CL", title="drag polar")
    ax[2].set(xlabel="alpha [deg]", ylabel="Cm (quarter chord)", title="pitching moment")
    for x in ax:
        x.grid(alpha=0.3)
    ax[0].legend(fontsize=7)
    fig.suptitle("Rung 2: the rigid ram-air wing, kOmegaSST, Re 1e6, half domain: steady (simpleFoam) or time-averaged "
                 "(pimpleFoam); bars: range over the averaging window; Helmbold lines from alpha0 -4.15 deg "
                 "(studies/wing/wing_polar.py)", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wing_polar: {png}")


COLOURS = {"flat": "C0", "arc": "C1", "bulged": "C3", "bulged16": "C4", "bulged10": "C2", "trimmed": "C5",
           "trimmed_own": "C6", "inflated16": "C9"}


def plot_layers(path, png):
    """Rung 2c: CL and CD against alpha of each skin on the layered wall (3 layers on the wall cell,
    time-averaged), coarse and medium skin, with Helmbold x arc factor."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = json.loads(Path(path).read_text())
    pts = [p for p in data["points"] if p.get("wall") == "layers3" and p.get("solver") == "pimple"]
    fig, ax = plt.subplots(1, 2, figsize=(13, 6.6))
    for v in ("arc", "bulged10", "bulged", "trimmed", "inflated16"):
        for lvl, fmt in (("coarse", "o:"), ("medium", "s-")):
            sel = sorted([p for p in pts if p["variant"] == v and p["level"] == lvl], key=lambda p: p["alpha_deg"])
            if not sel:
                continue
            a = [p["alpha_deg"] for p in sel]
            lo = [p["CL"] - p.get("CL_min_last_fifth", p["CL"]) for p in sel]
            hi = [p.get("CL_max_last_fifth", p["CL"]) - p["CL"] for p in sel]
            lab = {"arc": "flat panels", "bulged10": "cut bulge 0.10", "bulged": "cut bulge 0.25 (the case's design)",
                   "trimmed": "the coupled canopy's trimmed shape",
                   "inflated16": "16 cells cut 0.25, inflated (canopy design study)"}[v] + f", {lvl} skin"
            ax[0].errorbar(a, [p["CL"] for p in sel], yerr=[lo, hi], fmt=fmt, color=COLOURS[v], label=lab, capsize=3,
                           mfc="none" if lvl == "coarse" else None)
            ax[1].plot(a, [p["CD"] for p in sel], fmt, color=COLOURS[v], label=lab, mfc="none" if lvl == "coarse" else None)
    # the trimmed shape on the main job's own wall treatment (wall functions, coarse), and the coupled main job
    for v, mk in (("trimmed", "^"), ("trimmed_own", "v")):
        sel = [p for p in data["points"] if p["variant"] == v and p.get("wall") == "functions" and p["level"] == "coarse"]
        for p in sel:
            lab = "trimmed shape, coarse skin, wall functions" + (" (structure's facets)" if v == "trimmed_own" else "")
            ax[0].plot(p["alpha_deg"], p["CL"], mk, color=COLOURS["trimmed"], ms=8, mfc="none", label=lab)
            ax[1].plot(p["alpha_deg"], p["CD"], mk, color=COLOURS["trimmed"], ms=8, mfc="none", label=lab)
    polar = Path(path).parent / "ramair_polar.json"
    if polar.exists():
        main = [r for r in json.loads(polar.read_text())["rows"] if r["run"] == "s1-nobend"]
        for r in main:
            ax[0].plot(r["alpha_centre_deg"], r["CL_deformed_area"], "*", color="k", ms=12,
                       label="the coupled main job at its trim (moved coarse mesh, wall functions)")
            ax[1].plot(r["alpha_centre_deg"], r["CD_deformed_area"], "*", color="k", ms=12)
    ar = next((p["aspect_ratio"] for p in data["points"] if p["variant"] == "flat"), 3.0)
    al = [-2 + 0.5 * i for i in range(25)]
    a = helmbold(ar, 0.5)
    ax[0].plot(al, [a * math.radians(x + 3.72) for x in al], "--", color="grey", lw=1,
               label=f"Helmbold x arc factor ({a:.2f}/rad, alpha0 -3.72 deg: rung 1's NACA 4415)")
    ax[0].set(xlabel="alpha, centre rib's chord [deg]", ylabel="CL (projected area of the skin)",
              title="lift: 3 prism layers (y+ ~ 75 medium, ~ 140 coarse) unless marked")
    ax[1].set(xlabel="alpha, centre rib's chord [deg]", ylabel="CD", title="drag")
    for x in ax:
        x.grid(alpha=0.3)
    handles, labels = ax[0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7.5, loc="lower center", ncol=3, frameon=False)
    fig.suptitle("Rung 2c and the canopy design: the rigid wing's lift by the shape of its cells, kOmegaSST, Re 1e6, half domain, 3 prism "
                 "layers, time-averaged over 1 s (bars: range) - studies/wing/wing_polar.py --plot-layers", fontsize=9)
    fig.tight_layout(rect=(0, 0.17, 1, 0.97))
    fig.savefig(png, dpi=110)
    print(f"wing_polar: {png}")


def table(path, linear_max=8.0):
    """Markdown rows per variant, level and solver: lift slope and zero-lift angle fitted over alpha <= linear_max,
    the estimate it is compared with, CD at alpha 4 and 8, cells and the cost of a point."""
    data = json.loads(Path(path).read_text())
    pts = data["points"]
    rows = ["| variant | level | solver | wall | cells (half) | points | slope /rad (alpha <= %g) | alpha0 deg | Helmbold%s /rad "
            "| ratio | CL at 4 / 8 deg | CD at 4 / 8 deg | settled | wall s per point |" % (linear_max, " x arc"),
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for v in VARIANTS:
        for lvl in ("coarse", "medium", "fine"):
            for solver, wall in [(so, wa) for so in ("simple", "pimple") for wa in ("functions", "layers", "split", "layers3")]:
                sel = sorted([p for p in pts if p["variant"] == v and p["level"] == lvl
                              and p.get("solver", "simple") == solver and p.get("wall", "functions") == wall],
                             key=lambda p: p["alpha_deg"])
                if not sel:
                    continue
                lin = [p for p in sel if p["alpha_deg"] <= linear_max]
                a, a0 = fit_slope(lin)
                # the half-arc angle b / (2 R) of the arced variants (span 3 m along the arc, R = 3 m)
                eps = 0.0 if v == "flat" else 0.5
                ref = helmbold(sel[0]["aspect_ratio"], eps)
                at = {p["alpha_deg"]: p for p in sel}
                cl = " / ".join(f"{at[x]['CL']:.3f}" if x in at else "-" for x in (4.0, 8.0))
                cd = " / ".join(f"{at[x]['CD']:.4f}" if x in at else "-" for x in (4.0, 8.0))
                settled = sum(1 for p in sel if p.get("converged") or solver == "pimple")
                times = sorted(p["wall_s"] for p in sel if p.get("wall_s")) or [0.0]
                fit = f"{a:.2f} | {a0:.2f} | {ref:.2f} | {a / ref:.2f}" if a is not None else f"- | - | {ref:.2f} | -"
                rows.append(f"| {v} | {lvl} | {solver} | {wall} | {max(p['cells'] for p in sel):,} | {len(sel)} | "
                            f"{fit} | {cl} | {cd} | {settled}/{len(sel)} | {times[len(times) // 2]:.0f} |")
    return "\n".join(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--variants", default="flat,arc,bulged")
    ap.add_argument("--levels", default="coarse")
    ap.add_argument("--alpha", default="-2,2,6,10", help="centre-chord angles of attack [deg]")
    ap.add_argument("--iterations", type=int, default=1500, help="simple: SIMPLE iterations at most")
    ap.add_argument("--solver", choices=("simple", "pimple"), default="simple",
                    help="simple: steady simpleFoam; pimple: time-accurate pimpleFoam, the mean over the second half "
                         "(for flow a steady solver cannot settle)")
    ap.add_argument("--wall", choices=("functions", "layers", "split", "layers3"), default="functions",
                    help="functions: the 3D case's mesh, no prism layers; layers: prism_layers yes (y+ ~ 50); "
                         "split: wall_split 2 (the wall cells split twice, y+ ~ 100); "
                         "layers3: wall_layers 3 (3 layers sized on the wall cell, the coupled run's s1-f3 mesh)")
    ap.add_argument("--courant", type=float, default=2.0, help="pimple: Courant number on the finest wing cell")
    ap.add_argument("--flow-time", type=float, default=2.0, help="pimple: seconds of flow (30 chord passages at 15 m/s)")
    ap.add_argument("--deformed", help="variant trimmed: the structure run whose last frame is the skin (a coupled "
                                       "run's CASE/structure folder, or a results.h5)")
    ap.add_argument("--out", default=str(ROOT / "studies-out/wing"))
    ap.add_argument("--json", default=str(ROOT / "docs/data/wing_polar.json"))
    ap.add_argument("--png", default=str(ROOT / "docs/img/wing_polar.png"))
    ap.add_argument("--env", default=str(ENV), help="the build's or install's share/fsi/fsi-env.sh")
    ap.add_argument("--collect", action="store_true", help="read finished points in OUT, run nothing")
    ap.add_argument("--plot", action="store_true", help="only the plot from the JSON")
    ap.add_argument("--table", action="store_true", help="only the markdown table of slopes from the JSON")
    ap.add_argument("--plot-layers", metavar="PNG", help="only rung 2c's figure (the skins on the layered wall)")
    a = ap.parse_args()
    if a.plot_layers:
        plot_layers(a.json, a.plot_layers)
        return 0
    if a.plot or a.table:
        if a.plot:
            plot(a.json, a.png)
        if a.table:
            print(table(a.json))
        return 0
    variants = a.variants.split(",")
    for v in variants:
        if v not in VARIANTS:
            ap.error(f"--variants: unknown '{v}' (valid: {', '.join(VARIANTS)})")
    if any(v in DEFORMED for v in variants) and not a.deformed:
        ap.error(f"--variants {', '.join(sorted(DEFORMED))} need --deformed RUN (the structure run's folder)")
    if a.deformed:
        a.deformed = str(Path(a.deformed).resolve())
    levels = a.levels.split(",")
    for lvl in levels:
        if lvl not in ("coarse", "medium", "fine", "wake"):
            ap.error(f"--levels: unknown '{lvl}' (valid: coarse, medium, fine, wake)")
    try:
        alphas = [float(x) for x in a.alpha.split(",")]
    except ValueError:
        ap.error(f"--alpha: '{a.alpha}' is not a comma-separated list of numbers")
    failed = 0
    for lvl in levels:
        for v in variants:
            for al in alphas:
                case = case_dir(a.out, v, lvl, al, a.solver, a.wall)
                if a.collect:
                    if not (case / "summary.json").exists():
                        continue
                    wall = 0.0
                else:
                    print(f"wing_polar: {v} {lvl} alpha {al:g} ...", flush=True)
                    case, wall = run_point(a.out, v, lvl, al, a.iterations, a.env, a.solver, a.courant,
                                           a.flow_time, a.wall, a.deformed if v in DEFORMED else None)
                    if case is None:
                        failed += 1
                        continue
                row = collect(case, v, lvl, al, wall, a.solver, a.wall)
                if v in DEFORMED:
                    geo = shape(a.out, v, a.env)
                    row["shape"] = {"deformed_from": geo["deformed_from"], "incidence_deg": geo["incidence_deg"],
                                    "sections": {k: geo["skin"][k] for k in STATIONS},
                                    "planform_area_xy_m2": geo["skin"]["planform_area_xy_m2"],
                                    "design_planform_area_xy_m2": geo["design"]["planform_area_xy_m2"]}
                if a.collect:
                    old = json.loads(Path(a.json).read_text()) if Path(a.json).exists() else {"points": []}
                    prev = [p for p in old["points"] if (p["variant"], p["level"], p["alpha_deg"],
                                                         p.get("solver", "simple"), p.get("wall", "functions"))
                            == (v, lvl, al, a.solver, a.wall)]
                    row["wall_s"] = prev[0]["wall_s"] if prev else None
                store(a.json, [row])
                print(f"  CL {row['CL']:.4f} CD {row['CD']:.4f} Cm {row['Cm']:.4f}, {row['cells']} cells, "
                      f"y+ {row['y_plus']}, spread CL {100 * row['CL_spread_last_fifth']:.2f} %, {wall:.0f} s",
                      flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
