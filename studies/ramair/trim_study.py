#!/usr/bin/python3
"""Rungs 3 and 4 of the fluid validation ladder (issue 33, docs/AERODYNAMICS.md): the coupled ram-air wing of
cases/coupled/ramair-kt (the main job) at its trim,

  convergence  the same wing at four structure resolutions (chordwise points 20/30/40/60, span divisions
               2/3/4/6: edge length h = 1, 2/3, 1/2, 1/3 of the main job's; 60/6 is how finely the fluid's skin
               samples the generator at every level) and two fluid resolutions (the main job's mesh,
               and `resolution wake`: the near-wing and wake boxes one level finer);
               -> docs/data/ramair_convergence.json (CL, CD, trim angle, trim_reached per level pair);
  polar        the main job's wing at four or more rigging angles (the lines' tilt back, structure.yaml's
               rigging_angle): the flexible wing's CL, CD, Cm, L/D and trim angle of attack per rigging angle,
               the design chart of a parafoil -> docs/data/ramair_polar.json.

Every run is a copy of the case in OUT/<run> run with ./Allrun.parallel (2 ranks) and a settings file written
here; its summary (summary.json's `wing`, ramair_wing.py) gives the numbers. Runs already finished in OUT are
not run again (--rerun does), so a cut-off study resumes where it stopped.

  /usr/bin/python3 studies/ramair/trim_study.py --runs polar            (s1-nobend = the main job = rigging 13, rig09 rig11 rig15 rig17)
  /usr/bin/python3 studies/ramair/trim_study.py --runs convergence      (s1 s2 s3 at both fluid levels)
  /usr/bin/python3 studies/ramair/trim_study.py --runs rig09,s2 [--out DIR] [--collect] [--docs]

--collect reads finished runs only; --docs writes docs/data/ramair_convergence.json, ramair_polar.json and
their plots in docs/img/. About 4-5 min per run at the main job's fluid mesh and 12 min at `wake` on the 2-core
machine of docs/PERFORMANCE.md.

The structure levels carry the fabric's bending stiffness (5.2e-5 N m, docs/RAMAIR.md): without it the finer
skins fold at element scale at the leading edge (a folded skin is a mesh artefact, not the canopy), and on the
main job's skin it changes CL and CD by 1 % or less; s1-nobend (the main job itself) measures that here.
"""
import argparse
import datetime
import json
import math
import os
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
CASE = ROOT / "cases/coupled/ramair-kt"
ENV = ROOT / "build/share/fsi/fsi-env.sh"
sys.path.insert(0, str(ROOT / "studies/common"))
from case_variants import run_copy, stop_reason  # noqa: E402 (the same edits and runs of the case's copies)
from provenance import git_commit, machine  # noqa: E402 (the machine line of the stored results)

BENDING = {"+effect": "bending: {triangles: wing/skin, rigidity: 5.2e-5}"}
STRUCTURE_LEVELS = {  # name: (h relative to the main job's, generator changes)
    "s1": (1.0, {}),
    "s2": (2.0 / 3.0, {"chordwise_points": 30, "span_divisions": 3}),
    "s3": (0.5, {"chordwise_points": 40, "span_divisions": 4}),
    "s4": (1.0 / 3.0, {"chordwise_points": 60, "span_divisions": 6}),  # the fluid skin's own sampling
}
# f1: the main job's mesh; f2: finer off the skin; f3: the near-wall control, the main job's mesh with 3 prism
# layers on the wing (wall_layers 3: the first about a quarter of the wall cell) from the trim on: 400 steps on
# the plain mesh (trimmed by step ~350), then a new mesh snapped to the trimmed canopy with the layers
# (wall_after), 300 more steps' flow time at a quarter of the step (1,200 windows). The wall cells split
# instead (wall_split 2) invert: from the start at the tip's trailing edge as the canopy inflates (s1-f3-start),
# from the trim on within 19 windows at a near-degenerate face the split made (s1-f3-split).
FLUID_LEVELS = {"f1": {}, "f2": {"resolution": "wake"},
                "f3": {"wall_layers": 3, "wall_after": 400, "steps": 700}}
RIGGING = (9, 11, 15, 17)  # and 13: the main job's, run as s1-nobend


