#!/usr/bin/python3
"""Porous cloth across a channel: OpenFOAM's porous baffle against the Darcy-Forchheimer law (issue 37 item 2).

A 2D channel with slip walls is closed by a cloth across its whole height (a cyclic baffle with
porousBafflePressure). Mass conservation fixes the through-flow at the inflow speed u, so the pressure drop
across the cloth must be the law's:

    dp = a mu u + b rho u^2        (a [1/m]: viscous, Darcy; b [-]: inertial, Forchheimer)

OpenFOAM writes the jump as dp/rho = (D nu |u| + I/2 |u|^2) L; with L = 1 m, D = a and I = 2 b. For each
inflow speed the case is copied to runs/u_<speed>, meshed (blockMesh, createBaffles), solved (simpleFoam,
laminar, steady) and read: the pressure 1 m upstream and downstream (uniform there) and the flux through the
cloth. The run checks (exit 1 when one fails, naming it):
  - the through-flow equals the inflow speed (continuity through the cyclic baffle),
  - the pressure drop equals the law at every speed,
  - a, b fitted back from the drops (least squares on dp/u = a mu + b rho u) are the inputs.
Writes summary.json and porous_channel.png (the drop against the through-flow: runs, law, the two terms).

Usage: ./porous_channel.py [--speeds 0.1,0.25,0.5,1] [--a 7e6] [--b 200] [--tolerance 0.005]
       (./Allrun runs it; ./Allclean removes runs/, summary.json and the plot)
"""

import argparse
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DX = 0.1  # the cells' length across the cloth (system/blockMeshDict: 4 m in 40 cells) [m]
RHO = 1.2  # air [kg/m^3]: only converts kinematic pressure for the report (the flow is incompressible)


def nu_of(case):
    with open(os.path.join(case, "constant", "transportProperties")) as f:
        for line in f:
            words = line.split("//")[0].replace(";", " ").split()
            if len(words) >= 2 and words[0] == "nu":
                return float(words[-1])
    raise SystemExit(f"{case}/constant/transportProperties: no 'nu' entry")


def law(u, a, b, nu):
    """Kinematic pressure drop dp/rho [m^2/s^2] of the cloth at through-flow u [m/s]."""
    return a * nu * u + b * u * u


def run(cmd, case, log):
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")  # Debian's OpenFOAM finds its etc/ there
    with open(os.path.join(case, log), "w") as out:
        rc = subprocess.call(cmd, cwd=case, stdout=out, stderr=subprocess.STDOUT, env=env)
    if rc != 0:
        raise SystemExit(f"{case}: {' '.join(cmd)} failed (exit {rc}); see {os.path.join(case, log)}")


def last_row(path):
    rows = [line.split() for line in open(path) if line.strip() and not line.startswith("#")]
    if not rows:
        raise SystemExit(f"{path}: no data")
    return rows[-1]


def stable_step(u, a, b, nu):
    """The time step of the runs: dx / (a nu + 2 b u).

    OpenFOAM's porousBafflePressure evaluates the jump from the last flux: an explicit source whose gain
    d(dp/rho)/du = a nu + 2 b u acts on the cells next to the cloth. A flux perturbation then grows when the
    step exceeds about that gain's time scale over the cell: measured here (u = 1, dx = 0.1, a = 7e6, b = 200
    and b = 400), runs diverge above dt = (2.7-3.2) dx / (a nu + 2 b u) and are steady below. The runs use a
    third of it. (A coupled porous canopy has the same limit: docs/ROUND_CANOPY.md.)"""
    return DX / (a * nu + 2 * b * u)


def solve(u, a, b, work, dt, steps=300):
    case = os.path.join(work, f"u_{u:g}")
    shutil.rmtree(case, ignore_errors=True)
    for d in ("system", "constant"):
        shutil.copytree(os.path.join(HERE, d), os.path.join(case, d))
    shutil.copytree(os.path.join(HERE, "0.orig"), os.path.join(case, "0"))
    with open(os.path.join(case, "system", "clothCoefficients"), "w") as f:
        f.write(f"// written by porous_channel.py: a = {a:g} 1/m, b = {b:g}, L = 1 m\n"
                f"D {a:.12g}; I {2 * b:.12g}; length 1;\n")
    path = os.path.join(case, "0", "U")
    text = open(path).read().replace("U_IN", f"{u:.12g}")
    open(path, "w").write(text)
    path = os.path.join(case, "system", "controlDict")
    text = open(path).read().replace("endTime 0.5; deltaT 0.005;", f"endTime {dt * steps:.12g}; deltaT {dt:.12g};")
    open(path, "w").write(text.replace("writeInterval 100;", f"writeInterval {steps};"))
    run(["blockMesh"], case, "log.blockMesh")
    run(["createBaffles", "-overwrite"], case, "log.createBaffles")
    run(["pimpleFoam"], case, "log.pimpleFoam")
    open(os.path.join(case, os.path.basename(case) + ".foam"), "w").close()  # for ParaView
    probes = last_row(os.path.join(case, "postProcessing", "plenums", "0", "p"))
    flux = last_row(os.path.join(case, "postProcessing", "throughFlow", "0", "surfaceFieldValue.dat"))
    area = 1.0 * 0.1  # the cloth: channel height x thickness of the 2D slab
    return {"u_in": u, "dt": dt, "steps": steps, "p_up": float(probes[1]), "p_down": float(probes[2]),
            "drop": float(probes[1]) - float(probes[2]), "through_flow": float(flux[1]) / area,
            "end_time": float(probes[0])}


