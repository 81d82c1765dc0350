#!/usr/bin/python3
"""The round canopy's inflation trends (docs/ROUND_CANOPY.md, "Inflation"): runs
cases/structure/round-canopy-inflation/scene.yaml at line stretch
under canopy_pressure for the cases below, reads each run's riser force and projected diameter histories
(results.h5 /tables/probes; their extremes are in summary.json's probe_extremes) and checks what the classical
design estimates say must hold whatever the model's constants:

  speed      peak force at 28.28 m/s over that at 20 m/s near (v2/v1)^2 = 2 (band 1.6-2.4, ±20 %: the pressure
             scales with v^2 exactly, and so does the steady force - checked to 3 % - but the peak is the snatch
             of elastic lines and cloth whose stiffness does not scale with the load);
  porosity   a porous canopy (300 ft^3/ft^2/min cloth, Darcy a = 4.5e6 1/m) has a lower peak and steady force
             and fills more slowly than the tight one;
  filling    the filling distance n = v t_f / D0 the same at both speeds within 15 % (the design rule's
             t_f = n D0 / v; the output interval is 2 ms of a t_f of 0.13-0.18 s);
  mass       the finite-mass system (the 5 kg payload free: it slows, and the dynamic pressure with it) has a
             lower peak than the infinite-mass one (payload held: constant speed).

and reports the classical comparisons: the opening-load factor C_x = F_peak / F_steady (infinite mass; Knacke:
about 1.7 for a flat circular canopy) and the filling distance n = v t_f / D0 (t_f: line stretch to the
first time the projected diameter reaches 95 % of its largest; Knacke's order 8-12 for solid cloth).

  round_canopy_inflation.py FSI OUT [--full]       --full: the case's own mesh (12 gores) and the study's extra speeds, its
                                      results in docs/data/round_canopy_inflation.json and plots in docs/img/;
                                      without it the CI size (8 gores, 6 divisions, 0.5 s), plots in OUT.
Exit 0: every trend holds; 1: one does not (printed).
"""

import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(REPO, "cases", "structure", "round-canopy-inflation")
sys.path.insert(0, os.path.join(REPO, "studies", "common"))
import provenance  # noqa: E402
D0, RHO = 2.0, 1.225
HOLD = "constraints=[{nodes: canopy/payload, fix: all}]"
CI = ["meshes.canopy.generator.gores=8", "meshes.canopy.generator.radial_divisions=6",
      "meshes.canopy.generator.line_elements=2", "time.end=0.5", "output.fields=displacement"]


def cases(full):
    c = {
        "infinite mass, 20 m/s": {"speed": 20.0, "hold": True},
        "infinite mass, 28.28 m/s": {"speed": 28.2843, "hold": True},
        "infinite mass, 20 m/s, porous": {"speed": 20.0, "hold": True, "darcy": 4.5e6},
        "finite mass, 20 m/s": {"speed": 20.0, "hold": False},
    }
    if full:
        c["infinite mass, 14.14 m/s"] = {"speed": 14.1421, "hold": True}
        c["finite mass, 28.28 m/s"] = {"speed": 28.2843, "hold": False}
    return c


