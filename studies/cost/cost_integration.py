"""Accuracy versus cost, time integration: the safety factor on the stable step and selective mass scaling, on
a Hencky transient (against a much smaller step), its static answer and the static sphere; tables and plot
(studies/cost/accuracy_cost.py)."""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))  # fsi_runs
import fsi_runs  # noqa: E402
from cost_words import buy, buy_from_row_above, fmt_orders, order, times  # noqa: E402

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
        words = buy_from_row_above(saf["rows"], i, lambda p, r: f"safety {p['safety']:g} → {r['safety']:g}")
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
        words = buy_from_row_above(saf["static_rows"], i, lambda p, r: f"safety {p['safety']:g} → {r['safety']:g}")
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
    ax.set_title("Hencky static answer: wall time against the safety factor")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