def runs():
    """run name: (kind, settings changes, structure changes, facts)"""
    out = {"s1-nobend": ("polar", {}, {}, {"structure": "s1", "fluid": "f1", "h": 1.0, "bending": False,
                                           "rigging_angle_deg": 13, "main_job": True})}
    for f, fs in FLUID_LEVELS.items():
        for s, (h, gen) in STRUCTURE_LEVELS.items():
            name = s if f == "f1" else f"{s}-{f}"
            out[name] = ("convergence", fs, {**gen, **BENDING},
                         {"structure": s, "fluid": f, "h": h, "bending": True})
    # the finest structure with three times the equilibrium pseudo-steps per window (its elements are a third of
    # the main job's: does the relaxation per window, not the discretisation, set where it trims?)
    out["s4-eq600"] = ("convergence", {"equilibrium_steps": 600}, {**STRUCTURE_LEVELS["s4"][1], **BENDING},
                       {"structure": "s4", "fluid": "f1", "h": STRUCTURE_LEVELS["s4"][0], "bending": True,
                        "variant": "equilibrium_steps 600 (3 x the main job's)"})
    # the main job's mesh with its wall cells split twice (y+ ~ 180 instead of ~ 450, rung 2b) from the start, at a
    # quarter of the step (Courant 1 on the unsplit cell: 4 on the split one), the same flow times and the same
    # equilibrium pseudo-steps per second of flow: the split cells at the tip's trailing edge invert in window 57
    out["s1-f3-start"] = ("convergence", {"wall_split": 2, "courant": 1, "steps": 2400, "rigid_steps": 720,
                                          "carry_after": 800, "write_interval": 80, "equilibrium_steps": 50},
                          BENDING, {"structure": "s1", "fluid": "f3", "h": 1.0, "bending": True,
                                    "variant": "wall cells split twice from the start, a quarter of the step"})
    # f3 on other rigging angles: on the main job's 13 deg the canopy with the thin wall cells swings back into a
    # deep stall (s1-f3); does another rigging trim it? (remeshing lets the mesh follow a larger swing)
    for r in (9, 17):
        out[f"rig{r:02d}-f3"] = ("convergence", {**FLUID_LEVELS["f3"], "remesh_below": 0.1, "remesh_max": 10},
                                 {"rigging_angle": r, **BENDING},
                                 {"structure": "s1", "fluid": "f3", "h": 1.0, "bending": True, "rigging_angle_deg": r,
                                  "variant": f"rigging angle {r} deg"})
    out["s1-f3-split"] = ("convergence", {"wall_split": 2, "wall_after": 400, "steps": 700}, BENDING,
                          {"structure": "s1", "fluid": "f3", "h": 1.0, "bending": True,
                           "variant": "wall cells split twice from step 400 (wall_after)"})
    for r in RIGGING:
        out[f"rig{r:02d}"] = ("polar", {}, {"rigging_angle": r}, {"rigging_angle_deg": r})
    return out


RUNS = runs()


def run(name, out, rerun):
    kind, settings, structure, _ = RUNS[name]
    d = out / name
    if (d / "summary.json").exists() and not rerun:
        print(f"trim_study: {name} finished before; kept ({d})", flush=True)
        return
    print(f"trim_study: running {name} in {d}", flush=True)
    rc = run_copy(CASE, d, settings, structure, ENV)
    if rc != 0:
        print(f"trim_study: {name} failed (exit {rc}); see {d / 'Allrun.out'}", file=sys.stderr)


