#!/usr/bin/python3
"""Hard starts of the parafoil canopy (docs/PARAFOIL.md, "Hard starts"): full load at once, slack lines at the
start, very short cascade lines. Each mode runs `fsi run` on the scenes of cases/structure/parafoil-kt-inflation
(scene.yaml: damped explicit dynamics, relaxation.yaml: kinetic DR) with --set variants and
checks the exit code, the stop reason, that no result is NaN or infinite, and the final state (the static state
with its global equilibrium, or the diagnosis text).

usage: run_hard.py MODE FSI OUTDIR
"""
import json
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np

CASE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "cases", "structure",
                    "parafoil-kt-inflation")
RELAX = os.path.join(CASE, "relaxation.yaml")
EXPLICIT = os.path.join(CASE, "scene.yaml")
# The rig (confluence point and toggles) moved 0.3 m up towards the canopy at once: every suspension and brake
# line starts slack; the static state is the unmoved one, translated.
SLACK = ("constraints=[{nodes: [wing/confluence, wing/toggle_left, wing/toggle_right], "
         "prescribe: {direction: [0, 0, 1], amplitude: 0.3}}]")

failures = []


def check(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


def run(fsi, scene, out, sets, expect_rc):
    cmd = [fsi, "run", scene, "--out", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print("$ " + " ".join(cmd) + "\n" + p.stdout.strip())
    check(p.returncode == expect_rc, f"{os.path.basename(out)}: exit code {p.returncode} (expected {expect_rc})")
    summary = os.path.join(out, "summary.json")
    if not os.path.exists(summary):
        check(False, f"{summary} written")
        return {}, p.stdout
    text = open(summary).read()
    check(not re.search(r"\b(nan|inf|infinity)\b", text, re.IGNORECASE), f"{summary}: no NaN or infinity")
    bad = []

    def scan(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f" and not np.all(np.isfinite(obj[()])):
            bad.append(name)

    with h5py.File(os.path.join(out, "results.h5"), "r") as f:
        f.visititems(scan)
    check(not bad, f"{out}/results.h5: every value finite" + (f" (not: {bad[:5]})" if bad else ""))
    return json.loads(text), p.stdout


def static(s, what, equilibrium=1e-6):
    check(s.get("stop_reason") == "static", f"{what}: static state reached ({s.get('stop_reason')})")
    eq = s.get("probes", {}).get("equilibrium", math.inf)
    check(eq < equilibrium, f"{what}: global equilibrium error {eq:.3g} < {equilibrium:g}")


def same(a, b, key, rel, what):
    x, y = a["probes"][key], b["probes"][key]
    check(abs(x - y) <= rel * abs(y), f"{what}: {key} {x:.9g} = {y:.9g} within {rel:g}")


def main():
    mode, fsi, out = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(out, exist_ok=True)
    o = lambda name: os.path.join(out, name)
    if mode == "full-load-relaxation":
        # The whole load at once on the design shape, kinetic DR: the static state.
        s, _ = run(fsi, RELAX, o("relax"), [], 0)
        static(s, "kinetic DR, full load at once")
    elif mode == "full-load-explicit":
        # Damped explicit dynamics with mass scaling, the whole load as a step at t = 0: the static state.
        s, _ = run(fsi, EXPLICIT, o("explicit"), [], 0)
        static(s, "damped explicit, full load at once", 2e-6)
    elif mode == "full-load-undamped":
        # No damping, no mass scaling: the canopy is hit by the whole load and oscillates; the run must stay
        # stable (finite, energy balanced) to its end and report that it did not reach a static state.
        s, _ = run(fsi, EXPLICIT, o("undamped"),
                   ["effects.mass_damping.alpha=0", "time.mass_scaling_min_dt=0", "time.until_static.max_time=0.02"],
                   4)
        check(s.get("stop_reason") == "not_converged", f"undamped: stop reason {s.get('stop_reason')}")
        st = s.get("stats", {})
        check(abs(st.get("simulated_time", 0) - 0.02) < 1e-9, f"undamped: ran to 0.02 s ({st.get('simulated_time')})")
        check(st.get("energy_balance_error", 1) < 1e-6, f"undamped: energy balance error {st.get('energy_balance_error')}")
        check(st.get("added_mass", 1) == 0, "undamped: no mass added")
    elif mode in ("slack-lines-relaxation", "slack-lines-explicit"):
        # Lines slack at the start: the canopy must fall back onto them and reach the translated static state,
        # with the same line tensions and volume as the unmoved rig.
        base, _ = run(fsi, RELAX, o("base"), [], 0)
        static(base, "unmoved rig (kinetic DR)")
        scene = RELAX if mode.endswith("relaxation") else EXPLICIT
        s, _ = run(fsi, scene, o("slack"), [SLACK], 0)
        static(s, "slack lines at the start", 2e-6)
        for key in ("line_tension_max", "brake_tension_left", "enclosed_volume"):
            same(s, base, key, 1e-5, "slack start vs unmoved rig")
    elif mode in ("short-cascade-relaxation", "short-cascade-explicit"):
        # Junctions 1 % of the way from the attachments or 1 % from the confluence point: cascade cables of
        # about 5 mm. DR: the junction nodes get heavy fictitious masses (EA/l); explicit: mass scaling lifts the
        # stable step of those cables to the scene's minimum and reports the added mass.
        scene = RELAX if mode.endswith("relaxation") else EXPLICIT
        for cf in ("0.01", "0.99"):
            s, _ = run(fsi, scene, o("cascade" + cf), ["meshes.wing.generator.cascade_fraction=" + cf], 0)
            static(s, f"cascade_fraction {cf}", 2e-6)
            if scene == EXPLICIT:
                check(s["stats"]["added_mass_fraction"] > 0, f"cascade_fraction {cf}: added mass reported "
                      f"({s['stats']['added_mass_fraction']:.3g} of the physical mass)")
    elif mode == "short-cascade-diagnosis":
        # cascade_fraction 0.001 (0.5 mm cables) with a budget of iterations the normal canopy needs: the run must
        # stop with exit code 4 and a diagnosis that names the short element and what to change.
        s, text = run(fsi, RELAX, o("cascade0.001"),
                      ["meshes.wing.generator.cascade_fraction=0.001", "solver.max_iterations=20000"], 4)
        d = s.get("diagnosis", "")
        check(s.get("stop_reason") == "not_converged", f"stop reason {s.get('stop_reason')}")
        check(re.search(r"cable \d+ of mesh 'wing'", d) is not None, "diagnosis names the short cable: " + d)
        check("cascade_fraction" in d or "longer" in d, "diagnosis says what to change")
    else:
        print("unknown mode " + mode)
        return 2
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
