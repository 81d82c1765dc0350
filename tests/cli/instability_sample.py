#!/usr/bin/python3
"""Short explicit runs at random steps around the element estimate, to see whether an unstable run can end
without exit code 3 (silent garbage) or a stable one is stopped (false alarm).

Each sample: a case (hencky, sphere, airbag, catenary-cable), a fixed step f x the element estimate at rest
(f in [0.7, 1.6]), a length of 20-2000 steps, output interval 0 or a third of the run, sometimes another
monitoring interval. Its answer is compared with a run at half the element step to the same time: more than 2 %
of the case's static value away counts as wrong. With a second binary (the old one), both are run and compared.

Usage: instability_sample.py FSI [OLD_FSI] [--seed S] [--runs N]      (docs/VALIDATION.md quotes seed 11, 150)
"""
import argparse
import json
import math
import os
import random
import shutil
import subprocess
import tempfile

SOURCE = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
# case: (probe, static magnitude, element estimate of the stable step at rest [s])
CASES = {"hencky": ("center_deflection", 0.0331, 1.10e-5), "sphere": ("radial_displacement", 3.3e-4, 3.6e-6),
         "airbag": ("center_displacement", 0.216, 3.17e-5), "catenary-cable": ("apex_height", 1.0, 4.21e-5)}


def run(fsi, case, sets, out):
    shutil.rmtree(out, ignore_errors=True)
    cmd = [fsi, "run", os.path.join(SOURCE, "cases/structure", case, "scene.yaml"), "--out", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    try:
        with open(os.path.join(out, "summary.json")) as f:
            return rc, json.load(f)["probes"][CASES[case][0]]
    except (OSError, KeyError, ValueError):
        return rc, float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fsi")
    ap.add_argument("old", nargs="?")
    ap.add_argument("--seed", type=int, default=11)
    ap.add_argument("--runs", type=int, default=150)
    a = ap.parse_args()
    random.seed(a.seed)
    work = tempfile.mkdtemp(prefix="fsi-sample-")
    binaries = {"new": a.fsi} if not a.old else {"new": a.fsi, "old": a.old}
    stats = {k: {"silent": 0, "false_alarm": 0, "stopped": 0} for k in binaries}
    for _ in range(a.runs):
        case = random.choice(list(CASES))
        probe, mag, dt0 = CASES[case]
        f = random.uniform(0.7, 1.6)
        n = random.choice([20, 60, 200, 600, 2000])
        end = n * f * dt0
        common = [f"time.until_static.max_time={end:g}"]
        sets = common + [f"time.fixed_dt={f * dt0:g}", f"output.interval={random.choice([0, end / 3]):g}"]
        if random.random() < 0.3:
            sets.append(f"time.monitor_every={random.choice([1, 7, 50])}")
        _, ref = run(a.fsi, case, common + [f"time.fixed_dt={0.5 * dt0:g}", "time.monitor_every=1000000000",
                                             "output.interval=0"], os.path.join(work, "ref"))
        res = {k: run(b, case, sets, os.path.join(work, k)) for k, b in binaries.items()}
        bad = {k: not math.isfinite(p) or abs(p - ref) > 0.02 * mag for k, (rc, p) in res.items()}
        for k, (rc, _) in res.items():
            stats[k]["stopped"] += rc == 3
            stats[k]["silent"] += rc != 3 and bad[k]
            # A needless stop: another binary ran the same sample to the end and got the right answer.
            stats[k]["false_alarm"] += rc == 3 and any(res[o][0] != 3 and not bad[o] for o in res if o != k)
        print(f"{case:14s} f={f:.2f} n={n:4d} ref={ref:.4g} " +
              " ".join(f"{k}: exit {rc} {p:.4g}" for k, (rc, p) in res.items()), flush=True)
    shutil.rmtree(work, ignore_errors=True)
    for k, s in stats.items():
        print(f"{k}: {a.runs} runs, {s['stopped']} stopped as unstable, {s['silent']} ended otherwise with a wrong "
              f"answer, {s['false_alarm']} stopped where the other binary got the right answer")
    return 1 if stats["new"]["silent"] else 0


if __name__ == "__main__":
    raise SystemExit(main())
