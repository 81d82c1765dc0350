#!/usr/bin/python3
"""Table of issue 16's scaling runs (run.sh): per window, where the wall time went, and Amdahl's limit.

Usage: collect.py [RUNS_DIR] [--json OUT.json] [--plot OUT.png]   (RUNS_DIR default /tmp/fsi-adapter-scale)

Reads each RUNS_DIR/N<N>-np<R>[-t<T>]/ (T: the structure's threads, run.sh's 5th argument):
structure/timing.json (wall, transfer, structure, windows, ranks), log.pimpleFoam (the adapter's end-of-run
lines: set-up, the transfer's parts, the mesh guard's checks; the last ExecutionTime/ClockTime) and
uptime.txt (load before and after). All times are the master rank's wall times. Per window:
  fluid      = (wall - set-up - transfer - structure - checkpoints - mesh checks) / windows
               (the solver's own work: pimpleFoam's step and mesh motion, everything not the adapter's)
  master     = structure + load and displacement projections: work only rank 0 does
  comm       = gather + scatter (on the master: its own share plus waiting for and combining the others')
  serial fraction s = master / window wall (window wall = (wall - set-up) / windows); with the gather and
  scatter counted as serial too: s_comm. Amdahl: speed-up on P ranks <= 1 / (s + (1 - s) / P) < 1 / s.
"""
import argparse
import glob
import json
import os
import re
import sys


def number(pattern, text, what, path):
    m = re.search(pattern, text)
    if not m:
        sys.exit(f"collect.py: {path}: no {what} (pattern {pattern!r}); did the run finish?")
    return float(m.group(1))