def collect(name, out):
    kind, _, _, facts = RUNS[name]
    d = out / name
    row = {"run": name, **facts, "dir": os.path.relpath(d, ROOT)}
    if (d / "wall_seconds").exists():
        row["wall_s"] = float((d / "wall_seconds").read_text())
    if not (d / "summary.json").exists():
        row["trim_reached"] = False
        row["stopped"] = stop_reason(d) if d.exists() else "not run"
        row.update(history_points(d, RUNS[name][1]))
        return row
    s = json.loads((d / "summary.json").read_text())
    c, w = s["coupled"], s["wing"]
    des, dfm = w["coefficients"]["design_area"], w["coefficients"]["deformed_area"]
    a = w["section_alpha"]
    import h5py
    with h5py.File(d / "structure/results.h5", "r") as h:
        row["structure_triangles"] = int(h["mesh/triangles"].shape[0])
    row.update({
        "cells": s["mesh"]["cells"], "windows": c["windows"],
        "CL": des["CL_canopy"], "CD": des["CD_canopy"], "CD_system": des["CD_system"],
        "CL_deformed_area": dfm["CL_canopy"], "CD_deformed_area": dfm["CD_canopy"],
        "L_over_D_canopy": w["coefficients"]["L_over_D_canopy"], "L_over_D_system": w["coefficients"]["L_over_D_system"],
        "glide_angle_deg": w["coefficients"]["glide_angle_deg"],
        "Cm": w["fluid_surface"].get("Cm_quarter_chord"),
        "alpha_centre_deg": a["centre_deg"], "alpha_span_average_deg": a["span_average_deg"], "alpha_tip_deg": a["tip_deg"],
        "tips_te_inboard_m": a["tips_te_inboard_of_le_m"], "planform_change": w["reference"]["planform_change"],
        "trim_reached": w["trim"]["trim_reached"], "CL_change_last": w["trim"]["CL_change"],
        "CD_change_last": w["trim"]["CD_change"], "balance": c["equilibrium_relative"],
        "skin_folds": c.get("skin_folds"),
    })
    return row


def history_points(d, settings):
    """A run that stopped early: the interface force and the chord pitch where the thin wall cells began
    (wall_after's time; the main job's mesh until then) and at its last window, from structure/coupling*.csv."""
    import csv
    import glob
    rows = []
    for f in sorted(glob.glob(str(d / "structure" / "coupling*.csv"))):
        with open(f) as fh:
            rows += list(csv.DictReader(line for line in fh if not line.startswith("#")))
    if not rows:
        return {}
    def point(r):
        return {"time_s": float(r["time"]), "lift_N": float(r["Fz_fluid"]), "drag_N": float(r["Fx_fluid"]),
                "chord_pitch_deg": float(r["chord_pitch_angle"])}
    out = {"last_window": point(rows[-1])}
    after = settings.get("wall_after", 0)
    if after:
        t = [float(r["time"]) for r in rows]
        dt = t[1] - t[0]
        before = [r for r, tt in zip(rows, t) if tt <= after * dt + 1e-9]
        if before:
            out["at_wall_after"] = point(before[-1])
    return out


# The runs of the near-wall study's figure: the main job's mesh, and the thin wall cells from step 400 on
WALL_RUNS = (("s1", "main job's mesh (y+ ~450), rigging 13"), ("s1-f3", "prism layers from step 400, rigging 13"),
             ("rig17-f3", "prism layers from step 400, rigging 17"), ("rig09-f3", "prism layers from step 400, rigging 9"))