def run(fsi, out, name, spec, full):
    d = os.path.join(out, name.replace(" ", "_").replace(",", "").replace("/", ""))
    sets = [] if full else list(CI)
    sets += [f"effects.canopy_pressure.wind=[0, 0, {spec['speed']}]"]
    if spec["hold"]:
        sets.append(HOLD)
    if "darcy" in spec:
        sets.append(f"effects.canopy_pressure.darcy={spec['darcy']}")
    if full:
        sets.append("time.end=" + str(round(max(0.6, 12.0 / spec["speed"]), 3)))
    cmd = [fsi, "run", os.path.join(HERE, "scene.yaml"), "--out", d, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return d


def history(d):
    import h5py
    import numpy as np
    with h5py.File(os.path.join(d, "results.h5"), "r") as f:
        t = f["tables/probes"]
        return {k: np.array(t[k][:]) for k in ("time", "riser_force", "projected_diameter", "payload_z")}


def analyse(d, spec):
    import numpy as np
    h = history(d)
    s = json.load(open(os.path.join(d, "summary.json")))
    ext = s["probe_extremes"]
    t, f, dp = h["time"], h["riser_force"], h["projected_diameter"]
    tf = float(t[np.argmax(dp >= 0.95 * dp.max())])
    q = 0.5 * RHO * spec["speed"] ** 2
    tail = t >= t[-1] - 0.1
    r = {
        "speed": spec["speed"], "infinite_mass": spec["hold"], "darcy": spec.get("darcy", 0.0),
        "peak_force": ext["riser_force"]["max"], "time_of_peak": ext["riser_force"]["time_of_max"],
        "steady_force": float(f[tail].mean()), "filling_time": tf,
        "filling_distance_n": spec["speed"] * tf / D0,
        "projected_diameter_max": ext["projected_diameter"]["max"],
        "projected_diameter_end_over_D0": float(dp[tail].mean()) / D0,
        "wall_seconds": s["stats"]["wall_seconds"],
    }
    if spec["hold"]:
        r["CD0"] = r["steady_force"] / (q * 3.14159265 * D0 ** 2 / 4)
        r["Cx"] = r["peak_force"] / r["steady_force"]
    return r, h


def plots(results, hist, out, full):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for name, h in hist.items():
        ax[0].plot(h["time"], h["riser_force"], label=name, lw=1)
        ax[1].plot(h["time"], h["projected_diameter"] / D0, label=name, lw=1)
    ax[0].set_xlabel("time from line stretch [s]")
    ax[0].set_ylabel("riser force [N]")
    ax[1].set_xlabel("time from line stretch [s]")
    ax[1].set_ylabel("projected diameter D_p / D0")
    ax[0].legend(fontsize=8)
    ax[0].grid(alpha=0.3)
    ax[1].grid(alpha=0.3)
    fig.suptitle("Round canopy (flat, D0 = 2 m) opening from line stretch, structure only"
                 + ("" if full else " - CI size"))
    fig.tight_layout()
    name = os.path.join(out, "round_canopy_inflation.png")
    fig.savefig(name, dpi=110)
    plt.close(fig)
    return name


def snapshots(d, out, times):
    """Side views (x-z) of the opening at a few times: cloth triangles' edges and the lines."""
    import h5py
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    with h5py.File(os.path.join(d, "results.h5"), "r") as f:
        tri = f["mesh/triangles"][:]
        lines = f["mesh/lines"][:]
        steps = sorted(f["steps"].keys())
        st = np.array([f["steps/" + k].attrs["time"] for k in steps])
        frames = []
        for t in times:
            k = steps[int(np.argmin(abs(st - t)))]
            frames.append((float(f["steps/" + k].attrs["time"]), f["steps/" + k + "/coordinates"][:]))
    fig, ax = plt.subplots(1, len(frames), figsize=(2.6 * len(frames), 5), sharey=True)
    for a, (t, x) in zip(ax, frames):
        base = x[:, 2].min()
        for e in tri:
            p = x[list(e) + [e[0]]]
            a.plot(p[:, 0], p[:, 2] - base, color="tab:blue", lw=0.4)
        for e in lines:
            p = x[list(e)]
            a.plot(p[:, 0], p[:, 2] - base, color="0.5", lw=0.5)
        a.set_title(f"t = {t:.3f} s", fontsize=9)
        a.set_aspect("equal")
        a.set_xlim(-1.2, 1.2)
        a.set_xlabel("x [m]")
    ax[0].set_ylabel("height above the payload [m]")
    fig.suptitle("Opening from line stretch, side views (infinite mass, 20 m/s)")
    fig.tight_layout()
    name = os.path.join(out, "round_canopy_opening.png")
    fig.savefig(name, dpi=110)
    plt.close(fig)
    return name


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    fsi, out = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    full = "--full" in sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    cs = cases(full)
    with ThreadPoolExecutor(max_workers=2) as pool:
        dirs = dict(zip(cs, pool.map(lambda n: run(fsi, out, n, cs[n], full), cs)))
    results, hist = {}, {}
    for n in cs:
        results[n], hist[n] = analyse(dirs[n], cs[n])
    for n, r in results.items():
        print(f"{n:32s} peak {r['peak_force']:7.1f} N at {r['time_of_peak']:.3f} s  steady {r['steady_force']:6.1f} N"
              f"  t_f {r['filling_time']:.3f} s (n = {r['filling_distance_n']:.1f})"
              + (f"  C_D0 {r['CD0']:.2f}  C_x {r['Cx']:.2f}" if "Cx" in r else ""))
    a, b = results["infinite mass, 20 m/s"], results["infinite mass, 28.28 m/s"]
    p, m = results["infinite mass, 20 m/s, porous"], results["finite mass, 20 m/s"]
    checks = [
        ("peak force ratio 28.28 / 20 m/s in [1.6, 2.4] (v^2: 2)", 1.6 <= b["peak_force"] / a["peak_force"] <= 2.4,
         b["peak_force"] / a["peak_force"]),
        ("steady force ratio 28.28 / 20 m/s within 3 % of 2", abs(b["steady_force"] / a["steady_force"] / 2 - 1) < 0.03,
         b["steady_force"] / a["steady_force"]),
        ("filling distance n = v t_f / D0 the same at 28.28 and 20 m/s within 15 % (t_f ~ D0 / v)",
         abs(b["filling_distance_n"] / a["filling_distance_n"] - 1) < 0.15,
         b["filling_distance_n"] / a["filling_distance_n"]),
        ("porous canopy: lower peak force", p["peak_force"] < a["peak_force"], p["peak_force"] / a["peak_force"]),
        ("porous canopy: lower steady force", p["steady_force"] < a["steady_force"],
         p["steady_force"] / a["steady_force"]),
        ("porous canopy: fills more slowly", p["filling_time"] > a["filling_time"],
         p["filling_time"] / a["filling_time"]),
        ("finite mass: lower peak force than infinite mass", m["peak_force"] < a["peak_force"],
         m["peak_force"] / a["peak_force"]),
    ]
    ok = True
    for label, passed, value in checks:
        print(f"{'ok  ' if passed else 'FAIL'} {label}: {value:.3f}")
        ok = ok and passed
    img_dir = os.path.join(REPO, "docs", "img") if full else out
    print("plots:", plots(results, hist, img_dir, full), snapshots(dirs["infinite mass, 20 m/s"], img_dir,
                                                                    [0.0, 0.05, 0.1, 0.15, 0.2, 0.3, 0.45]))
    data = {"command": "studies/roundcanopy/round_canopy_inflation.py build/bin/fsi OUT" + (" --full" if full else ""),
            "machine": provenance.machine(), "commit": provenance.git_commit(),
            "results": results, "checks": {c[0]: {"passed": bool(c[1]), "value": c[2]} for c in checks}}
    path = os.path.join(REPO, "docs", "data", "round_canopy_inflation.json") if full else os.path.join(out, "trends.json")
    with open(path, "w") as fh:
        json.dump(data, fh, indent=2)
    print("results:", path)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