def read_run(d):
    tj = os.path.join(d, "structure", "timing.json")
    log = os.path.join(d, "log.pimpleFoam")
    for p in (tj, log):
        if not os.path.isfile(p):
            sys.exit(f"collect.py: {p} is missing; did the run finish?")
    with open(tj) as f:
        t = json.load(f)
    text = open(log, errors="replace").read()
    up = open(os.path.join(d, "uptime.txt")).read() if os.path.isfile(os.path.join(d, "uptime.txt")) else ""
    loads = [float(x) for x in re.findall(r"load average: ([0-9.]+)", up)]
    f = r"([0-9.eE+-]+)"
    r = {
        "case": os.path.basename(d),
        "threads": int(re.search(r"-t(\d+)$", d).group(1)) if re.search(r"-t(\d+)$", d) else 1,
        "points": int(number(r"\[fsi\] patch \S+: (\d+) fluid points", text, "patch line", log)),
        "nodes": int(number(r"<- (\d+) structure nodes", text, "patch line", log)),
        "projection": re.search(r"structure nodes, (\w+) L2 projection", text).group(1),
        "projection_setup": number(r"set up in " + f + " s", text, "projection set-up", log),
        "subcycles": int(number(r"(\d+) structural steps per window", text, "subcycles", log)),
        "ranks": t["ranks"],
        "windows": t["windows"],
        "wall": t["wall_seconds"],
        "transfer": t["transfer_seconds"],
        "structure": t["structure_seconds"],
        "checkpoints": t["checkpoint_seconds"],
        "setup": number(r"\[fsi\] set-up " + f, text, "set-up line", log),
        "gather": number(r"gather " + f + " s", text, "gather", log),
        "load_projection": number(r"load projection " + f + " s", text, "load projection", log),
        "disp_projection": number(r"displacement projection " + f + " s", text, "displacement projection", log),
        "scatter": number(r"scatter " + f + " s", text, "scatter", log),
        "mesh_checks": number(r"checks " + f + " s", text, "mesh guard checks", log),
        "execution_time": [float(x) for x in re.findall(r"ExecutionTime = " + f, text)][-1],
        "clock_time": [float(x) for x in re.findall(r"ClockTime = " + f, text)][-1],
        "load_before": loads[0] if loads else None,
        "load_after": loads[-1] if loads else None,
    }
    w = r["windows"]
    adapter = r["transfer"] + r["structure"] + r["checkpoints"] + r["mesh_checks"]
    r["window_wall"] = (r["wall"] - r["setup"]) / w
    r["fluid_per_window"] = (r["wall"] - r["setup"] - adapter) / w
    r["structure_per_window"] = r["structure"] / w
    r["projection_per_window"] = (r["load_projection"] + r["disp_projection"]) / w
    r["comm_per_window"] = (r["gather"] + r["scatter"]) / w
    r["face_forces_per_window"] = (r["transfer"] - r["gather"] - r["scatter"] - r["load_projection"]
                                   - r["disp_projection"]) / w
    r["other_adapter_per_window"] = (r["checkpoints"] + r["mesh_checks"]) / w
    master = r["structure_per_window"] + r["projection_per_window"]
    r["serial_fraction"] = master / r["window_wall"]
    r["serial_fraction_comm"] = (master + r["comm_per_window"]) / r["window_wall"]
    r["amdahl_limit"] = 1 / r["serial_fraction"]
    if r["face_forces_per_window"] < 0:
        sys.exit(f"collect.py: {log}: the transfer's parts add up to more than the transfer")
    # The master's share of a core over the run (CPU / wall; ClockTime has 1 s steps): on a shared machine
    # every wall time above is inflated by about 1 / cpu_share.
    r["cpu_share"] = r["execution_time"] / max(r["clock_time"], 1.0)
    r["structure_ns_per_triangle_step"] = 1e9 * r["structure"] / (
        w * r["subcycles"] * 4 * ((r["nodes"] - 1) // 2))  # cross pattern: nodes 2m^2+2m+1, triangles 4m^2
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="?", default="/tmp/fsi-adapter-scale")
    ap.add_argument("--json")
    ap.add_argument("--plot")
    a = ap.parse_args()
    dirs = sorted(glob.glob(os.path.join(a.runs, "N*-np*")),
                  key=lambda d: tuple(int(x) for x in re.findall(r"\d+", os.path.basename(d))))
    if not dirs:
        sys.exit(f"collect.py: no runs (N*-np*) in {a.runs}")
    runs = []
    for d in dirs:
        if not os.path.isfile(os.path.join(d, "structure", "timing.json")):
            print(f"collect.py: {d}: no structure/timing.json (running, or failed): left out", file=sys.stderr)
            continue
        runs.append(read_run(d))
    if not runs:
        sys.exit(f"collect.py: no finished runs in {a.runs}")
    ms = lambda x: f"{1e3 * x:.4g}"
    print("| fluid points (structure nodes) | ranks | load before/after | window wall [s] | fluid [s] | structure "
          "[s] | projections H, Hᵀ [ms] | gather + scatter [ms] | face forces [ms] | checkpoint, mesh checks "
          "[ms] | set-up [s] (projection) | master CPU share | serial fraction s (with gather/scatter) | 1/s |")
    print("|" + "---|" * 14)
    for r in runs:
        over = " (oversubscribed)" if r["ranks"] > 2 else ""
        if r["threads"] > 1:
            over += f", structure on {r['threads']} threads"
        print(f"| {r['points']:,} ({r['nodes']:,}) | {r['ranks']}{over} | {r['load_before']:.1f}/{r['load_after']:.1f} "
              f"| {r['window_wall']:.3g} | {r['fluid_per_window']:.3g} | {r['structure_per_window']:.3g} "
              f"| {ms(r['projection_per_window'])} | {ms(r['comm_per_window'])} | {ms(r['face_forces_per_window'])} "
              f"| {ms(r['other_adapter_per_window'])} | {r['setup']:.3g} ({r['projection_setup']:.3g}) | {r['cpu_share']:.2f} "
              f"| {100 * r['serial_fraction']:.1f} % ({100 * r['serial_fraction_comm']:.1f} %) "
              f"| {r['amdahl_limit']:.2g} |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(runs, f, indent=1)
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
        # colour: the quantity; marker and line: the rank count
        for ranks, mark, line in ((1, "o", "-"), (2, "s", "--"), (4, "^", ":")):
            sel = [r for r in runs if r["ranks"] == ranks and r["threads"] == 1]
            if not sel:
                continue
            label = f"{ranks} rank(s)" + (" (oversubscribed)" if ranks > 2 else "")
            x = [r["points"] for r in sel]
            ax[0].loglog(x, [r["structure_per_window"] for r in sel], mark + line, color="C0", label=f"structure, {label}")
            ax[0].loglog(x, [r["fluid_per_window"] for r in sel], mark + line, color="C1", label=f"fluid, {label}")
            ax[0].loglog(x, [r["comm_per_window"] + r["projection_per_window"] for r in sel], mark + line, color="C2",
                         label=f"gather+scatter+H+Hᵀ, {label}")
            ax[1].semilogx(x, [100 * r["serial_fraction"] for r in sel], mark + line, color="k", label=label)
        ax[0].set_xlabel("fluid points on the interface")
        ax[0].set_ylabel("seconds per window (master rank, wall)")
        ax[0].legend(fontsize=6)
        ax[0].grid(True, which="both", alpha=0.3)
        ax[1].set_xlabel("fluid points on the interface")
        ax[1].set_ylabel("serial fraction s [%] (structure + projections)")
        ax[1].legend(fontsize=7)
        ax[1].grid(True, which="both", alpha=0.3)
        fig.suptitle("Coupled runs at scale (issue 16): 2-core VM, shared (load in docs/PERFORMANCE.md)")
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)


if __name__ == "__main__":
    main()
