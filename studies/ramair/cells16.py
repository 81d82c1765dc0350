#!/usr/bin/python3
"""The main job with the canopy design study's 16 cells (docs/AERODYNAMICS.md, "Canopy design"): a copy of
cases/coupled/ramair-kt run with ./Allrun.parallel and coupled.settings unchanged, structure.yaml with
`cells: 16` (the cut, lines, rig and everything else the main job's), beside the main job's own row of
docs/data/ramair_convergence.json (s1: the 8-cell canopy on the same fluid mesh and settings).

  /usr/bin/python3 studies/ramair/cells16.py [--out DIR] [--collect] [--runs coarse,layers,brake-layers,...]
                                             [--plot RAMAIR_OUT]

Runs: `coarse` is the main job's fluid mesh and wall functions (y+ ~450); `layers` is the same with the near-wall
control of trim_study.py's level f3 (400 steps on the main job's mesh, then a new mesh snapped to the trimmed
canopy with 3 prism layers, `wall_layers 3` with `wall_after 400`, 300 more steps' flow time at a quarter of the
step); `brake-layers` is `layers` with both brakes drawn a quarter chord from 0.5 s after the new mesh (the
symmetric brake; remesh_below 0.1 as brake.settings); `layers-rig11`, `layers-rig15` and `layers-rig17` are
`layers` at the rigging angles 11, 15 and 17 deg (the main job's is 13): the layered canopy's polar.
--plot draws docs/img/ramair_cells16_wall.png: CL, CD and the chord pitch over the flow time of these runs beside
the 8-cell canopy's s1 and s1-f3 of trim_study.py (their folders in RAMAIR_OUT, studies-out/ramair by default).
Writes docs/data/ramair_cells16.json (a run not asked keeps its committed row). About 10 min (coarse) and 11-50 min
(each layered run) on a 2-core machine, idle to loaded."""
import argparse
import datetime
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies/common"))
from case_variants import run_copy, stop_reason  # noqa: E402
from provenance import git_commit, machine  # noqa: E402
CASE = ROOT / "cases/coupled/ramair-kt"
ENV = ROOT / "build/share/fsi/fsi-env.sh"


LAYERS = {"wall_layers": 3, "wall_after": 400, "steps": 700}
# the pilot's symmetric brake (issue 34) on the layered wall: both toggles drawn a quarter chord over 0.5 s from
# 0.5 s after the new mesh with the layers (brake.settings' travel and ramp), held 1.5 s; remesh_below as
# brake.settings (the moved mesh cannot follow the trailing edge drawn down: docs/RAMAIR.md)
BRAKE = {"brake_left": 0.25, "brake_right": 0.25, "brake_start": 3.835, "brake_duration": 0.5, "remesh_below": 0.1}
RUNS = {"coarse": {}, "layers": LAYERS, "brake-layers": {**LAYERS, **BRAKE}, "layers-rig11": LAYERS,
        "layers-rig15": LAYERS, "layers-rig17": LAYERS}
KEYS = {"coarse": "cells16", "layers": "cells16_layers", "brake-layers": "cells16_layers_symmetric_brake",
        "layers-rig11": "cells16_layers_rigging11", "layers-rig15": "cells16_layers_rigging15",
        "layers-rig17": "cells16_layers_rigging17"}
# structure.yaml's generator changes of each run (all 16 cells; the rigging angle of the polar's runs: the lines'
# tilt back from the vertical at the confluence point, 13 deg in the main job)
STRUCTURE = {n: {"cells": 16, **({"rigging_angle": int(n[-2:])} if "-rig" in n else {})} for n in RUNS}


Q = 0.5 * 1.225 * 15.0 ** 2  # the main job's dynamic pressure [Pa]


def history(d):
    """time, CL and CD on the design area, chord pitch of a run's structure/coupling*.csv (every stage)."""
    import csv
    import glob
    rows = []
    for f in sorted(glob.glob(str(d / "structure" / "coupling*.csv"))):
        with open(f) as fh:
            rows += list(csv.DictReader(line for line in fh if not line.startswith("#")))
    return rows


