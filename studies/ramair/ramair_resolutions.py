#!/usr/bin/python3
"""What accuracy costs in time on the coupled ram-air wing (issue 14, docs/ACCURACY_COST.md "Coupled ram-air
wing"): the main job's case (cases/coupled/ramair-kt, coupled.settings) at its coarse resolution, with the fluid
mesh refined one level (resolution medium: cells / 2 at the wing, the step halved to keep Courant 4, the same
flow time), with the fluid mesh refined one level off the skin only (resolution wake), and with the structure
refined (1.5 x the chordwise points and span divisions). Every variant is a
copy of the case run with ./Allrun.parallel (2 ranks) in OUT/<variant>; the table and the plot compare the
summary's figures against the wall time of the whole run.

  /usr/bin/python3 studies/ramair/ramair_resolutions.py [--out DIR] [--only coarse,fluid-medium] [--collect] [--docs]

--collect reads finished runs in OUT instead of running them. --docs also stores the rows with the machine,
date and commit in docs/data/ramair_resolutions.json and the plot in docs/img/ramair_resolutions.png, from
where studies/cost/accuracy_cost.py puts them into docs/ACCURACY_COST.md. Runs take 5 (coarse) to 30 (fluid-medium)
minutes on the 2-core machine of docs/PERFORMANCE.md. The environment (build/share/fsi/fsi-env.sh) is
sourced for every run."""
import argparse
import datetime
import json
import re
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies/common"))
from case_variants import chosen, run_copy, stop_reason  # noqa: E402
from provenance import git_commit, machine  # noqa: E402 (the same machine line as the other tables)
CASE = ROOT / "cases/coupled/ramair-kt"
ENV = ROOT / "build/share/fsi/fsi-env.sh"


def doubled_steps():
    """The step counts of coupled.settings twice over (the same flow times at half the step); only the keys
    the file sets (carry_after without equilibrium_start carry would be refused)."""
    text = (CASE / "coupled.settings").read_text()
    out = {}
    for key in ("rigid_steps", "steps", "write_interval", "carry_after"):
        m = re.search(rf"^{key}\s+(\d+)", text, re.M)
        if m:
            out[key] = 2 * int(m.group(1))
    return out


# variant: (what it changes, settings changes, structure generator changes)
VARIANTS = {
    "coarse": ("the main job", {}, {}),
    # The finer cells next to the skin cannot follow the canopy's motion from the design shape (the mesh guard
    # stopped every run without remeshing, docs/RAMAIR.md), and the finer skin shows the structure's element-
    # scale folds at the leading edge unless the fabric has its bending stiffness (the coarse run changes by
    # 1 % or less with it): remeshing where a moving cell folds, and bending. With remeshing the medium mesh
    # still folds a face at the trailing edge every 3-15 windows from window 360 on (2026-11-28, seventh
    # session: 5 new meshes in windows 360-390, each about a minute to snap, map and decompose): about three
    # hours to the end, so the variant stops itself after 10 new meshes (remesh_max).
    "fluid-medium": ("fluid mesh one level finer (Courant 4: half the step, twice the windows), remeshed where "
                     "a moving face folds (remesh_below 0.1), fabric bending 5.2e-5 N m",
                     {"resolution": "medium", **doubled_steps(), "remesh_below": 0.1, "remesh_max": 10},
                     {"+effect": "bending: {triangles: wing/skin, rigidity: 5.2e-5}"}),
    # The medium mesh's near-wing and wake boxes with the coarse mesh's cells at the skin (resolution wake): the
    # flow off the skin one level finer, the cells the canopy moves as in the main job.
    "fluid-wake": ("fluid mesh one level finer off the skin (near-wing and wake boxes; the skin's cells and the "
                   "step as coarse)", {"resolution": "wake"}, {}),
    "structure-fine": ("structure 1.5 x finer (chordwise points 30, span divisions 3)", {},
                       {"chordwise_points": 30, "span_divisions": 3}),
}


def run_variant(name, out):
    _, settings, structure = VARIANTS[name]
    rc = run_copy(CASE, out / name, settings, structure, ENV)
    if rc != 0:
        print(f"ramair_resolutions: {name} failed (exit {rc}); see {out / name / 'Allrun.out'}", file=sys.stderr)
    return rc == 0


def collect(name, out):
    d = out / name
    if not (d / "summary.json").exists():
        return {"variant": name, "what": VARIANTS[name][0], "stopped": stop_reason(d),
                "wall_s": float((d / "wall_seconds").read_text())}
    s = json.loads((d / "summary.json").read_text())
    c, m = s["coupled"], s["mesh"]
    import h5py  # the structure's own triangles (skin and ribs), from its results
    with h5py.File(d / "structure/results.h5", "r") as h:
        triangles = int(h["mesh/triangles"].shape[0])
    return {
        "variant": name, "what": VARIANTS[name][0], "cells": m["cells"], "wing_faces": m["wing_faces"],
        "structure_triangles": triangles, "windows": c["windows"], "wall_s": float((d / "wall_seconds").read_text()),
        "CL": c["CL"], "CD": c["CD"], "L_over_D": c["L_over_D"],
        "pitch_deg": c.get("mean_chord_pitch_deg", c.get("pitch_deg")),  # the probe's name before issue 33
        "balance": c["equilibrium_relative"], "stress_max_over_mean": c["stress_max_over_mean"],
        "skin_stress_max_Pa": c["skin_stress_max_Pa"], "line_tension_max_N": c["line_tension_max_N"],
    }