def fit(points, nu):
    """Least squares of dp/u = a nu + b u over the points: (a, b)."""
    xs = [p["through_flow"] for p in points]
    ys = [p["drop"] / p["through_flow"] for p in points]
    n, sx, sy = len(xs), sum(xs), sum(ys)
    sxx, sxy = sum(x * x for x in xs), sum(x * y for x, y in zip(xs, ys))
    b = (n * sxy - sx * sy) / (n * sxx - sx * sx)
    return (sy - b * sx) / n / nu, b


def plot(points, a, b, nu, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    umax = max(p["through_flow"] for p in points) * 1.1
    us = [umax * i / 100 for i in range(101)]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(us, [RHO * law(u, a, b, nu) for u in us], "k-", label=r"law $a\mu u + b\rho u^2$")
    ax.plot(us, [RHO * a * nu * u for u in us], "b--", lw=1, label=r"viscous (Darcy) $a\mu u$")
    ax.plot(us, [RHO * b * u * u for u in us], "g--", lw=1, label=r"inertial (Forchheimer) $b\rho u^2$")
    ax.plot([p["through_flow"] for p in points], [RHO * p["drop"] for p in points], "ro", label="OpenFOAM runs")
    ax.set_xlabel("through-flow u [m/s]")
    ax.set_ylabel(r"pressure drop across the cloth $\Delta p$ [Pa] ($\rho$ = 1.2 kg/m$^3$)")
    ax.set_title(f"Porous cloth across a channel: a = {a:g} 1/m, b = {b:g}")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--speeds", default="0.1,0.25,0.5,1", help="inflow speeds [m/s], comma-separated")
    ap.add_argument("--a", type=float, default=7.0e6, help="viscous (Darcy) coefficient a [1/m]")
    ap.add_argument("--b", type=float, default=200.0, help="inertial (Forchheimer) coefficient b [-]")
    ap.add_argument("--tolerance", type=float, default=0.005, help="relative tolerance of the checks")
    ap.add_argument("--work", default=os.path.join(HERE, "runs"), help="where the runs go")
    args = ap.parse_args(argv)
    try:
        speeds = [float(s) for s in args.speeds.split(",")]
    except ValueError:
        raise SystemExit(f"--speeds: not a list of numbers: {args.speeds!r}")
    if len(speeds) < 2 or any(not (s > 0 and math.isfinite(s)) for s in speeds):
        raise SystemExit("--speeds: at least two positive speeds")
    if not (args.a >= 0 and args.b >= 0 and args.a + args.b > 0):
        raise SystemExit("--a, --b: non-negative, not both zero")
    nu = nu_of(HERE)
    points = []
    for u in speeds:
        p = solve(u, args.a, args.b, args.work, stable_step(u, args.a, args.b, nu))
        p["law"] = law(p["through_flow"], args.a, args.b, nu)
        p["drop_error"] = p["drop"] / p["law"] - 1
        points.append(p)
        print(f"u = {u:g} m/s: through-flow {p['through_flow']:.6g} m/s, drop {RHO * p['drop']:.6g} Pa, "
              f"law {RHO * p['law']:.6g} Pa ({100 * p['drop_error']:+.3f} %)")
    a_fit, b_fit = fit(points, nu)
    failures = []
    for p in points:
        if abs(p["through_flow"] / p["u_in"] - 1) > args.tolerance:
            failures.append(f"u = {p['u_in']:g}: through-flow {p['through_flow']:.6g} m/s is not the inflow")
        if abs(p["drop_error"]) > args.tolerance:
            failures.append(f"u = {p['u_in']:g}: drop off the law by {100 * p['drop_error']:+.3f} %")
    for name, got, want in (("a", a_fit, args.a), ("b", b_fit, args.b)):
        if abs(got / want - 1) > args.tolerance if want > 0 else abs(got) > args.tolerance:
            failures.append(f"fitted {name} = {got:.6g}, the input is {want:g}")
    summary = {"case": "porous-channel", "a_per_m": args.a, "b": args.b, "nu": nu, "rho_report": RHO,
               "openfoam": {"D": args.a, "I": 2 * args.b, "length": 1.0},
               "fitted": {"a_per_m": a_fit, "b": b_fit}, "points": points, "tolerance": args.tolerance,
               "failures": failures}
    with open(os.path.join(HERE, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    plot(points, args.a, args.b, nu, os.path.join(HERE, "porous_channel.png"))
    print(f"fitted a = {a_fit:.6g} 1/m (input {args.a:g}), b = {b_fit:.6g} (input {args.b:g}); "
          "summary.json, porous_channel.png")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
