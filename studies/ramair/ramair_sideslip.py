#!/usr/bin/python3
"""The ram-air wing in sideslip (issue 38): the side force and the roll and yaw moments the flight table's
sideslip derivatives come from (docs/FLIGHT.md "The sideslip derivatives").

The main job's trimmed canopy as a rigid wing: the structure's last frame of the main job's run (--deformed
RUN/structure), made mirror-symmetric (studies/wing/wing_polar.py's symmetric_source), meshed whole (no
symmetry plane: the flow is not symmetric) at the main job's resolution and wall treatment (coarse, kOmegaSST
with wall functions), at the main job's attitude (inflow angle 0: the skin is in the coupled run's frame), time-
accurate as rung 2c's trimmed points (Courant 2, 2 outer correctors, 480 steps: 2 s of flow, the forces averaged
over the second second), with the free stream turned by the `sideslip` setting. Every point is a copy of
cases/coupled/ramair-kt (its tracked files) in OUT/b<sideslip>, run by its own Allrun; each finished point is
stored in the JSON at once, so a cut-off study keeps what it did.

  /usr/bin/python3 studies/ramair/ramair_sideslip.py --deformed RUN/structure [--sideslip=5,-5,0] [--out DIR]
      [--json docs/data/ramair_sideslip.json] [--env build/share/fsi/fsi-env.sh] [--collect]
  /usr/bin/python3 studies/ramair/ramair_sideslip.py --deformed RUN/structure --plot docs/img/ramair_sideslip.png

The JSON holds per point the forces function object's total force and moment about CofR (the case's axes: x
downstream, y right, z up), averaged over the second half of the steps, their range over that half, CL and CD,
and the anchor (the confluence point of the deformed run); cases/flight/ramair_flight_table.py turns them into
CY_beta, Cl_beta and Cn_beta about the flight model's canopy point.
"""
import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent
sys.path.insert(0, str(ROOT / "studies/wing"))
from wing_polar import symmetric_source, tracked_case_files  # noqa: E402

SETTINGS = """# written by studies/ramair/ramair_sideslip.py: the main job's trimmed canopy, rigid, in sideslip
speed 15
angle 0            # the main job's attitude: the skin is in the coupled run's frame
nu 1.5e-5
rho 1.225
model kOmegaSST    # wall functions, as the main job
turbulence_intensity 0.005
viscosity_ratio 10
resolution coarse
mesh_motion none
stl_bulge -1
solver pimple
courant 2
outer_correctors 2
"""


def run_point(out, beta, source, env, steps):
    case = Path(out) / f"b{beta:+g}"
    if (case / "summary.json").exists():
        return case, 0.0
    if case.exists():
        subprocess.run(["rm", "-rf", str(case)], check=True)
    case.mkdir(parents=True)
    for f in tracked_case_files():
        (case / f.name).write_bytes(f.read_bytes())
        os.chmod(case / f.name, f.stat().st_mode)
    (case / "sideslip.settings").write_text(SETTINGS + f"steps {steps}   # the forces averaged over the "
                                            f"second half\nstl_deformed {source}\nsideslip {beta:g}\n")
    t0 = time.time()
    cmd = ["bash", "-c", '. "$0" && exec nice -n 10 ./Allrun -settings sideslip.settings', str(env)]
    with open(Path(out) / f"b{beta:+g}.log", "w") as log:
        rc = subprocess.run(cmd, cwd=case, stdout=log, stderr=subprocess.STDOUT).returncode
    if rc != 0:
        print(f"ramair_sideslip: {case} failed (exit {rc}); see {case}.log", file=sys.stderr)
        return None, time.time() - t0
    return case, time.time() - t0


def anchor(source):
    """The confluence point: the structure's lowest node (held fixed, 3 m below the canopy)."""
    import h5py
    import numpy as np
    with h5py.File(source, "r") as f:
        x = f[f"steps/{sorted(f['steps'])[-1]}/coordinates"][()]
    return [float(v) for v in x[int(np.argmin(x[:, 2]))]]


def collect(case, beta, wall_s, source):
    s = json.loads((Path(case) / "summary.json").read_text())
    rec = json.loads((Path(case) / "constant/fluidSettings.json").read_text())
    lat, fl = s["lateral"], s["flow"]
    h = lat["history"]
    tail = len(h["time"]) // 2
    hist_cl, hist_cd = fl["history"]["CL"], fl["history"]["CD"]
    rng = {k: [min(h[k][-tail:]), max(h[k][-tail:])] for k in ("side_force_N", "roll_moment_Nm", "yaw_moment_Nm")}
    return {"sideslip_deg": beta, "flow_dir": rec["derived"]["flow_dir"], "CofR": lat["CofR"],
            "force_N": lat["force_N"], "moment_Nm": lat["moment_Nm"], "side_force_N": lat["side_force_N"],
            "roll_moment_Nm": lat["roll_moment_Nm"], "yaw_moment_Nm": lat["yaw_moment_Nm"],
            "range_second_half": rng, "averaged_over": lat["averaged_over"],
            "CL": sum(hist_cl[-tail:]) / tail, "CD": sum(hist_cd[-tail:]) / tail,
            "Aref_m2": rec["derived"]["Aref"], "span_projected_m": rec["derived"]["span_projected"],
            "cells": s["mesh"]["cells"], "mesh_ok": s["mesh"]["ok"], "wall_s": round(wall_s, 1),
            "anchor_m": anchor(source)}


