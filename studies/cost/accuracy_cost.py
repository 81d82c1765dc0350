#!/usr/bin/env python3
"""Accuracy versus cost, one knob at a time: for each knob the error against a converged or analytical
reference and the wall time it costs, as tables with a computed "what you buy" sentence per step, and
log-log plots of error against time. Writes OUT/ACCURACY_COST.md and OUT/img/accuracy_cost_*.png (OUT:
docs/ by default) and, with --json, every measured row for the test tests/cost/test_accuracy_cost.py.

Knobs: mesh refinement (Hencky, pressurised sphere, airbag), the safety factor on the stable step, selective
mass scaling, the dynamic-relaxation method and tolerance (studies/relaxation/dr_accuracy_cost.py's measurement), the
projection variant, mesh and quadrature level of `fsi map-check`; the coupled knobs (fluid step, subcycling,
acceleration and tolerance, staggered or implicit) on the added-mass problem through the driver
fsi_coupling_cost (tests/cost/coupling_cost.cpp). The coupled sail: measured by hand (static text, the doc says why).

Usage: studies/cost/accuracy_cost.py [--quick] [--out DIR] [--fsi PATH] [--coupling-driver PATH] [--json FILE]
                                [--repeats N]
  --quick   reduced set (< 3 min on 2 cores): the coarser levels of every knob
Wall time: the solver's own clock (summary.json stats.wall_seconds: the step or iteration loop, without
start-up and file output) for `fsi run`; setup_seconds of the map-check report for the projection. Runs
shorter than 2 s are repeated (--repeats, default 3) and the median is used."""
import argparse
import datetime
import json
import os
import shlex
import sys
import tempfile
import time
from pathlib import Path

STUDIES = Path(__file__).resolve().parents[1]
for d in ("common", "relaxation", "sail", "ramair"):  # fsi_runs, provenance; dr_accuracy_cost; sail_knobs; ...
    sys.path.insert(0, str(STUDIES / d))
import cost_coupled  # noqa: E402
import cost_dr  # noqa: E402
import cost_integration  # noqa: E402
import cost_mesh  # noqa: E402
import cost_projection  # noqa: E402
import dr_accuracy_cost  # noqa: E402
import fsi_runs  # noqa: E402
from cost_words import buy  # noqa: E402
from fsi_runs import ROOT  # noqa: E402
from provenance import git_commit, machine  # noqa: E402


# Sail knobs sail_knobs.py does not repeat (measured by hand on 2026-11-27).
SAIL_KNOBS_BY_HAND = """Measured by hand and not repeated by the script: the fluid faces along the chord, 80 graded 1:6 → 100
graded 1:2.5 (`end`, element damping), change the camber at 0.545 s from 4.417 to 4.418 % and the z-force from
0.01300 to 0.01301 N for 14,400 instead of 12,800 cells (about 1.1× the time).
"""

# Shown when docs/data/sail_knobs.json does not exist yet.
SAIL_KNOBS = """## Coupled knobs on the sail (measured by hand, not regenerated)

`cases/coupled/sail-2d` (docs/VALIDATION.md): each setting is a full pimpleFoam run of minutes and the sail
has no exact answer, so this script does not repeat these runs; the figures are from single serial runs of
2026-11-27 on the 2-core test machine while other jobs ran (wall times only as ratios within a row). The
reference for each knob is the case's own setting or its tighter variant:

| knob | setting → setting | what it changes | what it costs |
|---|---|---|---|
| coupling tolerance | default → 1e-8 (80-face mesh, first 20 windows) | the same forces to 4 digits (window 12: +0.016837 N both; window 19: 0.004571 vs 0.004578 N) | 9–10 instead of 6–8 iterations per window: about 1.35× the time for nothing |
| load in the window | `mean` → `end` | window-to-window alternation of the force 0.034 → 0.008 over 0.3–0.6 s (4× smoother), the same camber at 0.545 s to 0.1 % | the same 5–7 iterations per window: free |
| fluid faces along the chord | 80 graded 1:6 → 100 graded 1:2.5 (`end`, element damping) | camber at 0.545 s 4.417 → 4.418 %, z-force 0.01300 → 0.01301 N | 14,400 instead of 12,800 cells: about 1.1× |
| element damping | none → `bulk_viscosity: {}` | without it the run stops at t = 0.40 s (mesh guard, node-scale ringing); with it, it runs | a lower stable step, but the structure is 0.05 % of the wall time here |
| fluid time scheme | Euler → backward (BDF2) | the start-up alternation grows instead of decaying | no gain: keep Euler with the implicit coupling |

What you buy: with a light membrane the cheap settings (`end`, element damping) decide whether the run
survives; a tighter coupling tolerance buys nothing visible at 1.35× the cost.
"""


