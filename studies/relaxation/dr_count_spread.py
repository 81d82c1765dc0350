#!/usr/bin/env python3
"""How far a cushion's iteration count is a property of the method and how far an accident of round-off.
Each cushion is relaxed with the defaults (KDR, λ = 0.7, ε = 1e-3) under perturbations far below anything
physical, and the iterations to ε counted (summary.json):
  pressure   the pressure times (1 + k·1e-12), k = -N..N;
  lambda     λ moved by k units in the last place (the fictitious masses by ~1e-16 relative);
  pressure, no wrinkling   the pressure perturbation with materials.fabric.wrinkling=false (the reference
             thesis' membrane, which carries compression).
and, unperturbed, the iterations to ε = 1e-1, 1e-2, 1e-3 with and without wrinkling (where the extra
iterations go). Writes docs/data/dr_count_spread.json and docs/img/dr_count_spread.png.
Usage: studies/relaxation/dr_count_spread.py [--fsi PATH] [--n N]   (N = 10: 207 runs, about 4 minutes)"""
import argparse
import json
import statistics
from concurrent.futures import ThreadPoolExecutor

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from dr_common import ROOT, run  # noqa: E402  (puts studies/common on the path: fsi_runs)
import fsi_runs  # noqa: E402

# The thesis' best counts (../shared/reference/dynamic-relaxation.md) and the cases' pressure [Pa].
CASES = {"cushion-square-25": ("TL1", 518), "cushion-square-50": ("TL2", 1026),
         "cushion-circular": ("circular", 1542)}
PRESSURE, LAMBDA = 15.0e3, 0.7
FAMILIES = ["pressure", "lambda", "pressure, no wrinkling"]


def ulps_away(x, k):
    for _ in range(abs(k)):
        x = float(np.nextafter(x, np.inf if k > 0 else -np.inf))
    return x


def settings(family, k):
    if family == "lambda":
        return [f"solver.lambda={ulps_away(LAMBDA, k)!r}"]
    sets = [f"effects.pressure.value={PRESSURE * (1 + k * 1e-12)!r}"]
    return sets + (["materials.fabric.wrinkling=false"] if "no wrinkling" in family else [])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fsi", help="fsi binary (default build/bin/fsi)")
    ap.add_argument("--n", type=int, default=10)
    args = ap.parse_args()
    if args.fsi:
        fsi_runs.set_fsi(args.fsi)
    ks = list(range(-args.n, args.n + 1))
    jobs = [(case, fam, k) for case in CASES for fam in FAMILIES for k in ks]

    def one(job):
        s = run(job[0], settings(job[1], job[2]))["stats"]
        return s["iterations"] if s.get("converged") and s.get("restarts", 0) == 0 else None

    tails = [(case, w, eps) for case in CASES for w in (True, False) for eps in (1e-1, 1e-2, 1e-3)]

    def tail(job):
        sets = [f"solver.tolerance={job[2]!r}"] + ([] if job[1] else ["materials.fabric.wrinkling=false"])
        return run(job[0], sets)["stats"]["iterations"]

    with ThreadPoolExecutor(max_workers=2) as pool:
        counts = list(pool.map(one, jobs))
        tail_counts = list(pool.map(tail, tails))
    out = {"perturbation_k": ks, "pressure_step": 1e-12, "cases": {}}
    for case, (label, ref) in CASES.items():
        out["cases"][case] = {"label": label, "thesis_best": ref, "families": {}}
        for fam in FAMILIES:
            c = [n for (cs, f, _), n in zip(jobs, counts) if cs == case and f == fam]
            ok = [n for n in c if n is not None]
            d = {"iterations": c, "unperturbed": c[ks.index(0)], "median": statistics.median(ok),
                 "min": min(ok), "max": max(ok), "failed_or_restarted": len(c) - len(ok),
                 "below_thesis_best": sum(n <= ref for n in ok)}
            out["cases"][case]["families"][fam] = d
            print(f"{label:8s} {fam:24s} unperturbed {d['unperturbed']}, median {d['median']:g}, "
                  f"{d['min']}-{d['max']}, {d['below_thesis_best']}/{len(ok)} at or below the thesis' {ref}")
    for case, (label, _) in CASES.items():
        out["cases"][case]["to_tolerance"] = {}
        for w in (True, False):
            key = "wrinkling" if w else "no wrinkling"
            row = {f"{eps:g}": n for (c, ww, eps), n in zip(tails, tail_counts) if c == case and ww == w}
            out["cases"][case]["to_tolerance"][key] = row
            print(f"{label:8s} {key:13s} iterations to ε: {row}")
    (ROOT / "docs/data").mkdir(exist_ok=True)
    (ROOT / "docs/data/dr_count_spread.json").write_text(json.dumps(out, indent=1) + "\n")
    fig, axes = plt.subplots(1, len(CASES), figsize=(13, 3.8))
    for ax, (case, d) in zip(axes, out["cases"].items()):
        for fam, style in zip(FAMILIES, ["o-", "s--", "^:"]):
            f = d["families"][fam]
            ax.plot(ks, [n if n is not None else np.nan for n in f["iterations"]], style, ms=3,
                    label=f"{fam} (median {f['median']:g})")
        ax.axhline(d["thesis_best"], color="r", lw=1, label=f"thesis best {d['thesis_best']}")
        ax.set_title(d["label"])
        ax.set_xlabel("perturbation k (pressure ×(1 + k·1e-12); λ + k ulp)")
        ax.set_ylim(0, None)
        ax.legend(loc="lower right", fontsize=7)
    axes[0].set_ylabel("iterations to ε = 1e-3")
    fig.tight_layout()
    fig.savefig(ROOT / "docs/img/dr_count_spread.png", dpi=110)


if __name__ == "__main__":
    main()