def store(path, rows, meta):
    data = json.loads(Path(path).read_text()) if Path(path).exists() else {}
    old = {r["sideslip_deg"]: r for r in data.get("rows", [])}
    for r in rows:
        old[r["sideslip_deg"]] = r
    data.update(meta)
    data["rows"] = [old[k] for k in sorted(old)]
    Path(path).write_text(json.dumps(data, indent=1) + "\n")


def plot(out, png):
    """The side force, roll and yaw about CofR against time for every finished point (the averaged half shaded)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    keys = ("side_force_N", "roll_moment_Nm", "yaw_moment_Nm")
    late = {k: [] for k in keys}
    for case in sorted(Path(out).glob("b*/summary.json")):
        lat = json.loads(case.read_text()).get("lateral")
        if not lat:
            continue
        h = lat["history"]
        for ax, key in zip(axes, keys):
            ax.plot(h["time"], h[key], label=f"sideslip {case.parent.name[1:]} deg")
            late[key] += h[key][len(h[key]) // 4:]
    for ax, key in zip(axes, keys):  # the start's impulse off the scale
        if late[key]:
            lo, hi = min(late[key]), max(late[key])
            ax.set_ylim(lo - 0.3 * (hi - lo) - 1e-3, hi + 0.3 * (hi - lo) + 1e-3)
    t_end = max(ax.get_xlim()[1] for ax in axes)
    for ax, label in zip(axes, ("side force [N] (+: right)", "roll about CofR [N m] (+: right wing down)",
                                "yaw about CofR [N m] (+: nose right)")):
        ax.set_ylabel(label, fontsize=8)
        ax.axvspan(0.5 * t_end, t_end, color="0.9")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("time [s] (shaded: the half averaged)")
    fig.suptitle("the main job's trimmed canopy, rigid, in sideslip (coarse mesh, wall functions)", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print("wrote", png)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--deformed", required=True, help="the main job's structure run (its structure/ folder)")
    ap.add_argument("--sideslip", default="5,-5,0", help="sideslip angles [deg], run in this order")
    ap.add_argument("--out", default=str(ROOT / "studies-out/sideslip"))
    ap.add_argument("--json", default=str(ROOT / "docs/data/ramair_sideslip.json"))
    ap.add_argument("--env", default=str(ROOT / "build/share/fsi/fsi-env.sh"))
    ap.add_argument("--steps", type=int, default=480, help="time steps of each run (480: 2 s of flow)")
    ap.add_argument("--collect", action="store_true", help="only collect the finished points")
    ap.add_argument("--plot", default=None, help="only draw the histories of the finished points to this PNG "
                                                 "(docs/img/ramair_sideslip.png)")
    a = ap.parse_args()
    if a.plot:
        plot(a.out, a.plot)
        return
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    source = out / "shape" / "source" / "results.h5"
    if not source.exists():
        _, moved = symmetric_source(a.deformed, out / "shape")
        print(f"ramair_sideslip: the trimmed skin made symmetric (largest change {moved:.2e} m)")
    meta = {"command": "/usr/bin/python3 studies/ramair/ramair_sideslip.py --deformed RUN/structure "
                       f"--sideslip={a.sideslip}" + (f" --steps {a.steps}" if a.steps != 480 else ""),
            "deformed_from": str(Path(a.deformed).resolve()),
            "settings": SETTINGS + f"steps {a.steps}\nstl_deformed <the symmetrised last frame>\nsideslip <the point's>\n",
            "machine": f"{platform.node()}, {os.cpu_count()} cores (shared), {platform.machine()}",
            "date": datetime.date.today().isoformat()}
    for beta in [float(b) for b in a.sideslip.split(",")]:
        case, wall = (Path(a.out) / f"b{beta:+g}", 0.0) if a.collect else run_point(a.out, beta, source.resolve(), a.env, a.steps)
        if case is None or not (case / "summary.json").exists():
            continue
        row = collect(case, beta, wall, source)
        store(a.json, [row], meta)
        print(f"ramair_sideslip: beta {beta:+g} deg: side force {row['side_force_N']:+.3f} N, roll "
              f"{row['roll_moment_Nm']:+.3f} N m, yaw {row['yaw_moment_Nm']:+.3f} N m about CofR; CL {row['CL']:.4f}, "
              f"CD {row['CD']:.4f} ({row['wall_s']:.0f} s)")


if __name__ == "__main__":
    main()