def table(rows):
    base = rows[0]
    out = ["| variant | fluid cells; wing faces; structure triangles | windows | wall [s] | CL | CD | L/D | pitch [°] | "
           "balance | stress max/mean | change of CL, CD, max stress vs coarse |", "|" + "---|" * 11]
    for r in rows:
        if "stopped" in r:
            cells = [f"{r['variant']} ({r['what']})", "", "", f"{r['wall_s']:.0f}", r["stopped"]] + [""] * 6
            out.append("| " + " | ".join(cells) + " |")
            continue
        rel = "—" if r is base else ", ".join(
            f"{100 * (r[k] / base[k] - 1):+.1f} %" for k in ("CL", "CD", "skin_stress_max_Pa"))
        out.append(f"| {r['variant']} ({r['what']}) | {r['cells']}; {r['wing_faces']}; {r['structure_triangles']} | "
                   f"{r['windows']} | {r['wall_s']:.0f} | {r['CL']:.3f} | {r['CD']:.4f} | {r['L_over_D']:.2f} | "
                   f"{r['pitch_deg']:.2f} | {100 * r['balance']:.1f} % | {r['stress_max_over_mean']:.2f} | {rel} |")
    return "\n".join(out) + "\n"


def plot(rows, png):
    """Left: the change of CL, CD and the largest stress against the coarse run, in %; right: the trim's chord
    pitch itself (a change relative to a pitch near zero says nothing). Both against the whole run's wall time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    base = rows[0]
    rows = [r for r in rows if "stopped" not in r]  # a stopped run has no figures to plot
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.2), gridspec_kw={"width_ratios": [3, 2]})
    colour = {r["variant"]: f"C{list(VARIANTS).index(r['variant'])}" for r in rows}
    for key, label, mark in (("CL", "CL", "o"), ("CD", "CD", "s"), ("skin_stress_max_Pa", "max principal stress", "^")):
        for r in rows:
            ax.plot(r["wall_s"] / 60, 100 * (r[key] / base[key] - 1), mark, color=colour[r["variant"]], ms=7)
        ax.plot([], [], mark, color="grey", label=label)
    for r in rows:
        bx.plot(r["wall_s"] / 60, r["pitch_deg"], "v", color=colour[r["variant"]], ms=7)
    for k, r in enumerate(rows):  # labels stacked where runs took about the same time
        ax.annotate(r["variant"], (r["wall_s"] / 60, 0), textcoords="offset points", xytext=(6, 6 + 12 * k),
                    fontsize=8, color=colour[r["variant"]])
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("wall time of the whole run, 2 ranks [min]")
    ax.set_ylabel("change against the coarse run [%]")
    ax.set_title("Coupled ram-air wing: resolution against wall time", fontsize=10)
    ax.legend(fontsize=8)
    bx.set_xlabel("wall time of the whole run, 2 ranks [min]")
    bx.set_ylabel("chord pitch at the trim [deg]")
    bx.set_title("trim", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "results/ramair-resolutions"))
    ap.add_argument("--only", default=",".join(VARIANTS))
    ap.add_argument("--collect", action="store_true")
    ap.add_argument("--docs", action="store_true", help="store the rows and the plot under docs/ (see above)")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    names = chosen(a.only, VARIANTS, "ramair_resolutions")
    if not a.collect:
        for n in names:
            print(f"ramair_resolutions: running {n} in {out / n}", flush=True)
            run_variant(n, out)
    rows = [collect(n, out) for n in VARIANTS if (out / n / "wall_seconds").exists()]
    if not rows or rows[0]["variant"] != "coarse" or "stopped" in rows[0]:
        sys.exit("ramair_resolutions: the coarse run is the reference and has no summary.json")
    (out / "resolutions.json").write_text(json.dumps(rows, indent=1))
    (out / "resolutions.md").write_text(table(rows))
    plot(rows, out / "resolutions.png")
    print(table(rows))
    if a.docs:
        stamp = datetime.datetime.fromtimestamp(max((out / r["variant"] / "wall_seconds").stat().st_mtime
                                                    for r in rows), datetime.timezone.utc)
        meta = {"command": "/usr/bin/python3 studies/ramair/ramair_resolutions.py --docs", "machine": machine(),
                "finished": stamp.strftime("%Y-%m-%d %H:%M UTC"), "commit": git_commit(), "rows": rows}
        (ROOT / "docs/data").mkdir(exist_ok=True)
        (ROOT / "docs/data/ramair_resolutions.json").write_text(json.dumps(meta, indent=1) + "\n")
        shutil.copy(out / "resolutions.png", ROOT / "docs/img/ramair_resolutions.png")


if __name__ == "__main__":
    main()
