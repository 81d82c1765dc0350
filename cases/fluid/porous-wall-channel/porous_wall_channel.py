#!/usr/bin/python3
"""Permeable wall baffle across a channel: the adapter's fsiPorousWall against the Darcy-Forchheimer law.

The porous-channel case (cases/fluid/porous-channel) with the cloth as a pair of walls, as the coupled canopy
has it, each side's velocity the adapter's fsiPorousWall (libfsiFoam.so): the seepage of the law

    dp = a mu u + b rho u^2        (kinematic: dp/rho = a nu u + b u^2; rho cancels)

from the pressure difference across the cloth. The channel (slip walls) is driven by the inlet's pressure:
the upstream part has no other pressure level, since the walls separate it from the outlet (with a given
inflow speed its pressure level would be undetermined). For each speed u_k the inlet pressure is the law's
drop at u_k; the run is solved to steady and read: the pressure 1 m upstream and downstream (uniform there),
the flux through each side of the cloth and through the inlet. Checks (exit 1 naming a failed one):
  - the drop between the plenums is the law at the measured through-flow (every speed),
  - the through-flow is the inflow (continuity) and the two sides' fluxes cancel (mass through the pair),
  - a, b fitted back from the drops (dp/u = a nu + b u, least squares) are the inputs,
  - with --moving V: the same channel with the cloth moving downstream at V (dynamicMotionSolverFvMesh, the
    cloth patches' pointDisplacement given): the inflow is the relative through-flow plus V (the wall's own
    motion kept by the condition), and the drop is the law at the relative through-flow.
Writes summary.json and porous_wall_channel.png.

Usage: ./porous_wall_channel.py [--speeds 0.1,0.25,0.5,1] [--a 7e6] [--b 200] [--moving 0.05]
       [--relaxation 1] [--dt-factor 4] [--tolerance 0.005]
The adapter library: $FSI_LIB_DIR, else build/lib of the source tree this case is in, else LD_LIBRARY_PATH.
"""

import argparse
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
LENGTH = 4.0  # the channel's length [m]: the air column the inlet's pressure accelerates
RHO = 1.2  # air [kg/m^3]: only converts kinematic pressure for the report
AREA = 1.0 * 0.1  # the cloth: channel height x thickness of the 2D slab [m^2]


def nu_of(case):
    with open(os.path.join(case, "constant", "transportProperties")) as f:
        for line in f:
            words = line.split("//")[0].replace(";", " ").split()
            if len(words) >= 2 and words[0] == "nu":
                return float(words[-1])
    raise SystemExit(f"{case}/constant/transportProperties: no 'nu' entry")


def law(u, a, b, nu):
    """Kinematic pressure drop dp/rho [m^2/s^2] of the cloth at through-flow u [m/s]."""
    return a * nu * u + b * u * abs(u)


def environment():
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")  # Debian's OpenFOAM finds its etc/ there
    for d in (os.environ.get("FSI_LIB_DIR", ""), os.path.join(HERE, "..", "..", "..", "build", "lib")):
        if d and os.path.exists(os.path.join(d, "libfsiFoam.so")):
            env["LD_LIBRARY_PATH"] = os.path.abspath(d) + ":" + env.get("LD_LIBRARY_PATH", "")
            break
    return env


def run(cmd, case, log):
    with open(os.path.join(case, log), "w") as out:
        rc = subprocess.call(cmd, cwd=case, stdout=out, stderr=subprocess.STDOUT, env=environment())
    if rc != 0:
        raise SystemExit(f"{case}: {' '.join(cmd)} failed (exit {rc}); see {os.path.join(case, log)}")


def rows(path):
    out = [[float(w) for w in line.split()] for line in open(path) if line.strip() and not line.startswith("#")]
    if not out:
        raise SystemExit(f"{path}: no data")
    return out


def edit(path, pairs):
    text = open(path).read()
    for old, new in pairs:
        if old not in text:
            raise SystemExit(f"{path}: '{old}' not found")
        text = text.replace(old, new)
    open(path, "w").write(text)


