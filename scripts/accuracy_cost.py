#!/usr/bin/env python3
"""Accuracy versus cost, one knob at a time: for each knob the error against a converged or analytical
reference and the wall time it costs, as tables with a computed "what you buy" sentence per step, and
log-log plots of error against time. Writes OUT/ACCURACY_COST.md and OUT/img/accuracy_cost_*.png (OUT:
docs/ by default) and, with --json, every measured row for the test tests/cost/test_accuracy_cost.py.

Knobs: mesh refinement (Hencky, pressurised sphere, airbag), the safety factor on the stable step, selective
mass scaling, the dynamic-relaxation method and tolerance (scripts/dr_accuracy_cost.py's measurement), the
projection variant, mesh and quadrature level of `fsi map-check`; the coupled knobs (fluid step, subcycling,
acceleration and tolerance, staggered or implicit) on the added-mass problem through the driver
fsi_coupling_cost (tests/cost/coupling_cost.cpp). The coupled sail: not yet (the doc says why).

Usage: scripts/accuracy_cost.py [--quick] [--out DIR] [--fsi PATH] [--coupling-driver PATH] [--json FILE]
                                [--repeats N]
  --quick   reduced set (< 3 min on 2 cores): the coarser levels of every knob
Wall time: the solver's own clock (summary.json stats.wall_seconds: the step or iteration loop, without
start-up and file output) for `fsi run`; setup_seconds of the map-check report for the projection. Runs
shorter than 2 s are repeated (--repeats, default 3) and the median is used."""
import argparse
import datetime
import json
import math
import os
import platform
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import dr_accuracy_cost  # noqa: E402
import fsi_runs  # noqa: E402
from fsi_runs import MESH_STUDIES, ROOT  # noqa: E402

# ---------------------------------------------------------------------------------------------------------
# Words from numbers


def times(x):
    """A ratio as the doc prints it: 2 significant digits below 10, whole numbers above."""
    return f"{x:.0f}" if x >= 9.95 else f"{x:.1f}"


def buy(change, e0, e1, t0, t1, floor=0.0):
    """'change: error 4.0× smaller, 7.9× the time' from the errors and times before (0) and after (1).
    Errors at or below `floor` (the reference's own precision) are not compared."""
    if e1 <= floor and e0 <= floor:
        err = "error below the reference's precision before and after"
    elif e1 <= floor:
        err = f"error from {e0:.2g} to below the reference's precision ({floor:.1g})"
    elif e1 <= e0:
        err = f"error {times(e0 / e1)}× smaller"
    else:
        err = f"error {times(e1 / e0)}× larger"
    if e0 > floor and e1 > floor and max(e0 / e1, e1 / e0) > 30:
        err += f" ({e0:.1e} → {e1:.1e})"
    return f"{change}: {err}, {times(t1 / t0)}× the time"


def order(h, e):
    """Observed convergence orders between successive levels: log(e_i/e_{i+1}) / log(h_i/h_{i+1})."""
    return [math.log(e[i] / e[i + 1]) / math.log(h[i] / h[i + 1]) if e[i] > 0 and e[i + 1] > 0 else float("nan")
            for i in range(len(e) - 1)]


def fmt_orders(p):
    return ", ".join(f"{x:.2f}" for x in p)


# ---------------------------------------------------------------------------------------------------------
# Mesh refinement


def mesh_study(name, levels, repeats, finest_reference=None):
    """Runs MESH_STUDIES[name] at each level. Error against the study's analytical/published reference and,
    if finest_reference is a level, against that (finer, not tabulated) solution too. Also the observed order
    from successive differences (independent of any reference) and the Richardson extrapolation."""
    st = MESH_STUDIES[name]
    rows = []
    for n in levels:
        s = fsi_runs.run_timed(st["case"], st["sets"](n), repeats=repeats)
        v = s["probes"][st["probe"]]
        rows.append(dict(level=n, h=st["h"](n), elements=s["stats"]["membrane_elements"], value=v,
                         steps=s["stats"]["steps"], wall=s["wall"], wall_runs=s["wall_runs"],
                         error=abs(v / st["reference"] - 1)))
    out = dict(name=name, rows=rows, reference=st["reference"], reference_text=st["reference_text"],
               floor=st["reference_resolution"] / abs(st["reference"]), expected_order=st["expected_order"])
    if finest_reference:
        s = fsi_runs.run(st["case"], st["sets"](finest_reference))
        vf = s["probes"][st["probe"]]
        out["fine"] = dict(level=finest_reference, value=vf, wall=s["stats"]["wall_seconds"],
                           elements=s["stats"]["membrane_elements"])
        for r in rows:
            r["error_fine"] = abs(r["value"] / vf - 1)
    v = [r["value"] for r in rows]
    h = [r["h"] for r in rows]
    if len(v) >= 3:
        d = [abs(v[i] - v[i + 1]) for i in range(len(v) - 1)]
        out["difference_orders"] = order(h[:-1], d)
        p = out["difference_orders"][-1]
        q = h[-2] / h[-1]
        if st["expected_order"] and p == p and p > 0:
            out["richardson"] = v[-1] + (v[-1] - v[-2]) / (q ** p - 1)
    return out