def sail_section():
    """The sail's coupled knobs: the rows studies/sail/sail_knobs.py --docs stored (minutes of pimpleFoam each, so
    this script reads them instead of repeating them), then the hand-measured rows it does not repeat."""
    path = ROOT / "docs/data/sail_knobs.json"
    if not path.exists():
        return [SAIL_KNOBS]
    import sail_knobs
    d = json.loads(path.read_text())
    return ["## Coupled knobs on the sail\n",
            f"`cases/coupled/sail-2d` (docs/VALIDATION.md), one knob changed at a time against the case as shipped, "
            f"each a serial run to t = {d['end']:g} s (the impulsive start and the overshoot). Measured by "
            f"`{d['command']}` on {d['machine']}, finished {d['finished']}, commit {d['commit']}; the wall times "
            f"are comparable within one such run of the script only (the machine may have been shared). The "
            f"force alternation is summarize.py's `force_smoothness` of the sail's z-force from 0.2 s on (1: a sign "
            f"flip every window; the case's CI check requires < 0.02 to 2 s).\n",
            sail_knobs.table(d["rows"]),
            "What each knob does against the shipped case (the wall times from one loaded machine):\n",
            sail_knobs.reading(d["rows"]),
            SAIL_KNOBS_BY_HAND]


def ramair_section():
    """The coupled ram-air wing's resolutions against wall time: the rows studies/ramair/ramair_resolutions.py --docs
    stored (its runs take half an hour, so this script reads them instead of repeating them)."""
    import ramair_resolutions
    path = ROOT / "docs/data/ramair_resolutions.json"
    head = "## Coupled ram-air wing: fluid and structure resolution against wall time\n"
    if not path.exists():
        return [head, "Not measured yet: `/usr/bin/python3 studies/ramair/ramair_resolutions.py --docs` (half an hour).\n"]
    d = json.loads(path.read_text())
    rows = d["rows"]
    trimmed = d["finished"] >= "2026-11-28"  # runs to the trim since the main job of 2026-11-28
    missing = [n for n in ramair_resolutions.VARIANTS if n not in {r["variant"] for r in rows}]
    return [head,
            f"The main job's case (`cases/coupled/ramair-kt`, `coupled.settings`, 2 ranks), the fluid mesh one "
            f"level finer (everywhere, and off the skin only), and the structure 1.5× finer; the wall time is the whole `Allrun.parallel` (meshing, "
            f"rigid start, coupled windows, reconstruction, checkMesh, plots). Measured by `{d['command']}` on "
            f"{d['machine']}, finished {d['finished']}, commit {d['commit']}."
            + (" Each run follows the main job's schedule to its trim (200 windows from rest, then 400 with the "
               "canopy's pseudo-motion carried; the fluid-medium run twice as many windows at half the step), so "
               "the rows compare trimmed states where the balance column is small." if trimmed else
               " The coupled wing has not trimmed after its windows (docs/RAMAIR.md): the rows compare the same "
               "flow time, not converged states. These rows are the main job as it was then (the whole snapped "
               "fluid mesh, taut brake lines, 200 windows from rest); since 2026-11-28 it runs on the mirrored mesh "
               "with slack brake lines, 200 windows from rest and 400 carried to its trim, and its finer variants "
               "wait for a rerun (the fluid-medium one is 1200 windows, about an hour).")
            + ("".join(f" Not in this measurement: {n} ({ramair_resolutions.VARIANTS[n][0]}); `--only {n}` into "
                       "the same `--out` adds it." for n in missing))
            + "\n",
            ramair_resolutions.table(rows)] + ramair_reading(rows) + [
            "![ram-air resolutions](img/ramair_resolutions.png)\n"]