def plot(out, ramair_out, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = ((Path(ramair_out) / "s1", 2.948, "8 cells, main job's mesh (y+ ~450)", "C0", "-"),
            (Path(ramair_out) / "s1-f3", 2.948, "8 cells, prism layers from step 400", "C0", "--"),
            (Path(out) / "coarse", 2.9235, "16 cells, main job's mesh", "C3", "-"),
            (Path(out) / "layers", 2.9235, "16 cells, prism layers from step 400", "C3", "--"),
            (Path(out) / "brake-layers", 2.9235, "16 cells, layers, symmetric brake from 3.835 s", "C2", "-."))
    fig, ax = plt.subplots(1, 3, figsize=(14, 4))
    for d, area, label, colour, style in runs:
        rows = history(d)
        if not rows:
            continue
        t = [float(r["time"]) for r in rows]
        ax[0].plot(t, [float(r["Fz_fluid"]) / (Q * area) for r in rows], colour, ls=style, lw=1.1, label=label)
        ax[1].plot(t, [float(r["Fx_fluid"]) / (Q * area) for r in rows], colour, ls=style, lw=1.1)
        ax[2].plot(t, [float(r["chord_pitch_angle"]) for r in rows], colour, ls=style, lw=1.1)
    for a, lab in zip(ax, ("CL (canopy, design area)", "CD (canopy, design area)",
                           "chord pitch [deg] (mean LE -> mean TE)")):
        a.axvline(400 * 0.00833697, color="grey", ls=":", lw=1)
        a.set(xlabel="flow time t [s]", ylabel=lab)
        a.grid(alpha=0.3)
    ax[1].set_ylim(0, 0.4)
    for a in ax:
        a.axvspan(BRAKE["brake_start"], BRAKE["brake_start"] + BRAKE["brake_duration"], color="C2", alpha=0.08)
    ax[0].legend(fontsize=8)
    fig.suptitle("The coupled canopy when its wall cells become thin at its trim (dotted: the new mesh with layers, "
                 "step 400): 8 cells against 16; green band: the 16-cell canopy's symmetric brake pulled", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def stopped_row(d):
    """A run without a summary: why it stopped (case_variants.stop_reason)."""
    return {"trim_reached": False, "stopped": stop_reason(d) if d.exists() else "not run",
            "wall_s": float((d / "wall_seconds").read_text()) if (d / "wall_seconds").exists() else None}


def row(d):
    s = json.loads((d / "summary.json").read_text())
    w = s["wing"]
    co = w["coefficients"]
    return {"CL_design_area": co["design_area"]["CL_canopy"], "CD_canopy_design_area": co["design_area"]["CD_canopy"],
            "CD_system_design_area": co["design_area"]["CD_system"], "CL_loaded_area": co["deformed_area"]["CL_canopy"],
            "loaded_area_m2": co["deformed_area"]["area_m2"], "design_area_m2": co["design_area"]["area_m2"],
            "L_over_D_canopy": co["L_over_D_canopy"], "L_over_D_system": co["L_over_D_system"],
            "section_alpha": w["section_alpha"], "trim": w["trim"],
            "wall_s": float((d / "wall_seconds").read_text()) if (d / "wall_seconds").exists() else None}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=str(ROOT / "studies-out/c16"))
    ap.add_argument("--collect", action="store_true", help="read the finished runs in OUT/<run>")
    ap.add_argument("--runs", default="coarse", help="comma-separated: " + ", ".join(RUNS))
    ap.add_argument("--plot", nargs="?", const=str(ROOT / "studies-out/ramair"), metavar="RAMAIR_OUT",
                    help="draw docs/img/ramair_cells16_wall.png (the 8-cell runs from RAMAIR_OUT)")
    a = ap.parse_args()
    if a.plot:
        plot(a.out, a.plot, ROOT / "docs/img/ramair_cells16_wall.png")
        return
    names = [n for n in a.runs.split(",") if n]
    for n in names:
        if n not in RUNS:
            sys.exit(f"cells16: unknown run '{n}'; valid: {', '.join(RUNS)}")
    data = ROOT / "docs/data/ramair_cells16.json"
    old = json.loads(data.read_text()) if data.exists() else {}
    rows = {n: old.get(KEYS[n]) for n in RUNS if old.get(KEYS[n]) is not None}
    for n in names:
        d = Path(a.out) / n
        if not a.collect:
            rc = run_copy(CASE, d, RUNS[n], STRUCTURE[n], ENV)
            if rc != 0:
                print(f"cells16: run {n} failed (exit {rc}); see {d}/Allrun.out", file=sys.stderr)
        rows[n] = row(d) if (d / "summary.json").exists() else stopped_row(d)
    conv = json.loads((ROOT / "docs/data/ramair_convergence.json").read_text())
    main_job = next(x for x in conv["levels"] if x["run"] == "s1")
    out = {"what": "the main job (coupled.settings) with 16 cells instead of 8: cells16 on the main job's mesh and "
                   "wall functions; cells16_layers with prism layers from step 400 (wall_layers 3, wall_after 400, "
                   "700 steps); cells16_layers_symmetric_brake the same with both brakes drawn a quarter chord "
                   "from t = 3.835 s (BRAKE in the script)",
           "command": "/usr/bin/python3 studies/ramair/cells16.py", "machine": machine(), "commit": git_commit(),
           "date": datetime.date.today().isoformat(), **{KEYS[n]: r for n, r in rows.items()},
           "main_job_8_cells": {k: main_job.get(k) for k in ("CL", "CD", "alpha_centre_deg", "trim_reached", "wall_s")},
           "main_job_is": "docs/data/ramair_convergence.json row s1 (CL and CD of the canopy on the design area)"}
    data.write_text(json.dumps(out, indent=1) + "\n")
    for n in names:
        print(n, json.dumps(rows[n].get("trim", rows[n].get("stopped")), indent=1))


if __name__ == "__main__":
    main()