def mesh_section(studies):
    md = ["## Mesh refinement\n",
          "Each level halves the element size (rings of the Hencky disc, divisions of the sphere octant, squares "
          "per airbag face). Error: relative to the reference named in the heading. *Order from differences*: "
          "log(|v₁−v₂|/|v₂−v₃|)/log 2 over three successive levels, which needs no reference; *Richardson*: the "
          "finest two values extrapolated with that order. Expected: second order (linear triangles, smooth "
          "solution); the airbag's wrinkled band along the seam is not smooth, and its deflection is not "
          "monotone in the mesh.\n",
          "![mesh refinement: error against wall time](img/accuracy_cost_mesh.png)\n"]
    for s in studies:
        st = MESH_STUDIES[s["name"]]
        u, un = st["unit"], st["unit_name"]
        title = {"hencky": "Hencky membrane (`cases/structure/hencky`), centre deflection",
                 "sphere": "Pressurised sphere (`cases/structure/sphere`, E = 3000 MPa, 10 kPa), mean radial "
                           "displacement",
                 "airbag": "Square airbag (`cases/structure/airbag`), centre displacement"}[s["name"]]
        md.append(f"### {title}\n")
        md.append(f"Reference: {s['reference_text']}." + (
            f" Also against the {s['fine']['level']} {st['level_name']} solution ({s['fine']['elements']} "
            f"triangles, {s['fine']['value'] / u:.3f} {un}, {s['fine']['wall']:.1f} s), the converged value "
            "of this model (the *error vs finest* leaves out the finest mesh's own error, at order p about "
            "1/(2^p − 1) of the last row's)." if "fine" in s else "") + "\n")
        fine = "fine" in s
        md.append(f"| {st['level_name']} | triangles | value [{un}] | error | "
                  + ("error vs finest | " if fine else "") + "steps | wall [s] | what you buy (from the row above) |")
        md.append("|---|---|---|---|---|---|---|" + ("---|" if fine else ""))
        for i, r in enumerate(s["rows"]):
            key = "error_fine" if fine else "error"
            words = ""
            if i > 0:
                p = s["rows"][i - 1]
                words = buy(f"halving the mesh size ({p['level']} → {r['level']})", p[key], r[key], p["wall"],
                            r["wall"], 0.0 if fine else s["floor"])
            err = f"{r['error']:.2e}" + (" (within the reference's precision)" if r["error"] <= s["floor"] else "")
            md.append(f"| {r['level']} | {r['elements']} | {r['value'] / u:.4f} | {err} | "
                      + (f"{r['error_fine']:.2e} | " if fine else "")
                      + f"{r['steps']} | {r['wall']:.3f} | {words} |")
        extra = []
        if "difference_orders" in s:
            extra.append(f"order from differences: {fmt_orders(s['difference_orders'])}")
        if "richardson" in s:
            extra.append(f"Richardson extrapolation {s['richardson'] / u:.4f} {un} "
                         f"({100 * (s['richardson'] / s['reference'] - 1):+.3f} % from the reference)")
        if extra:
            md.append("\n" + "; ".join(extra) + ".\n")
        else:
            md.append("")
    return md