def ramair_reading(rows):
    """What the ram-air rows say, computed from them: which refined runs ended early or unbalanced, and whether
    any refined run gives a resolution error of the coarse answer."""
    lines, usable = [], []
    for r in rows[1:]:
        if "stopped" in r and "new mesh" in r["stopped"]:  # remeshing that could not keep up
            lines.append(f"- {r['variant']}: {r['stopped']} after {r['wall_s']:.0f} s: no figures at this "
                         "resolution. The finer cells next to the skin fold as the canopy moves, and a fresh mesh "
                         "folds again within a few windows, so remeshing does not carry this run to its trim in a "
                         "usable time (docs/COUPLING.md \"Remeshing during a run\", docs/RAMAIR.md; `remesh_max` ends "
                         "such a run by itself).")
        elif "stopped" in r:
            lines.append(f"- {r['variant']}: {r['stopped']} after {r['wall_s']:.0f} s: no figures at this "
                         "resolution (the mesh guard names the cell; docs/COUPLING.md \"When the run stops\").")
        elif r["balance"] > 0.05:
            lines.append(f"- {r['variant']}: the supports and the applied load differ by {100 * r['balance']:.0f} % of the load "
                         "when the run ends: the canopy is still moving, its figures are not this resolution's answer.")
        else:
            usable.append(r)
    if usable:
        lines.append("- resolution error of the coarse run, from " + ", ".join(r["variant"] for r in usable) + ": "
                     + "; ".join(f"CL {100 * (r['CL'] / rows[0]['CL'] - 1):+.1f} %, CD "
                                 f"{100 * (r['CD'] / rows[0]['CD'] - 1):+.1f} % for {r['wall_s'] / rows[0]['wall_s']:.1f}× "
                                 "the time" for r in usable) + ".")
    else:
        lines.append("- so the coarse run's resolution error is not measured yet: no refined run reached a state "
                     "to compare with.")
    return lines + [""]


def summary_lines(res):
    """The top table: one computed sentence per knob (the most typical step)."""
    out = []
    h = next((s for s in res["mesh"] if s["name"] == "hencky"), None)
    if h and len(h["rows"]) >= 2:
        a, b = h["rows"][-2], h["rows"][-1]
        key, floor = ("error_fine", 0.0) if "fine" in h else ("error", h["floor"])
        out.append(("mesh size (Hencky)", buy(f"halving the mesh size ({a['level']} → {b['level']} rings)", a[key],
                                               b[key], a["wall"], b["wall"], floor)))
    s = next((s for s in res["mesh"] if s["name"] == "sphere"), None)
    if s and len(s["rows"]) >= 2:
        a, b = s["rows"][-2], s["rows"][-1]
        out.append(("mesh size (sphere)", buy(f"halving the mesh size ({a['level']} → {b['level']} divisions)",
                                               a["error"], b["error"], a["wall"], b["wall"])))
    r = res["safety"]["rows"]
    out.append(("stable-step safety (transient)", buy(f"safety {r[0]['safety']:g} → {r[-1]['safety']:g}",
                                                       r[0]["error"], r[-1]["error"], r[0]["wall"], r[-1]["wall"])))
    r = res["safety"]["static_rows"]
    out.append(("stable-step safety (static)", buy(f"safety {r[0]['safety']:g} → {r[-1]['safety']:g}",
                                                    r[0]["error"], r[-1]["error"], r[0]["wall"], r[-1]["wall"])))
    r = res["mass_scaling"]["rows"]
    out.append(("mass scaling (transient)", buy(f"min_dt {r[-1]['factor']:g}× the stable step", r[0]["error"],
                                                 r[-1]["error"], r[0]["wall"], r[-1]["wall"])))
    sp = res["mass_scaling"]["sphere"]["rows"]
    fastest = min(sp[1:], key=lambda x: x["wall"])
    out.append(("mass scaling (static sphere, fastest factor)", buy(f"min_dt {fastest['factor']:g}× the step",
                                                                    sp[0]["error"], fastest["error"], sp[0]["wall"],
                                                                    fastest["wall"])))
    k = [x for x in res["dr"]["rows"] if x["method"] == "KDR" and x["converged"]]
    if len(k) >= 2:
        out.append(("DR tolerance (KDR)", buy(f"ε {k[0]['eps']:.0e} → {k[-1]['eps']:.0e}", k[0]["ew"], k[-1]["ew"],
                                               k[0]["wall"], k[-1]["wall"])))
    c = [x for x in res["projection"]["rows"] if x["variant"] == "consistent"]
    out.append(("projection mesh (consistent)", buy(f"halving the mesh size ({c[-2]['n']} → {c[-1]['n']})",
                                                    c[-2]["error"], c[-1]["error"], c[-2]["setup"], c[-1]["setup"],
                                                    cost="the setup time")))
    n = c[-1]["n"]
    d = next(x for x in res["projection"]["rows"] if x["variant"] == "dual" and x["n"] == n)
    out.append(("projection variant", buy(f"dual instead of consistent (n = {n})", c[-1]["error"], d["error"],
                                          c[-1]["setup"], d["setup"], cost="the setup time")))
    q = res["projection"]["quadrature"]
    out.append(("quadrature level", buy(f"level {q[0]['level']} → {q[-1]['level']} (source 10× finer)", q[0]["error"],
                                        q[-1]["error"], q[0]["setup"], q[-1]["setup"],
                                        cost="the setup time")))
    if "coupled" in res:
        cp = res["coupled"]
        a, b = cp["windows"][0], cp["windows"][-1]
        out.append(("coupled: fluid step", buy(f"window {a['window'] * 1e3:g} → {b['window'] * 1e3:g} ms", a["error"],
                                               b["error"], a["wall"], b["wall"])))
        a, b = cp["subcycles"][0], cp["subcycles"][-1]
        out.append(("coupled: subcycling", buy(f"N = {a['subcycles']} → {b['subcycles']}", a["error"], b["error"],
                                               a["wall"], b["wall"])))
        t = [r for r in cp["tolerances"] if r["acceleration"] == "IQN-ILS"]
        out.append(("coupled: tolerance (IQN-ILS)", buy(f"tolerance {t[0]['tolerance']:.0e} → {t[-1]['tolerance']:.0e}"
                                                        " (iteration error)", t[0]["error"], t[-1]["error"],
                                                        t[0]["wall"], t[-1]["wall"])))
        light = [r for r in cp["schemes"] if r["added_mass"] < 1]
        st, im = (next(r for r in light if r["scheme"] == k) for k in ("staggered", "implicit"))
        if st["finite"]:
            out.append(("coupled: staggered (light fluid)", buy("staggered instead of implicit", im["error"],
                                                                st["error"], im["wall"], st["wall"])))
    return out