def solve(name, u, a, b, nu, args, wall_speed=0.0):
    """One run at the inlet pressure of the law's drop at u (through-flow relative to the cloth)."""
    case = os.path.join(args.work, name)
    shutil.rmtree(case, ignore_errors=True)
    for d in ("system", "constant"):
        shutil.copytree(os.path.join(HERE, d), os.path.join(case, d))
    shutil.copytree(os.path.join(HERE, "0.orig"), os.path.join(case, "0"))
    with open(os.path.join(case, "system", "clothCoefficients"), "w") as f:
        f.write(f"// written by porous_wall_channel.py\na {a:.12g}; b {b:.12g}; relaxation {args.relaxation:g};\n")
    edit(os.path.join(case, "0", "p"), [("P_IN", f"{law(u, a, b, nu):.12g}")])
    # the step: dt_factor x the time scale of the air column against the cloth, L / (a nu + 2 b u)
    dt = args.dt_factor * LENGTH / (a * nu + 2 * b * u)
    # the moving run: a tenth of the steps (the cloth moves 0.16 m at 0.05 m/s; the through-flow settles in a
    # few L / (a nu + 2 b u))
    steps = args.steps // 10 if wall_speed else args.steps
    edit(os.path.join(case, "system", "controlDict"),
         [("endTime 0.5; deltaT 0.005;", f"endTime {dt * steps:.12g}; deltaT {dt:.12g};"),
          ("writeInterval 100;", f"writeInterval {steps};")])
    if wall_speed:
        os.rename(os.path.join(case, "system", "dynamicMeshDict.moving"),
                  os.path.join(case, "constant", "dynamicMeshDict"))
        edit(os.path.join(case, "0", "pointDisplacement"), [("V_WALL_100", f"{100 * wall_speed:.12g}")])
    else:
        os.remove(os.path.join(case, "0", "pointDisplacement"))
    run(["blockMesh"], case, "log.blockMesh")
    run(["createBaffles", "-overwrite"], case, "log.createBaffles")
    run(["pimpleFoam"], case, "log.pimpleFoam")
    open(os.path.join(case, name + ".foam"), "w").close()  # for ParaView
    pp = os.path.join(case, "postProcessing")
    probes = rows(os.path.join(pp, "plenums", "0", "p"))
    up = rows(os.path.join(pp, "throughFlow", "0", "surfaceFieldValue.dat"))
    down = rows(os.path.join(pp, "throughFlowDown", "0", "surfaceFieldValue.dat"))
    inflow = rows(os.path.join(pp, "inflow", "0", "surfaceFieldValue.dat"))
    pair = max(abs(x[1] + y[1]) / max(abs(x[1]), 1e-300) for x, y in zip(up, down))
    last = probes[-1]
    drop = last[1] - last[2]
    through = up[-1][1] / AREA
    # steadiness: the through-flow's change over the last tenth of the run
    tenth = up[-len(up) // 10][1] / AREA
    return {"name": name, "u_set": u, "wall_speed": wall_speed, "dt": dt, "steps": steps,
            "p_in": law(u, a, b, nu), "drop": drop, "through_flow": through, "inflow": -inflow[-1][1] / AREA,
            "pair_imbalance": pair, "unsteadiness": abs(through - tenth) / abs(through),
            "law": law(through, a, b, nu), "drop_error": drop / law(through, a, b, nu) - 1}


def fit(points, nu):
    """Least squares of dp/u = a nu + b u over the points: (a, b)."""
    xs = [p["through_flow"] for p in points]
    ys = [p["drop"] / p["through_flow"] for p in points]
    n, sx, sy = len(xs), sum(xs), sum(ys)
    sxx, sxy = sum(x * x for x in xs), sum(x * y for x, y in zip(xs, ys))
    b = (n * sxy - sx * sy) / (n * sxx - sx * sx)
    return (sy - b * sx) / n / nu, b


def plot(points, moving, a, b, nu, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    umax = max(p["through_flow"] for p in points) * 1.1
    us = [umax * i / 100 for i in range(101)]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(us, [RHO * law(u, a, b, nu) for u in us], "k-", label=r"law $a\mu u + b\rho u^2$")
    ax.plot([p["through_flow"] for p in points], [RHO * p["drop"] for p in points], "ro",
            label="fsiPorousWall, static wall pair")
    if moving:
        ax.plot([moving["through_flow"]], [RHO * moving["drop"]], "bs", mfc="none", ms=10,
                label=f"moving wall pair ({moving['wall_speed']:g} m/s), relative through-flow")
    ax.set_xlabel("through-flow relative to the cloth u [m/s]")
    ax.set_ylabel(r"pressure drop across the cloth $\Delta p$ [Pa] ($\rho$ = 1.2 kg/m$^3$)")
    ax.set_title(f"Permeable wall baffle in a channel: a = {a:g} 1/m, b = {b:g}")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def check(p, tol, failures):
    tag = p["name"]
    relative_inflow = p["inflow"] - p["wall_speed"]
    if abs(p["through_flow"] / relative_inflow - 1) > tol:
        failures.append(f"{tag}: through-flow {p['through_flow']:.6g} m/s is not the inflow minus the wall's "
                        f"speed {relative_inflow:.6g} m/s")
    if abs(p["drop_error"]) > tol:
        failures.append(f"{tag}: drop off the law by {100 * p['drop_error']:+.3f} %")
    if p["pair_imbalance"] > 1e-9:
        failures.append(f"{tag}: the two sides' fluxes differ by {p['pair_imbalance']:.3g} of the flux")
    if p["unsteadiness"] > tol / 10:
        failures.append(f"{tag}: not steady (through-flow changed by {p['unsteadiness']:.3g} over the last tenth)")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--speeds", default="0.1,0.25,0.5,1", help="through-flow speeds [m/s], comma-separated")
    ap.add_argument("--a", type=float, default=7.0e6, help="viscous (Darcy) coefficient a [1/m]")
    ap.add_argument("--b", type=float, default=200.0, help="inertial (Forchheimer) coefficient b [-]")
    ap.add_argument("--moving", type=float, default=0.05, help="the moving run's wall speed [m/s] (0: none)")
    ap.add_argument("--relaxation", type=float, default=1.0, help="fsiPorousWall relaxation")
    ap.add_argument("--dt-factor", type=float, default=4.0, help="step / (L / (a nu + 2 b u))")
    ap.add_argument("--steps", type=int, default=200, help="steps per run")
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
    failures, points = [], []
    for u in speeds:
        p = solve(f"u_{u:g}", u, args.a, args.b, nu, args)
        points.append(p)
        check(p, args.tolerance, failures)
        print(f"u = {u:g} m/s: through-flow {p['through_flow']:.6g} m/s (inflow {p['inflow']:.6g}), drop "
              f"{RHO * p['drop']:.6g} Pa, law {RHO * p['law']:.6g} Pa ({100 * p['drop_error']:+.3f} %), "
              f"pair imbalance {p['pair_imbalance']:.2g}")
    moving = None
    if args.moving:
        u = speeds[len(speeds) // 2]
        moving = solve(f"moving_u_{u:g}", u, args.a, args.b, nu, args, wall_speed=args.moving)
        check(moving, args.tolerance, failures)
        print(f"moving at {args.moving:g} m/s: inflow {moving['inflow']:.6g} m/s, relative through-flow "
              f"{moving['through_flow']:.6g} m/s, drop {RHO * moving['drop']:.6g} Pa, law "
              f"{RHO * moving['law']:.6g} Pa ({100 * moving['drop_error']:+.3f} %)")
    a_fit, b_fit = fit(points, nu)
    for name, got, want in (("a", a_fit, args.a), ("b", b_fit, args.b)):
        if abs(got / want - 1) > args.tolerance if want > 0 else abs(got) > args.tolerance:
            failures.append(f"fitted {name} = {got:.6g}, the input is {want:g}")
    summary = {"case": "porous-wall-channel", "a_per_m": args.a, "b": args.b, "nu": nu, "rho_report": RHO,
               "relaxation": args.relaxation, "dt_factor": args.dt_factor,
               "fitted": {"a_per_m": a_fit, "b": b_fit}, "points": points, "moving": moving,
               "tolerance": args.tolerance, "failures": failures}
    with open(os.path.join(HERE, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    plot(points, moving, args.a, args.b, nu, os.path.join(HERE, "porous_wall_channel.png"))
    print(f"fitted a = {a_fit:.6g} 1/m (input {args.a:g}), b = {b_fit:.6g} (input {args.b:g}); "
          "summary.json, porous_wall_channel.png")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