def plot_wall_swing(out, png):
    """ramair_wall_swing.png: lift, drag and the chord pitch over the flow time of the main job's mesh against
    the runs that go on with prism layers at the wall from step 400 (WALL_RUNS that exist)."""
    import csv
    import glob
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(14, 4))
    for k, (name, label) in enumerate(WALL_RUNS):
        files = sorted(glob.glob(str(out / name / "structure" / "coupling*.csv")))
        rows = []
        for f in files:
            with open(f) as fh:
                rows += list(csv.DictReader(line for line in fh if not line.startswith("#")))
        if not rows:
            continue
        t = [float(r["time"]) for r in rows]
        for j, key in enumerate(("Fz_fluid", "Fx_fluid", "chord_pitch_angle")):
            ax[j].plot(t, [float(r[key]) for r in rows], color=f"C{k}", lw=1.2, label=label)
    for j, lab in enumerate(("lift [N]", "drag [N]", "chord pitch [deg] (LE -> TE, nose up +)")):
        ax[j].axvline(400 * 0.00833697, color="grey", ls=":", lw=1)
        ax[j].set(xlabel="flow time t [s] (dotted: the new mesh, step 400)", ylabel=lab)
        ax[j].grid(alpha=0.3)
    ax[0].legend(fontsize=8)
    fig.suptitle("The coupled canopy when its wall cells become thin at its trim: it does not hold the trim", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def richardson(h, f):
    """The value at h -> 0 from the levels (h: edge length relative to the main job's), with an error bar.
    Three or more levels that converge monotonically: the least-squares fit f = f0 + k h^p with the order p
    fitted, the error bar |f0 - f(finest)|. Two levels: p = 1 assumed (the cautious bound). Levels that do not
    converge monotonically are not in the asymptotic range: the finest level's value, with the largest
    difference between it and any other level as the error bar. None below two levels."""
    import numpy as np
    pts = sorted((hi, fi) for hi, fi in zip(h, f) if fi is not None)
    if len(pts) < 2:
        return None
    hs, fs = np.array([p[0] for p in pts]), np.array([p[1] for p in pts])
    d = np.diff(fs)
    monotone = bool(np.all(d > 0) or np.all(d < 0))

    def fit(q):
        A = np.vstack([np.ones_like(hs), hs ** q]).T
        coef = np.linalg.lstsq(A, fs, rcond=None)[0]
        return coef, float(np.sum((A @ coef - fs) ** 2))

    p = 1.0
    if len(pts) >= 3 and monotone:
        p = float(min(np.linspace(0.3, 4.0, 3701), key=lambda q: fit(q)[1]))
    if len(pts) >= 3 and (not monotone or not 0.5 <= p <= 3.5):
        why = ("the levels do not converge monotonically" if not monotone else
               f"the fitted order {p:.2f} lies outside 0.5-3.5 (the changes do not shrink as a power of h)")
        return {"extrapolated": float(fs[0]), "order": None, "finest": float(fs[0]),
                "error_bar": float(np.max(np.abs(fs - fs[0]))),
                "order_is": f"none: {why}, so not in the asymptotic range; the finest level's value, the error bar "
                            "its largest difference to another level"}
    f0 = float(fit(p)[0][0])
    return {"extrapolated": f0, "order": p, "finest": float(fs[0]), "error_bar": abs(f0 - float(fs[0])),
            "order_is": "fitted over three or more monotone levels" if len(pts) >= 3
            else "1 (assumed: two levels)"}


KEYS = ("CL", "CD", "CD_system", "alpha_centre_deg", "alpha_span_average_deg", "L_over_D_system")


def convergence_doc(rows):
    """The structure levels extrapolated on each fluid level; the fluid levels' effect where a structure level
    ran on more than one; the converged answer (the structure extrapolation on the main job's fluid mesh, its
    error bar the structure's plus the largest fluid-level change); the main job's error against it."""
    # the levels at a static equilibrium: the supports balance the applied load within 1 % and CL is steady within
    # 1 % over the last fifth (trim_reached also asks the centre angle to move less than 0.25 deg); a variant of
    # a level (another setting) is shown, not extrapolated
    ok = {(r["structure"], r["fluid"]): r for r in rows if "CL" in r and r.get("bending") and "variant" not in r
          and r["balance"] < 0.01 and r["CL_change_last"] < 0.01}
    main = next((r for r in rows if r["run"] == "s1-nobend" and "CL" in r), None)
    out = {"levels": rows, "extrapolated": {}, "fluid_effect": {}}
    for f in FLUID_LEVELS:
        lv = [ok[(s, f)] for s in STRUCTURE_LEVELS if (s, f) in ok]
        out["extrapolated"][f] = {k: richardson([r["h"] for r in lv], [r[k] for r in lv]) for k in KEYS}
        if f != "f1":
            out["fluid_effect"][f] = {s: {k: ok[(s, f)][k] - ok[(s, "f1")][k] for k in KEYS}
                                      for s in STRUCTURE_LEVELS if (s, f) in ok and (s, "f1") in ok}
    out["fluid_effect_is"] = "the value on fluid level f minus the value on f1 (the main job's mesh), same structure level"
    # The converged answer stands on the near-wall control (f3) once two structure levels reached equilibrium
    # on it; the off-skin refinement's change (f2 against f1) is added to its bar
    base = "f3" if sum((s, "f3") in ok for s in STRUCTURE_LEVELS) >= 2 else "f1"
    conv = {}
    for k, ex in out["extrapolated"][base].items():
        if not ex:
            continue
        fl = [abs(e[k]) for f, per in out["fluid_effect"].items() if f == "f2" for e in per.values()]
        conv[k] = {**ex, "structure_error_bar": ex["error_bar"], "fluid_error_bar": max(fl) if fl else None,
                   "error_bar": ex["error_bar"] + (max(fl) if fl else 0.0)}
    out["converged"] = conv
    out["converged_fluid_level"] = base
    if base == "f3":
        out["converged_is"] = ("structure h -> 0 over the levels at a static equilibrium (bending) on the fluid mesh "
                               "with the wall cells split twice (f3: y+ ~180, wall functions); error bar = the "
                               "structure levels' + the largest change the finer off-skin mesh made (f2 against f1). "
                               "NOT included: a further wall refinement (3 splits invert cells at the leading edge; "
                               "on the rigid arced wing with flat panels the split coarse mesh gave the fine mesh's "
                               "CL within 1 %, docs/AERODYNAMICS.md rung 2b)")
    else:
        out["converged_is"] = ("structure h -> 0 over the levels at a static equilibrium (bending) on the main "
                               "job's fluid mesh; error bar = the structure levels' + the largest change the finer "
                               "off-skin mesh made (f2 against f1); NOT included, and larger than the bar: the "
                               "wall treatment's and the moved mesh's error (y+ ~450 on the design mesh moved with "
                               "the canopy). The main job's trimmed canopy as a rigid wing at its attitude has CL "
                               "0.30 on a mesh snapped to it with the same wall functions (the coupled run: 0.60, "
                               "loaded area) and no lift (-0.04, separated) on the resolved wall (3 prism layers, "
                               "y+ ~75): docs/AERODYNAMICS.md rung 2c")
    if main:
        import hashlib
        s_main = json.loads((ROOT / main["dir"] / "summary.json").read_text())
        out["main_job_inputs"] = {
            "structure_yaml_sha256": hashlib.sha256((ROOT / main["dir"] / "structure.yaml").read_bytes()).hexdigest(),
            "settings": s_main["settings"],
            "is": "the inputs of the run s1-nobend (the case's structure.yaml and coupled.settings): a coupled summary "
                  "whose case has these states its error against `converged` (ramair_wing.py)"}
        out["main_job_error"] = {k: {"main_job": main[k], "converged": c["extrapolated"],
                                     "error": main[k] - c["extrapolated"],
                                     "relative": None if k.startswith("alpha") else main[k] / c["extrapolated"] - 1,
                                     "error_bar_of_converged": c["error_bar"]} for k, c in conv.items()}
        out["main_job_error_is"] = "the main job (s1-nobend: level s1 without bending, fluid f1) against `converged`"
    return out


def plot_convergence(doc, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [r for r in doc["levels"] if "CL" in r and r.get("bending")]
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    for k, (key, lab) in enumerate((("CL", "CL canopy (design area)"), ("CD_system", "CD system (canopy + lines)"),
                                    ("alpha_centre_deg", "centre section's angle of attack [deg]"))):
        for j, f in enumerate(FLUID_LEVELS):
            sel = sorted((r for r in rows if r["fluid"] == f), key=lambda r: r["h"])
            if not sel:
                continue
            ax[k].plot([r["h"] for r in sel], [r[key] for r in sel], {"f1": "o-", "f2": "s--", "f3": "D:"}[f], color=f"C{j}",
                       label={"f1": "fluid: main job's mesh", "f2": "fluid: wake (finer off the skin)",
                              "f3": "fluid: wall cells split twice (y+ ~180)"}[f])
            for r in sel:
                if not r["trim_reached"]:
                    ax[k].plot(r["h"], r[key], "x", color="k", ms=10)
            ex = (doc["converged"].get(key) if f == doc.get("converged_fluid_level", "f1")
                  else doc["extrapolated"][f].get(key))
            if ex:
                ax[k].errorbar([0], [ex["extrapolated"]], yerr=[ex["error_bar"]], fmt="*", color=f"C{j}", ms=10,
                               capsize=4)
        main = next((r for r in doc["levels"] if r["run"] == "s1-nobend" and "CL" in r), None)
        if main:
            ax[k].plot([1.0], [main[key]], "D", color="C3", mfc="none", ms=9, label="main job (no bending)")
        ax[k].set(xlabel="structure edge length h / main job's", ylabel=lab, xlim=(-0.05, 1.1))
        ax[k].grid(alpha=0.3)
    ax[0].legend(fontsize=8)
    fig.suptitle("Coupled ram-air wing at its trim: structure x fluid resolution (star: extrapolated to h -> 0; "
                 "x: trim not reached)", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def plot_polar(rows, png, rigid=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = sorted((r for r in rows if "CL" in r), key=lambda r: r["rigging_angle_deg"])
    fig, ax = plt.subplots(1, 4, figsize=(17, 4.6))
    a = [r["alpha_span_average_deg"] for r in rows]
    rig = [r["rigging_angle_deg"] for r in rows]
    ax[0].plot(rig, [r["alpha_centre_deg"] for r in rows], "o-", label="centre section")
    ax[0].plot(rig, a, "s-", label="span average")
    ax[0].plot(rig, [r["alpha_tip_deg"] for r in rows], "^-", label="tips")
    ax[0].set(xlabel="rigging angle [deg]", ylabel="trim angle of attack [deg]", title="trim per rigging angle")
    ac = [r["alpha_centre_deg"] for r in rows]
    ax[1].plot(ac, [r["CL"] for r in rows], "o-", label="flexible, coupled (design area), x: centre section")
    ax[1].plot(a, [r["CL"] for r in rows], "s:", label="flexible, coupled (design area), x: span average")
    if rigid:
        for r in rigid["series"]:
            ax[1].plot(r["alpha"], r["CL"], r["style"], label=r["label"], mfc="none")
        est = rigid["estimate"]
        ax[1].plot(est["alpha"], est["CL"], "k-", lw=0.8, label=est["label"])
    ax[1].set(xlabel="section angle of attack [deg]", ylabel="CL", title="lift")
    ax[2].plot([r["CD"] for r in rows], [r["CL"] for r in rows], "o-", label="canopy")
    ax[2].plot([r["CD_system"] for r in rows], [r["CL"] for r in rows], "s-", label="system (canopy + lines)")
    if rigid:
        for r in rigid["series"]:
            ax[2].plot(r["CD"], r["CL"], r["style"], label=r["label"], mfc="none")
    ax[2].set(xlabel="CD", ylabel="CL", title="drag polar (design area)")
    ax[3].plot(rig, [r["L_over_D_system"] for r in rows], "s-", label="L/D system")
    ax[3].plot(rig, [r["L_over_D_canopy"] for r in rows], "o-", label="L/D canopy")
    if all(r.get("Cm") is not None for r in rows):
        b = ax[3].twinx()
        b.plot(rig, [r["Cm"] for r in rows], "d:", color="C3", label="Cm (quarter chord)")
        b.set_ylabel("Cm about the centre section's quarter chord", color="C3")
    ax[3].set(xlabel="rigging angle [deg]", title="glide ratio and pitching moment")
    for k, x in enumerate(ax):
        x.grid(alpha=0.3)
        x.legend(fontsize=6.5, loc="lower right" if k in (1, 2) else "best")
    for r in rows:
        if not r["trim_reached"]:
            ax[0].annotate("trim not reached", (r["rigging_angle_deg"], r["alpha_centre_deg"]), fontsize=7)
    fig.suptitle("Flexible ram-air wing (coupled, anchored at the confluence): the design chart", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def rigid_polar():
    """Rung 2's rigid wings (docs/data/wing_polar.json) and Helmbold's lifting line with the arc factor from rung
    1's zero-lift angle, for the plot; x: the centre section's angle. Series: the arc wing with flat panels
    (medium, steady), the scene's bulged cells (coarse, time-averaged) and 16 bulged cells (coarse, steady)."""
    p = ROOT / "docs/data/wing_polar.json"
    if not p.exists():
        return None
    d = json.loads(p.read_text())
    series = []
    for variant, level, solver, label, style in (
            ("arc", "medium", "simple", "rigid arc wing, flat panels (rung 2, medium)", "k^--"),
            ("bulged", "coarse", "pimple", "rigid, the scene's 8 bulged cells (coarse, time-averaged)", "rv--"),
            ("bulged16", "coarse", "simple", "rigid, 16 bulged cells (coarse)", "m<--")):
        pts = sorted((r for r in d.get("points", []) if r.get("variant") == variant and r.get("level") == level
                      and r.get("solver") == solver and r.get("wall") == "functions" and "CL" in r),
                     key=lambda r: r["alpha_deg"])
        if pts:
            series.append({"alpha": [r["alpha_deg"] for r in pts], "CL": [r["CL"] for r in pts],
                           "CD": [r["CD"] for r in pts], "label": label, "style": style,
                           "aspect_ratio": pts[0]["aspect_ratio"]})
    if not series:
        return None
    sys.path.insert(0, str(ROOT / "studies/wing"))
    from wing_polar import helmbold  # noqa: E402
    slope = helmbold(series[0]["aspect_ratio"], 0.5)  # the half-arc angle of the 3 m arc on R = 3 m: 0.5 rad
    alpha0 = -3.72  # rung 1: NACA 4415, fine layers (docs/data/section_polar.json)
    est_a = [-4.0, 12.0]
    return {"series": series,
            "estimate": {"alpha": est_a, "CL": [slope * math.radians(a - alpha0) for a in est_a],
                         "label": f"Helmbold x arc ({slope:.2f}/rad), alpha0 {alpha0} deg"}}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "studies-out/ramair"))
    ap.add_argument("--runs", default="polar,convergence")
    ap.add_argument("--collect", action="store_true")
    ap.add_argument("--rerun", action="store_true")
    ap.add_argument("--docs", action="store_true")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    names = []
    for item in a.runs.split(","):
        if item in ("polar", "convergence"):
            names += [n for n, v in RUNS.items() if v[0] == item]
        elif item in RUNS:
            names.append(item)
        else:
            sys.exit(f"trim_study: unknown run '{item}'; valid: polar, convergence, {', '.join(RUNS)}")
    if not a.collect:
        for n in names:
            run(n, out, a.rerun)
    conv = [collect(n, out) for n, v in RUNS.items() if (v[0] == "convergence" or n == "s1-nobend")
            and (out / n).exists()]
    polar = [collect(n, out) for n, v in RUNS.items() if v[0] == "polar" and (out / n).exists()]
    # the main job (s1-nobend) is both the convergence study's reference and the polar's rigging angle 13
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    meta = {"machine": machine(), "finished": stamp, "commit": git_commit()}
    cdoc = {"command": "/usr/bin/python3 studies/ramair/trim_study.py --runs convergence --docs", **meta,
            **convergence_doc(conv)}
    pdoc = {"command": "/usr/bin/python3 studies/ramair/trim_study.py --runs polar --docs", **meta,
            "coefficients_are": "CL, CD on the design projected area (forceCoeffs' Aref); CD_system adds the lines' "
                                "drag; Cm about the deformed centre section's quarter-chord point, on the design "
                                "area and the root chord, nose up positive",
            "rows": polar}
    (out / "ramair_convergence.json").write_text(json.dumps(cdoc, indent=1) + "\n")
    (out / "ramair_polar.json").write_text(json.dumps(pdoc, indent=1) + "\n")
    for r in conv + polar:
        print(json.dumps({k: (round(v, 4) if isinstance(v, float) else v) for k, v in r.items()}))
    if conv:
        plot_convergence(cdoc, out / "ramair_convergence.png")
    if polar:
        plot_polar(polar, out / "ramair_polar.png", rigid_polar())
    if any((out / n).exists() for n, _ in WALL_RUNS[1:]):
        plot_wall_swing(out, out / "ramair_wall_swing.png")
    if a.docs:
        if (out / "ramair_wall_swing.png").exists():
            shutil.copy(out / "ramair_wall_swing.png", ROOT / "docs/img/ramair_wall_swing.png")
        for n in ("ramair_convergence", "ramair_polar"):
            if (out / f"{n}.png").exists():
                shutil.copy(out / f"{n}.json", ROOT / f"docs/data/{n}.json")
                shutil.copy(out / f"{n}.png", ROOT / f"docs/img/{n}.png")


if __name__ == "__main__":
    main()