def write_doc(res, out, command, started, seconds):
    md = ["# Accuracy versus cost\n",
          "What each knob buys and what it costs: the error against a converged or analytical reference and "
          "the wall time, measured. Every number, ratio and sentence below is computed by one command from "
          "this run's measurements (nothing is typed by hand):\n",
          f"```sh\n{command}\n```\n",
          f"Machine: {machine()}; {started} UTC, commit {git_commit()}; load average at the start "
          f"{res['load'][0]:.2f}, at the end {res['load'][1]:.2f}; the whole run took {seconds:.0f} s. "
          "Wall times are the solver's own clock (`summary.json` `stats.wall_seconds`: the step or iteration "
          "loop, without start-up and file output; `timing.json` exists only for coupled runs) and, for the "
          "projection, map-check's `setup_seconds`; runs under 2 s are repeated "
          f"{res['repeats']} times and the median is used. Times on a shared 2-core VM vary by ±20 %: read "
          "ratios within a table, not across tables. *What you buy* compares a row with the row above it "
          "(or the named alternative): \"error 4.0× smaller, 7.9× the time\".\n",
          "| knob | what you buy (one typical step) |", "|---|---|"]
    md += [f"| {k} | {v} |" for k, v in summary_lines(res)]
    md.append("")
    md += cost_mesh.mesh_section(res["mesh"])
    md += cost_integration.integration_sections(res["safety"], res["mass_scaling"])
    md += cost_dr.dr_section(res["dr"])
    md += cost_projection.projection_section(res["projection"])
    if "coupled" in res:
        md += cost_coupled.coupled_section(res["coupled"])
    else:
        md.append(f"## Coupled knobs (added-mass problem): not measured in this run\n\n{res['coupled_missing']}\n")
    md += ramair_section()
    md += sail_section()
    (out / "ACCURACY_COST.md").write_text("\n".join(md))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="reduced set, < 3 min")
    ap.add_argument("--out", default=str(ROOT / "docs"), help="folder for ACCURACY_COST.md and img/ (default docs/)")
    ap.add_argument("--fsi", default=str(fsi_runs.FSI), help="the fsi binary (default build/bin/fsi)")
    ap.add_argument("--coupling-driver", default=str(ROOT / "build/bin/fsi_coupling_cost"),
                    help="the coupled knobs' driver (default build/bin/fsi_coupling_cost)")
    ap.add_argument("--json", help="also write every measured row to this JSON file")
    ap.add_argument("--repeats", type=int, default=3, help="repeats of runs shorter than 2 s (median)")
    args = ap.parse_args()
    fsi_runs.set_fsi(args.fsi)
    if not fsi_runs.FSI.exists():
        sys.exit(f"accuracy_cost.py: {fsi_runs.FSI}: no such file (build it, or give --fsi PATH)")
    out = Path(args.out)
    (out / "img").mkdir(parents=True, exist_ok=True)
    started = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M")
    t0 = time.monotonic()
    load0 = os.getloadavg()[0]
    q = args.quick
    rep = args.repeats

    def step(what):
        print(f"[{time.monotonic() - t0:6.1f} s] {what}", flush=True)

    res = dict(quick=q, repeats=rep)
    step("mesh refinement")
    res["mesh"] = [cost_mesh.mesh_study("hencky", [8, 16, 32] if q else [8, 16, 32, 64], rep),
                   cost_mesh.mesh_study("sphere", [8, 16, 32] if q else [8, 16, 32, 64], rep),
                   cost_mesh.mesh_study("airbag", [8, 16] if q else [8, 16, 32], rep, None if q else 64)]
    step("safety factor")
    ref_safety = 0.05 if q else 0.02  # its own error: (0.05/0.225)² ≈ 5 % of the finest row's in --quick
    res["safety"] = cost_integration.safety_study([0.9, 0.45, 0.225] if q else [0.9, 0.6, 0.45, 0.3, 0.225, 0.15],
                                 [0.9, 0.45] if q else [0.9, 0.6, 0.45, 0.3], ref_safety, rep)
    step("mass scaling")
    res["mass_scaling"] = cost_integration.mass_scaling_study([1, 1.5, 2] if q else [1, 1.1, 1.25, 1.5, 2, 3], ref_safety,
                                             32 if q else 64, rep)
    step("dynamic relaxation")
    res["dr"] = cost_dr.dr_study(["KDR", "oDR"] if q else list(dr_accuracy_cost.METHODS),
                         [1e-2, 1e-4, 1e-6] if q else dr_accuracy_cost.EPS, rep)
    step("projection")
    with tempfile.TemporaryDirectory() as work:
        res["projection"] = cost_projection.projection_study([8, 16, 32] if q else [8, 16, 32, 64, 128],
                                             [1, 2, 4, 8] if q else [1, 2, 4, 8, 16], rep, Path(work))
    driver = Path(args.coupling_driver)
    if driver.exists():
        step("coupled knobs")
        res["coupled"] = cost_coupled.coupled_study(driver, q, rep)
    else:
        res["coupled_missing"] = f"{driver} not found: build it (`cmake --build build --target fsi_coupling_cost`)."
    step("plots and document")
    cost_mesh.mesh_plot(res["mesh"], out / "img/accuracy_cost_mesh.png")
    cost_integration.integration_plot(res["safety"], res["mass_scaling"], out / "img/accuracy_cost_time.png")
    cost_dr.dr_plot(res["dr"], out / "img/accuracy_cost_dr.png")
    cost_projection.projection_plot(res["projection"], out / "img/accuracy_cost_projection.png")
    if "coupled" in res:
        cost_coupled.coupled_plot(res["coupled"], out / "img/accuracy_cost_coupled.png")
    res["load"] = (load0, os.getloadavg()[0])
    # The command as run from the repository root (paths inside it relative to it).
    def shown(a):
        try:
            return str(Path(a).resolve().relative_to(ROOT)) if Path(a).exists() else a
        except ValueError:
            return a
    command = " ".join(["/usr/bin/python3 studies/cost/accuracy_cost.py"] + [shlex.quote(shown(a)) for a in sys.argv[1:]])
    write_doc(res, out, command, started, time.monotonic() - t0)
    if args.json:
        Path(args.json).write_text(json.dumps(res, indent=1))
    step(f"wrote {out / 'ACCURACY_COST.md'} and {out / 'img'}/accuracy_cost_*.png")


if __name__ == "__main__":
    main()