def mesh_plot(studies, path):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for s in studies:
        key = "error_fine" if "fine" in s else "error"
        w = [r["wall"] for r in s["rows"]]
        e = [max(r[key], 1e-9) for r in s["rows"]]
        label = s["name"] + (" (vs finest mesh)" if "fine" in s else " (vs reference)")
        ax.loglog(w, e, "o-", label=label)
        for r, x, y in zip(s["rows"], w, e):
            ax.annotate(str(r["level"]), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error")
    ax.set_title("Mesh refinement (labels: rings / divisions / squares per face)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------------------
# Time integration: safety factor and mass scaling, on the Hencky transient

TRANSIENT_CASE = "hencky"
TRANSIENT_RINGS = 32
TRANSIENT_END = 2.0e-3  # s: after the first overshoot (39 mm at 1.5 ms), on the way back down


def transient(extra_time, repeats):
    """The Hencky disc (TRANSIENT_RINGS rings) loaded at once, run to TRANSIENT_END; returns (summary, centre
    deflection). `extra_time`: entries of the time section beyond `end`."""
    tsec = ", ".join([f"end: {TRANSIENT_END}"] + [f"{k}: {v}" for k, v in extra_time.items()])
    s = fsi_runs.run_timed(TRANSIENT_CASE, [f"meshes.disc.generator.rings={TRANSIENT_RINGS}", f"time={{{tsec}}}"],
                           repeats=repeats)
    return s, s["probes"]["center_deflection"]


def static_hencky(extra, repeats):
    s = fsi_runs.run_timed("hencky", [f"meshes.disc.generator.rings={TRANSIENT_RINGS}"] + extra, repeats=repeats)
    return s, s["probes"]["center_deflection"]


def safety_study(safeties, static_safeties, ref_safety, repeats):
    ref, w_ref = transient({"safety": ref_safety}, 1)
    rows = []
    for sf in safeties:
        s, w = transient({"safety": sf}, repeats)
        rows.append(dict(safety=sf, value=w, error=abs(w / w_ref - 1), steps=s["stats"]["steps"], wall=s["wall"],
                         dt=s["stats"]["last_dt"]))
    st_ref, ws_ref = static_hencky(["time.until_static.tolerance=1.0e-14"], 1)
    static_rows = []
    for sf in static_safeties:
        s, w = static_hencky([f"time.safety={sf}"], repeats)
        static_rows.append(dict(safety=sf, value=w, error=abs(w / ws_ref - 1), steps=s["stats"]["steps"],
                                wall=s["wall"]))
    p = order([r["safety"] for r in rows], [r["error"] for r in rows])
    return dict(reference=dict(safety=ref_safety, value=w_ref, steps=ref["stats"]["steps"]), rows=rows,
                orders=p, static_reference=dict(value=ws_ref, steps=st_ref["stats"]["steps"]), static_rows=static_rows)


def mass_scaling_study(factors, ref_safety, sphere_divisions, repeats):
    """mass_scaling_min_dt = factor × the step of the unscaled run (safety 0.9 × its stable step). Transient:
    error against the unscaled reference at safety ref_safety; static: against the unscaled static answer
    at until_static tolerance 1e-14. Then the static sphere octant, whose few small corner elements are what
    mass scaling is for."""
    base, _ = transient({}, 1)
    dt0 = 0.9 * base["stats"]["stable_dt"]
    ref, w_ref = transient({"safety": ref_safety}, 1)
    st0, ws0 = static_hencky(["time.until_static.tolerance=1.0e-14"], 1)
    rows = []
    for f in factors:
        extra = {"mass_scaling_min_dt": f * dt0} if f > 1 else {}
        s, w = transient(extra, repeats)
        sets = [f"time.mass_scaling_min_dt={f * dt0}"] if f > 1 else []
        ss, ws = static_hencky(sets, repeats)
        rows.append(dict(factor=f, min_dt=f * dt0 if f > 1 else 0.0, added=s["stats"]["added_mass_fraction"],
                         value=w, error=abs(w / w_ref - 1), steps=s["stats"]["steps"], wall=s["wall"],
                         static_value=ws, static_error=abs(ws / ws0 - 1), static_steps=ss["stats"]["steps"],
                         static_wall=ss["wall"]))
    # The sphere octant has a few small elements (at its corners): there a small factor adds little mass.
    sets = [f"meshes.sphere.generator.divisions={sphere_divisions}"]
    base = fsi_runs.run("sphere", sets)
    dt_s = 0.9 * base["stats"]["stable_dt"]
    r_s = fsi_runs.run("sphere", sets + ["time.until_static.tolerance=1.0e-14"])["probes"]["radial_displacement"]
    sphere_rows = []
    for f in factors:
        s = fsi_runs.run_timed("sphere", sets + ([f"time.mass_scaling_min_dt={f * dt_s}"] if f > 1 else []),
                               repeats=repeats)
        v = s["probes"]["radial_displacement"]
        sphere_rows.append(dict(factor=f, added=s["stats"]["added_mass_fraction"], value=v, error=abs(v / r_s - 1),
                                steps=s["stats"]["steps"], wall=s["wall"]))
    return dict(dt0=dt0, reference=w_ref, ref_safety=ref_safety, static_reference=ws0, rows=rows,
                sphere=dict(divisions=sphere_divisions, dt0=dt_s, reference=r_s, rows=sphere_rows))


def integration_sections(saf, ms):
    md = ["## Time integration: safety factor on the stable step\n",
          f"**Transient.** The Hencky disc ({TRANSIENT_RINGS} rings, its mass damping) loaded at once by the "
          f"full pressure and run to t = {TRANSIENT_END * 1e3:g} ms, after the first overshoot (39 mm at 1.5 ms) "
          "on the way back down; "
          f"error of the centre deflection against the same run at `time.safety={saf['reference']['safety']}` "
          f"({saf['reference']['steps']} steps, {saf['reference']['value'] * 1e3:.4f} mm). Central differences "
          "are second order in Δt and Δt is proportional to the safety factor, so the error should fall as "
          "safety².\n",
          "![safety factor and mass scaling: error against wall time](img/accuracy_cost_time.png)\n",
          "| `time.safety` | last Δt [µs] | steps | deflection [mm] | error | wall [s] | what you buy (from the row above) |",
          "|---|---|---|---|---|---|---|"]
    for i, r in enumerate(saf["rows"]):
        words = ""
        if i > 0:
            p = saf["rows"][i - 1]
            words = buy(f"safety {p['safety']:g} → {r['safety']:g}", p["error"], r["error"], p["wall"], r["wall"])
        md.append(f"| {r['safety']:g} | {r['dt'] * 1e6:.3f} | {r['steps']} | {r['value'] * 1e3:.4f} | "
                  f"{r['error']:.2e} | {r['wall']:.3f} | {words} |")
    md.append(f"\nObserved order in the safety factor: {fmt_orders(saf['orders'])} (expected 2).\n")
    md.append(f"**Static answer** (`until_static`, the case as shipped at {TRANSIENT_RINGS} rings): error against the same mesh "
              f"at until_static tolerance 1e-14 ({saf['static_reference']['value'] * 1e3:.5f} mm). The step does not "
              "enter the static equilibrium: the error left is that of the stop criterion (KE/U < 1e-10), and a "
              "smaller step only makes the damped path to the static state longer.\n")
    md.append("| `time.safety` | steps | deflection [mm] | error | wall [s] | what you buy (from the row above) |")
    md.append("|---|---|---|---|---|---|")
    for i, r in enumerate(saf["static_rows"]):
        words = ""
        if i > 0:
            p = saf["static_rows"][i - 1]
            words = buy(f"safety {p['safety']:g} → {r['safety']:g}", p["error"], r["error"], p["wall"], r["wall"])
        md.append(f"| {r['safety']:g} | {r['steps']} | {r['value'] * 1e3:.5f} | {r['error']:.2e} | {r['wall']:.3f} "
                  f"| {words} |")
    md += ["", "## Time integration: selective mass scaling\n",
           "`time.mass_scaling_min_dt` = factor × the stable step of the unscaled run "
           f"({ms['dt0'] * 1e6:.3f} µs: 0.9 × its stable step): the density of every element whose step is below it is "
           "raised just enough. The disc's elements all have nearly the same step, so the added mass grows fast "
           "with the factor (second column) and the transient slows down: the error is the physics changed, "
           "not a discretisation error. "
           f"Transient error against the unscaled run at safety {ms['ref_safety']:g} (as above); static error against the "
           "unscaled static answer at until_static tolerance 1e-14 (mass does not enter the static equilibrium).\n",
           "| factor | added mass | transient: steps | error | wall [s] | static: steps | error | wall [s] | "
           "what you buy (transient; static) |",
           "|---|---|---|---|---|---|---|---|---|"]
    r0 = ms["rows"][0]
    for r in ms["rows"]:
        words = ""
        if r is not r0:
            words = (buy(f"min_dt {r['factor']:g}× the stable step", r0["error"], r["error"], r0["wall"], r["wall"])
                     + "; static: " + f"{times(r['static_wall'] / r0['static_wall'])}× the time, error "
                     f"{r['static_error']:.1e}")
        md.append(f"| {r['factor']:g}{' (off)' if r['factor'] <= 1 else ''} | {100 * r['added']:.1f} % | "
                  f"{r['steps']} | {r['error']:.2e} | {r['wall']:.3f} | {r['static_steps']} | "
                  f"{r['static_error']:.1e} | {r['static_wall']:.3f} | {words} |")
    sp = ms["sphere"]
    md += ["", f"**Where it is meant to help**: the pressurised sphere octant ({sp['divisions']} divisions, static, "
           "`until_static`), whose corner elements are smaller than the rest; factor × its step "
           f"({sp['dt0'] * 1e6:.3f} µs), error against the unscaled answer at until_static tolerance 1e-14 "
           f"({sp['reference'] * 1e3:.6f} mm).\n",
           "| factor | added mass | steps | mean radial displacement [mm] | error | wall [s] | what you buy (against no scaling) |",
           "|---|---|---|---|---|---|---|"]
    r0 = sp["rows"][0]
    for r in sp["rows"]:
        words = "" if r is r0 else buy(f"min_dt {r['factor']:g}× the step", r0["error"], r["error"], r0["wall"],
                                       r["wall"])
        md.append(f"| {r['factor']:g}{' (off)' if r['factor'] <= 1 else ''} | {100 * r['added']:.2f} % | "
                  f"{r['steps']} | {r['value'] * 1e3:.6f} | {r['error']:.1e} | {r['wall']:.3f} | {words} |")
    worst = max([r["static_error"] for r in ms["rows"]] + [r["error"] for r in sp["rows"]])
    md.append(f"\nLargest change of a static answer by mass scaling: {worst:.1e} (the transient's: up to "
              f"{max(r['error'] for r in ms['rows']):.1e}). Mass is not in the static equilibrium; it changes only "
              "the damped path to it, and the stop criterion (KE/U < 1e-10) along that path.\n")
    return md


def integration_plot(saf, ms, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    ax = axes[0]
    ax.loglog([r["wall"] for r in saf["rows"]], [max(r["error"], 1e-12) for r in saf["rows"]], "o-",
              label="safety factor (transient)")
    for r in saf["rows"]:
        ax.annotate(f"{r['safety']:g}", (r["wall"], max(r["error"], 1e-12)), textcoords="offset points",
                    xytext=(4, 4), fontsize=7)
    ax.loglog([r["wall"] for r in ms["rows"]], [max(r["error"], 1e-12) for r in ms["rows"]], "s--",
              label="mass scaling (transient)")
    for r in ms["rows"]:
        ax.annotate(f"×{r['factor']:g}", (r["wall"], max(r["error"], 1e-12)), textcoords="offset points",
                    xytext=(4, -10), fontsize=7)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error of the centre deflection")
    ax.set_title(f"Hencky transient, t = {TRANSIENT_END * 1e3:g} ms")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax = axes[1]
    ax.semilogx([r["safety"] for r in saf["static_rows"]], [r["wall"] for r in saf["static_rows"]], "o-",
                label="safety factor")
    ax.set_xlabel("time.safety")
    ax.set_ylabel("wall time to the static state [s]")
    ax.set_title("Hencky static answer: the step only costs")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------------------
# Dynamic relaxation


def dr_study(methods, eps, repeats):
    ref, rows = dr_accuracy_cost.measure(methods, eps, repeats)
    return dict(reference=dict(iterations=ref["stats"]["iterations"], value=ref["probes"]["center_displacement"]),
                rows=rows)


def dr_section(dr):
    md = ["## Static answers by dynamic relaxation: method and tolerance\n",
          "The 25×25 square cushion (`cases/structure/cushion-square-25`, 2028 dof), measured by "
          "`scripts/dr_accuracy_cost.py`'s `measure()`; error of the centre displacement against the "
          f"KDR solution at ε = 1e-10 ({dr['reference']['iterations']} iterations, "
          f"{dr['reference']['value'] * 1e3:.4f} mm). Methods: docs/DYNAMIC_RELAXATION.md.\n",
          "![dynamic relaxation: error against iterations and wall time](img/accuracy_cost_dr.png)\n",
          "| method | ε | iterations | wall [ms] | error | what you buy (from the row above) |",
          "|---|---|---|---|---|---|"]
    prev = None
    for r in dr["rows"]:
        words = ""
        conv = "" if r["converged"] else " (not converged)"
        if prev is not None and prev["method"] == r["method"] and prev["converged"] and r["converged"]:
            words = buy(f"ε {prev['eps']:.0e} → {r['eps']:.0e}", prev["ew"], r["ew"], prev["wall"], r["wall"])
        md.append(f"| {r['method']} | {r['eps']:.0e} | {r['it']}{conv} | {r['wall'] * 1e3:.1f} | {r['ew']:.2e} | "
                  f"{words} |")
        prev = r
    kdr = {r["eps"]: r for r in dr["rows"] if r["method"] == "KDR"}
    lines = []
    for r in dr["rows"]:
        k = kdr.get(r["eps"])
        if r["method"] != "KDR" and k and r["converged"] and k["converged"]:
            lines.append("* " + buy(f"{r['method']} instead of KDR at ε = {r['eps']:.0e}", k["ew"], r["ew"],
                                    k["wall"], r["wall"]))
    if lines:
        md += ["", "Other methods against the default (KDR) at the same ε:\n"] + lines
    md.append("")
    return md


# ---------------------------------------------------------------------------------------------------------
# Projection between non-matching meshes (fsi map-check)

ARC = math.radians(70.0)  # a cylinder patch, radius 1 m, length 1 m: curved like a canopy panel


def write_cylinder_msh(path, n, quads, seed):
    """A Gmsh MSH 2.2 ASCII patch of the cylinder r = 1, 0 ≤ θ ≤ 70°, 0 ≤ z ≤ 1: n×n cells, interior nodes
    moved at random by up to ±0.2 cell (seeded), cells split into two triangles or kept as quads. The two
    meshes of a check differ in n, element kind and perturbation: non-matching everywhere."""
    rng = np.random.default_rng(seed)
    u = np.linspace(0.0, 1.0, n + 1)
    uu, vv = np.meshgrid(u, u, indexing="ij")
    inner = (uu > 0) & (uu < 1) & (vv > 0) & (vv < 1)
    uu = uu + inner * rng.uniform(-0.2, 0.2, uu.shape) / n
    vv = vv + inner * rng.uniform(-0.2, 0.2, vv.shape) / n
    nodes = [(math.cos(ARC * a), math.sin(ARC * a), b) for a, b in zip(uu.ravel(), vv.ravel())]
    idx = lambda i, j: i * (n + 1) + j + 1  # noqa: E731
    cells = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            cells += [(3, (a, b, c, d))] if quads else [(2, (a, b, c)), (2, (a, c, d))]
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", str(len(nodes))]
    lines += [f"{k + 1} {x:.17g} {y:.17g} {z:.17g}" for k, (x, y, z) in enumerate(nodes)]
    lines += ["$EndNodes", "$Elements", str(len(cells))]
    lines += [f"{k + 1} {t} 2 1 1 " + " ".join(map(str, c)) for k, (t, c) in enumerate(cells)]
    lines += ["$EndElements", ""]
    Path(path).write_text("\n".join(lines))


def map_check_timed(a, b, args, repeats):
    """One map-check, repeated `repeats` times for the setup time (median), errors from the first."""
    reports = [fsi_runs.map_check(a, b, args) for _ in range(max(1, repeats))]
    d = reports[0]["directions"][0]
    setups = sorted(r["directions"][0]["setup_seconds"] for r in reports)
    applies = sorted(r["directions"][0]["apply_seconds_vector"] for r in reports)
    return dict(error=d["quadratic_error"]["rms"], error_max=d["quadratic_error"]["max"],
                linear=d["linear_error"]["max"], source_nodes=d["source_nodes"], target_nodes=d["target_nodes"],
                setup=setups[len(setups) // 2], apply=applies[len(applies) // 2],
                unmapped=d["unmapped_quadrature_points"], force=d["conservative_force_error"])


def projection_study(sizes, levels, repeats, work):
    """Variant × mesh: structure-like triangles (n×n cells) → fluid-like quads 1.38× finer, the displacement
    direction; error of the quadratic test field. Quadrature level: a fine source (80×80 cells) mapped onto a
    10× coarser target (8×8 quads), where the level matters (docs/PROJECTION.md, "Quadrature")."""
    rows = []
    for n in sizes:
        src, dst = work / f"tri-{n}.msh", work / f"quad-{n}.msh"
        write_cylinder_msh(src, n, False, 1000 + n)
        write_cylinder_msh(dst, round(1.38 * n), True, 2000 + n)
        for variant in ("consistent", "dual", "lumped"):
            r = map_check_timed(src, dst, ["--variant", variant], repeats)
            rows.append(dict(n=n, h=1.0 / n, variant=variant, **r))
    fine, coarse = work / "tri-fine.msh", work / "quad-coarse.msh"
    write_cylinder_msh(fine, 80, False, 3000)
    write_cylinder_msh(coarse, 8, True, 3001)
    qrows = []
    for level in levels:
        r = map_check_timed(fine, coarse, ["--quadrature-level", str(level)], repeats)
        qrows.append(dict(level=level, **r))
    orders = {v: order([r["h"] for r in rows if r["variant"] == v], [r["error"] for r in rows if r["variant"] == v])
              for v in ("consistent", "dual", "lumped")}
    return dict(rows=rows, orders=orders, quadrature=qrows)


def projection_section(pr):
    md = ["## Projection between non-matching meshes: variant, mesh and quadrature level\n",
          "`fsi map-check SRC DST --json` on a curved patch (cylinder r = 1 m, 70° arc, 1 m long; both meshes "
          "perturbed at random by ±0.2 cell): source n×n cells of triangles (the structure), target 1.38n×1.38n "
          "quads (the fluid); direction source → target (displacements). Error: RMS nodal error of map-check's "
          "quadratic test field relative to its range. Cost: the setup (search, assembly, factorisation), done "
          "once per run; the apply (one 3-component transfer) is listed too: it is paid every coupling "
          "iteration.\n",
          "![projection: error against setup time](img/accuracy_cost_projection.png)\n",
          "| n | source / target nodes | variant | error (RMS) | linear field max error | setup [ms] | apply [µs] | "
          "what you buy |",
          "|---|---|---|---|---|---|---|---|"]
    by = {(r["variant"], r["n"]): r for r in pr["rows"]}
    sizes = sorted({r["n"] for r in pr["rows"]})
    for r in pr["rows"]:
        words = []
        i = sizes.index(r["n"])
        if i > 0:
            p = by[(r["variant"], sizes[i - 1])]
            words.append(buy(f"halving the mesh size ({p['n']} → {r['n']})", p["error"], r["error"], p["setup"],
                             r["setup"]))
        if r["variant"] != "consistent":
            c = by[("consistent", r["n"])]
            words.append(buy(f"{r['variant']} instead of consistent", c["error"], r["error"], c["setup"], r["setup"]))
        md.append(f"| {r['n']} | {r['source_nodes']} / {r['target_nodes']} | {r['variant']} | {r['error']:.2e} | "
                  f"{r['linear']:.1e} | {r['setup'] * 1e3:.2f} | {r['apply'] * 1e6:.1f} | {'; '.join(words)} |")
    md.append("\nObserved orders (RMS error, successive halvings): "
              + "; ".join(f"{v} {fmt_orders(p)}" for v, p in pr["orders"].items())
              + " (expected 2 for consistent and dual; lumped is first order on irregular meshes).\n")
    q = pr["quadrature"]
    md += [f"**Quadrature level** (consistent): a fine source ({q[0]['source_nodes']} nodes, 80×80 cells) onto a "
           f"10× coarser target ({q[0]['target_nodes']} nodes, 8×8 quads), the case where one 3-point rule per "
           "target triangle samples the source too sparsely.\n",
           "| `--quadrature-level` | error (RMS) | max error | setup [ms] | what you buy (from the row above) |",
           "|---|---|---|---|---|"]
    for i, r in enumerate(q):
        words = ""
        if i > 0:
            p = q[i - 1]
            words = buy(f"level {p['level']} → {r['level']}", p["error"], r["error"], p["setup"], r["setup"])
        md.append(f"| {r['level']} | {r['error']:.2e} | {r['error_max']:.2e} | {r['setup'] * 1e3:.2f} | {words} |")
    md.append("\nThe error measured here is that of a smooth field carried from the fine source to the coarse "
              "target, where the 3-point rule per target triangle already integrates well. What the level is for "
              "is the other direction of the same operator: Hᵀ hands a coarse target's forces only to the source "
              "nodes near its quadrature points (docs/PROJECTION.md, \"Quadrature\"), which map-check's field "
              "errors do not measure.\n")
    return md


def projection_plot(pr, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    ax = axes[0]
    for v in ("consistent", "dual", "lumped"):
        rs = [r for r in pr["rows"] if r["variant"] == v]
        ax.loglog([r["setup"] * 1e3 for r in rs], [r["error"] for r in rs], "o-", label=v)
        for r in rs:
            ax.annotate(str(r["n"]), (r["setup"] * 1e3, r["error"]), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
    ax.set_xlabel("setup time [ms]")
    ax.set_ylabel("RMS error, quadratic field (rel. to range)")
    ax.set_title("Variant and mesh (labels: n)")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax = axes[1]
    q = pr["quadrature"]
    ax.loglog([r["setup"] * 1e3 for r in q], [r["error"] for r in q], "o-")
    for r in q:
        ax.annotate(f"L={r['level']}", (r["setup"] * 1e3, r["error"]), textcoords="offset points", xytext=(4, 4),
                    fontsize=7)
    ax.set_xlabel("setup time [ms]")
    ax.set_ylabel("RMS error, quadratic field (rel. to range)")
    ax.set_title("Quadrature level, source 10× finer than target")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def dr_plot(dr, path):
    dr_accuracy_cost.plot(dr["rows"], path, "Dynamic relaxation, 25×25 cushion: error against cost")


# ---------------------------------------------------------------------------------------------------------
# Coupled knobs: the added-mass drum (tests/cost/coupling_cost.cpp, the real structure + a reduced fluid)

DRUM_PEXT, DRUM_AREAL_MASS, DRUM_END = 200.0, 1.0, 0.02  # Pa, kg/m² (ρt of the film), s


def drum_analytic(added_mass, t=DRUM_END):
    """Centre of the flat, unstressed drum under a suddenly applied pressure: until the membrane's tension
    (second order in the deflection) matters, the centre accelerates freely, w = p t² / (2 (ρt + m_a))."""
    return DRUM_PEXT * t * t / (2.0 * (DRUM_AREAL_MASS + added_mass))


def drum(driver, args, repeats):
    """One fsi_coupling_cost call (median wall of `repeats`); its JSON."""
    def once():
        with tempfile.TemporaryDirectory() as out:
            p = subprocess.run([str(driver), "--end", str(DRUM_END), "--out", out, *map(str, args)],
                               capture_output=True, text=True)
        if p.returncode != 0:
            raise fsi_runs.RunFailed(f"{driver} {' '.join(map(str, args))}: exit code {p.returncode}\n{p.stderr}")
        return json.loads(p.stdout)
    runs = [once() for _ in range(max(1, repeats))]
    r = runs[0]
    r["wall"] = sorted(x["wall_seconds"] for x in runs)[len(runs) // 2]
    return r


def coupled_study(driver, quick, repeats):
    ma = 5.0
    w_exact = drum_analytic(ma)
    mono = drum(driver, ["--monolithic", "--added-mass", ma, "--safety", 0.05], 1)
    base = ["--added-mass", ma, "--scheme", "implicit", "--acceleration", "IQN-ILS"]

    def row(args, ref, **extra):
        r = drum(driver, args, repeats)
        r.update(extra)
        r["error"] = abs(r["centre"] / ref - 1) if r["finite"] else float("nan")
        return r

    windows = [1e-3, 0.5e-3, 0.25e-3] if quick else [1e-3, 0.5e-3, 0.25e-3, 0.125e-3, 0.0625e-3]
    wrows = [row(base + ["--window", w, "--tolerance", 1e-8], w_exact, window=w) for w in windows]
    subs = [1, 4] if quick else [1, 2, 4, 8, 16]
    srows = [row(base + ["--window", 0.25e-3, "--tolerance", 1e-8, "--subcycles", n], w_exact, subcycles=n)
             for n in subs]
    # Iteration error: against the same window converged to 1e-12 (the scheme's own answer).
    tight = drum(driver, base + ["--window", 0.25e-3, "--tolerance", 1e-12], 1)
    tols = [1e-2, 1e-4, 1e-6] if quick else [1e-2, 1e-3, 1e-4, 1e-6, 1e-8]
    accs = {"IQN-ILS": ["--acceleration", "IQN-ILS"], "Aitken": ["--acceleration", "Aitken"],
            "constant ω = 0.25": ["--acceleration", "constant", "--omega", 0.25]}
    trows = []
    for name, a in accs.items():
        for tol in tols:
            r = row(["--added-mass", ma, "--scheme", "implicit", *a, "--window", 0.25e-3, "--tolerance", tol],
                    tight["centre"], acceleration=name, tolerance=tol)
            r["error_exact"] = abs(r["centre"] / w_exact - 1)
            trows.append(r)
    # Staggered against implicit: a light fluid (below the staggered limit m_a/m_s < 1/3) and the heavy one.
    grows = []
    for m in (0.1, ma):
        for scheme in ("staggered", "implicit"):
            grows.append(row(["--added-mass", m, "--scheme", scheme, "--window", 0.25e-3, "--tolerance", 1e-8],
                             drum_analytic(m), added_mass=m, scheme=scheme))
    return dict(added_mass=ma, exact=w_exact, monolithic=mono["centre"], windows=wrows,
                window_orders=order([r["window"] for r in wrows], [r["error"] for r in wrows]), subcycles=srows,
                tight=tight["centre"], tolerances=trows, schemes=grows)


def coupled_section(cp):
    ma = cp["added_mass"]
    md = ["## Coupled knobs: fluid step, subcycling, coupling scheme and tolerance (added-mass problem)\n",
          f"The drum film of the coupled tests (1 m square, 8×8 cross-pattern squares, normal motion only) under a "
          f"suddenly applied {DRUM_PEXT:g} Pa with a heavy incompressible fluid reduced to its added mass, "
          f"p = p_ext − m_a ẅ with m_a = {ma:g} kg/m² against the film's {DRUM_AREAL_MASS:g} kg/m² (the fluid takes "
          "ẅ from second differences of the interface positions, as an ALE solver does); the real explicit "
          "structure (`StructureParticipant`, subcycled), the product's `CouplingScheme`. Driver: "
          "`fsi_coupling_cost` (tests/cost/coupling_cost.cpp, built with the tests; shares the problem with "
          "tests/unit/test_coupled_membrane.cpp). Error: centre deflection at "
          f"t = {DRUM_END * 1e3:g} ms against the exact w = p t²/(2(ρt + m_a)) = {cp['exact'] * 1e3:.6f} mm "
          "(the flat film's centre accelerates freely until its tension, second order in w, matters; the "
          f"monolithic run with the added mass in the density gives {cp['monolithic'] * 1e3:.6f} mm). "
          "Wall time: the coupling loop.\n",
          "![coupled knobs: error against wall time](img/accuracy_cost_coupled.png)\n",
          "**Fluid step (window)**, implicit IQN-ILS, tolerance 1e-8:\n",
          "| window [ms] | windows | iterations per window | structure steps | centre [mm] | error | wall [ms] | what you buy (from the row above) |",
          "|---|---|---|---|---|---|---|---|"]
    for i, r in enumerate(cp["windows"]):
        words = ""
        if i > 0:
            p = cp["windows"][i - 1]
            words = buy(f"window {p['window'] * 1e3:g} → {r['window'] * 1e3:g} ms", p["error"], r["error"], p["wall"],
                        r["wall"])
        md.append(f"| {r['window'] * 1e3:g} | {r['windows']} | {r['mean_iterations']:.2f} | {r['structural_steps']} | "
                  f"{r['centre'] * 1e3:.5f} | {r['error']:.2e} | {r['wall'] * 1e3:.1f} | {words} |")
    md.append(f"\nObserved order in the window: {fmt_orders(cp['window_orders'])} (first order expected: the fluid's "
              "acceleration from second differences lags by one window).\n")
    md += ["**Subcycling** (at least N structure steps per window of 0.25 ms; N = 1: as many as the stable step "
           "needs):\n",
           "| N | structure steps | iterations per window | centre [mm] | error | wall [ms] | what you buy (against N = 1) |",
           "|---|---|---|---|---|---|---|"]
    r0 = cp["subcycles"][0]
    for r in cp["subcycles"]:
        words = "" if r is r0 else buy(f"N = {r['subcycles']}", r0["error"], r["error"], r0["wall"], r["wall"])
        md.append(f"| {r['subcycles']} | {r['structural_steps']} | {r['mean_iterations']:.2f} | {r['centre'] * 1e3:.5f} | "
                  f"{r['error']:.2e} | {r['wall'] * 1e3:.1f} | {words} |")
    md += ["", "**Acceleration and tolerance** (implicit, window 0.25 ms): iteration error against the same window "
           f"iterated to 1e-12 ({cp['tight'] * 1e3:.6f} mm), and the total error against the exact answer.\n",
           "| acceleration | tolerance | iterations per window | iteration error | total error | wall [ms] | "
           "what you buy (from the row above) |",
           "|---|---|---|---|---|---|---|"]
    prev = None
    for r in cp["tolerances"]:
        words = ""
        if prev is not None and prev["acceleration"] == r["acceleration"]:
            words = buy(f"tolerance {prev['tolerance']:.0e} → {r['tolerance']:.0e}", prev["error"], r["error"],
                        prev["wall"], r["wall"])
        md.append(f"| {r['acceleration']} | {r['tolerance']:.0e} | {r['mean_iterations']:.2f} | {r['error']:.1e} | "
                  f"{r['error_exact']:.2e} | {r['wall'] * 1e3:.1f} | {words} |")
        prev = r
    md += ["", "**Staggered or implicit** (window 0.25 ms; the staggered scheme with the linear predictor is stable "
           "for m_a/m_s < 1/3, docs/COUPLING.md):\n",
           "| m_a/m_s | scheme | windows run | iterations per window | centre [mm] | error | wall [ms] | what you buy |",
           "|---|---|---|---|---|---|---|---|"]
    for r in cp["schemes"]:
        words = ""
        if r["scheme"] == "staggered":
            imp = next(x for x in cp["schemes"] if x["added_mass"] == r["added_mass"] and x["scheme"] == "implicit")
            words = (buy("staggered instead of implicit", imp["error"], r["error"], imp["wall"], r["wall"])
                     if r["finite"] else f"unstable: blew up after {r['windows']} windows")
        centre = f"{r['centre'] * 1e3:.5f}" if r["finite"] else "–"
        its = f"{r['mean_iterations']:.2f}" if r["finite"] else "–"
        err = f"{r['error']:.2e}" if r["finite"] else "unstable"
        md.append(f"| {r['added_mass'] / DRUM_AREAL_MASS:g} | {r['scheme']} | {r['windows']} | {its} | "
                  f"{centre} | {err} | {r['wall'] * 1e3:.1f} | {words} |")
    md.append("")
    return md


def coupled_plot(cp, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    ax = axes[0]
    for key, label, fmt in (("windows", "window (labels: ms)", "o-"), ("subcycles", "subcycling N", "s--")):
        rs = cp[key]
        ax.loglog([r["wall"] * 1e3 for r in rs], [r["error"] for r in rs], fmt, label=label)
        for r in rs:
            text = f"{r['window'] * 1e3:g}" if key == "windows" else f"N={r['subcycles']}"
            ax.annotate(text, (r["wall"] * 1e3, r["error"]), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xlabel("wall time [ms]")
    ax.set_ylabel("relative error vs exact")
    ax.set_title("Added-mass drum: fluid step and subcycling")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax = axes[1]
    for acc in dict.fromkeys(r["acceleration"] for r in cp["tolerances"]):
        rs = [r for r in cp["tolerances"] if r["acceleration"] == acc]
        ax.loglog([r["wall"] * 1e3 for r in rs], [max(r["error"], 1e-14) for r in rs], "o-", label=acc)
    ax.set_xlabel("wall time [ms]")
    ax.set_ylabel("iteration error vs tolerance 1e-12")
    ax.set_title("Acceleration and tolerance (points: 1e-2 → tighter)")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------------------
# The document


def machine():
    cpu = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    osname = platform.system()
    try:
        for line in Path("/etc/os-release").read_text().splitlines():
            if line.startswith("PRETTY_NAME="):
                osname = line.split("=", 1)[1].strip('"')
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores ({osname}, Python {platform.python_version()})"


def git_commit():
    try:
        c = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                           check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return c + (" with local changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


SAIL_NOT_YET = """## Coupled knobs on the sail: not yet

The same knobs on a coupled sail (an OpenFOAM flow, e.g. `cases/coupled/baffle-canopy-2d`) are not measured
yet: each setting is a full pimpleFoam run (minutes), and a sail has no exact answer, so the reference would
be a run with a finer window and tighter tolerance. The adapter writes what such a study needs
(`structure/timing.json`, `structure/coupling.csv`; docs/COUPLING.md).
"""


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
                                                    c[-2]["error"], c[-1]["error"], c[-2]["setup"], c[-1]["setup"])))
    n = c[-1]["n"]
    d = next(x for x in res["projection"]["rows"] if x["variant"] == "dual" and x["n"] == n)
    out.append(("projection variant", buy(f"dual instead of consistent (n = {n})", c[-1]["error"], d["error"],
                                          c[-1]["setup"], d["setup"])))
    q = res["projection"]["quadrature"]
    out.append(("quadrature level", buy(f"level {q[0]['level']} → {q[-1]['level']} (source 10× finer)", q[0]["error"],
                                        q[-1]["error"], q[0]["setup"], q[-1]["setup"])))
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
    md += mesh_section(res["mesh"])
    md += integration_sections(res["safety"], res["mass_scaling"])
    md += dr_section(res["dr"])
    md += projection_section(res["projection"])
    if "coupled" in res:
        md += coupled_section(res["coupled"])
    else:
        md.append(f"## Coupled knobs (added-mass problem): not measured in this run\n\n{res['coupled_missing']}\n")
    md.append(SAIL_NOT_YET)
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
    res["mesh"] = [mesh_study("hencky", [8, 16, 32] if q else [8, 16, 32, 64], rep, None if q else 128),
                   mesh_study("sphere", [8, 16, 32] if q else [8, 16, 32, 64], rep),
                   mesh_study("airbag", [8, 16] if q else [8, 16, 32], rep, None if q else 64)]
    step("safety factor")
    ref_safety = 0.05 if q else 0.02  # its own error: (0.05/0.225)² ≈ 5 % of the finest row's in --quick
    res["safety"] = safety_study([0.9, 0.45, 0.225] if q else [0.9, 0.6, 0.45, 0.3, 0.225, 0.15],
                                 [0.9, 0.45] if q else [0.9, 0.6, 0.45, 0.3], ref_safety, rep)
    step("mass scaling")
    res["mass_scaling"] = mass_scaling_study([1, 1.5, 2] if q else [1, 1.1, 1.25, 1.5, 2, 3], ref_safety,
                                             32 if q else 64, rep)
    step("dynamic relaxation")
    res["dr"] = dr_study(["KDR", "oDR"] if q else list(dr_accuracy_cost.METHODS),
                         [1e-2, 1e-4, 1e-6] if q else dr_accuracy_cost.EPS, rep)
    step("projection")
    with tempfile.TemporaryDirectory() as work:
        res["projection"] = projection_study([8, 16, 32] if q else [8, 16, 32, 64, 128],
                                             [1, 2, 4, 8] if q else [1, 2, 4, 8, 16], rep, Path(work))
    driver = Path(args.coupling_driver)
    if driver.exists():
        step("coupled knobs")
        res["coupled"] = coupled_study(driver, q, rep)
    else:
        res["coupled_missing"] = f"{driver} not found: build it (`cmake --build build --target fsi_coupling_cost`)."
    step("plots and document")
    mesh_plot(res["mesh"], out / "img/accuracy_cost_mesh.png")
    integration_plot(res["safety"], res["mass_scaling"], out / "img/accuracy_cost_time.png")
    dr_plot(res["dr"], out / "img/accuracy_cost_dr.png")
    projection_plot(res["projection"], out / "img/accuracy_cost_projection.png")
    if "coupled" in res:
        coupled_plot(res["coupled"], out / "img/accuracy_cost_coupled.png")
    res["load"] = (load0, os.getloadavg()[0])
    # The command as run from the repository root (paths inside it relative to it).
    def shown(a):
        try:
            return str(Path(a).resolve().relative_to(ROOT)) if Path(a).exists() else a
        except ValueError:
            return a
    command = " ".join(["/usr/bin/python3 scripts/accuracy_cost.py"] + [shlex.quote(shown(a)) for a in sys.argv[1:]])
    write_doc(res, out, command, started, time.monotonic() - t0)
    if args.json:
        Path(args.json).write_text(json.dumps(res, indent=1))
    step(f"wrote {out / 'ACCURACY_COST.md'} and {out / 'img'}/accuracy_cost_*.png")


if __name__ == "__main__":
    main()
