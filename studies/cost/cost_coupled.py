"""Accuracy versus cost, coupled knobs: the added-mass drum (tests/unit/AddedMassDrum.hpp; one run per call of
the driver fsi_coupling_cost, tests/cost/coupling_cost.cpp) against its exact answer: fluid step, subcycling,
acceleration and tolerance, staggered or implicit; tables and plot (studies/cost/accuracy_cost.py)."""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))  # fsi_runs
import fsi_runs  # noqa: E402
from cost_words import buy, buy_from_row_above, fmt_orders, order  # noqa: E402

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
          "| window [ms] | windows | iterations per window | structure steps | centre [mm] | error | wall [ms] | "
          "what you buy (from the row above) |",
          "|---|---|---|---|---|---|---|---|"]
    for i, r in enumerate(cp["windows"]):
        words = buy_from_row_above(cp["windows"], i,
                                   lambda p, r: f"window {p['window'] * 1e3:g} → {r['window'] * 1e3:g} ms")
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
            ax.annotate(text, (r["wall"] * 1e3, r["error"]), textcoords="offset points",
                        xytext=(4, 4) if key == "windows" else (4, -11), fontsize=7)
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
