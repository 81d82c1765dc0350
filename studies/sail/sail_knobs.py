#!/usr/bin/python3
"""What the coupled knobs cost and buy on the light sail (issue 15, docs/ACCURACY_COST.md "Coupled knobs on the
sail"): cases/coupled/sail-2d as shipped (implicit IQN-ILS at the default tolerance, the window's end load,
element damping) and one knob changed at a time — a 100x tighter coupling tolerance (1e-7), the default `mean`
load in the window, no element damping, the second-order fluid time scheme (backward), a 4x finer structural
step (subcycles), the staggered scheme instead of the implicit one — each a copy of the case
run serially with ./Allrun END to END = 0.6 s (120 windows: the impulsive start and the overshoot). Per run:
whether it reached END (else the mesh guard's or OpenFOAM's stop), the wall time, coupling iterations per
window, the window-to-window alternation of the sail's force over 0.2 s to END (summarize.py's
force_smoothness: 1 for a sign flip every window, 0 for a smooth force), and the camber and lift at END against
the shipped case's.

  /usr/bin/python3 studies/sail/sail_knobs.py [--out DIR] [--only shipped,tolerance] [--end 0.6] [--collect] [--docs]

--collect reads finished runs in OUT instead of running them. --docs also stores the rows with the machine,
date and commit in docs/data/sail_knobs.json, from where studies/cost/accuracy_cost.py puts them into
docs/ACCURACY_COST.md. About 3 minutes per run on the 2-core machine of docs/PERFORMANCE.md (the run without
damping stops early). The environment (build/share/fsi/fsi-env.sh) is sourced for every run."""
import argparse
import datetime
import json
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CASE = ROOT / "cases/coupled/sail-2d"
ENV = ROOT / "build/share/fsi/fsi-env.sh"
sys.path.insert(0, str(ROOT / "cases/coupled"))
sys.path.insert(0, str(ROOT / "studies/common"))
import summarize  # noqa: E402 (the cases' own reader and force_smoothness)
from case_variants import chosen, stop_reason  # noqa: E402
from provenance import git_commit, machine  # noqa: E402 (the same machine line as the other tables)


def replace_once(text, old, new, where):
    if text.count(old) != 1:
        sys.exit(f"sail_knobs: {where} has {text.count(old)} copies of {old!r}, expected 1 (the case changed?)")
    return text.replace(old, new)


# variant: (what it changes, {file: (old text, new text)})
VARIANTS = {
    "shipped": ("the case as shipped: tolerance 1e-5, `end`, element damping, Euler", {}),
    "tolerance": ("coupling tolerance 1e-5 -> 1e-7",
                  {"system/controlDict": ("scheme implicit; acceleration IQN-ILS;",
                                          "scheme implicit; acceleration IQN-ILS; tolerance 1e-7; maxIterations 60;")}),
    "mean-load": ("load in the window `end` -> `mean` (the default)",
                  {"structure.yaml": ("load_in_window: end", "load_in_window: mean")}),
    "no-damping": ("element damping `bulk_viscosity: {}` -> none",
                   {"structure.yaml": ("\n  bulk_viscosity: {}", "\n  {}")}),
    "bdf2": ("fluid time scheme Euler -> backward (BDF2)",
             {"system/fvSchemes": ("ddtSchemes { default Euler; }", "ddtSchemes { default backward; }")}),
    # The structure's own stable step already takes 16 steps per 5 ms window (wave speed 50 m/s over
    # 2 cm elements; the log's "structural steps per window"): 64 is 4x finer in time.
    "subcycles": ("structural steps per window: the stable step's 16 -> 64",
                  {"system/controlDict": ("scheme implicit; acceleration IQN-ILS;",
                                          "scheme implicit; acceleration IQN-ILS; subcycles 64;")}),
    "staggered": ("coupling scheme implicit IQN-ILS -> staggered (one pass per window)",
                  {"system/controlDict": ("scheme implicit; acceleration IQN-ILS;", "scheme staggered;")}),
}


def run_variant(name, out, end):
    _, changes = VARIANTS[name]
    d = out / name
    if d.exists():
        shutil.rmtree(d)
    shutil.copytree(CASE, d, ignore=shutil.ignore_patterns("0", "processor*", "[1-9]*", "log.*", "structure",
                                                          "postProcessing", "plots", "summary.json"))
    for f, (old, new) in changes.items():
        (d / f).write_text(replace_once((d / f).read_text(), old, new, f"{name}/{f}"))
    t0 = time.monotonic()
    with open(d / "Allrun.out", "w") as log:
        p = subprocess.run(["bash", "-c", f". '{ENV}' && ./Allrun {end}"], cwd=d, stdout=log,
                           stderr=subprocess.STDOUT)
    (d / "wall_seconds").write_text(f"{time.monotonic() - t0:.1f}\n")
    if p.returncode != 0:
        print(f"sail_knobs: {name} stopped (exit {p.returncode}); see {d / 'Allrun.out'}", file=sys.stderr)


def collect(name, out, end):
    d = out / name
    rows = summarize.coupling_rows(str(d))
    r = {"variant": name, "what": VARIANTS[name][0], "wall_s": float((d / "wall_seconds").read_text()),
         "windows": len(rows), "t_end": float(rows[-1]["time"]) if rows else 0.0}
    r["reached_end"] = r["t_end"] >= end * (1 - 1e-9)
    if not r["reached_end"]:
        r["stopped"] = stop_reason(d)
    if rows:
        r["iterations"] = summarize.iteration_statistics(rows)["mean_iterations"]
        r["alternation"] = summarize.force_smoothness(rows, {"column": "Fz_fluid", "from": 0.2,
                                                             "max_alternation": 1.0})["alternation"]
        r["camber"] = float(rows[-1]["camber"])
        r["lift_z"] = float(rows[-1]["lift_z"])
    return r


def table(rows):
    base = rows[0]
    out = ["| variant | reached the end | wall [s] | iterations per window | force alternation from 0.2 s | "
           "camber at the end [% c] | change of camber, lift vs shipped |", "|" + "---|" * 7]
    for r in rows:
        reached = "yes" if r["reached_end"] else f"no: {r['stopped']} (t = {r['t_end']:.3f} s)"
        if "camber" not in r:
            out.append(f"| {r['variant']} ({r['what']}) | {reached} | {r['wall_s']:.0f} | | | | |")
            continue
        same_time = r["reached_end"] and base["reached_end"]
        rel = "—" if r is base else (", ".join(f"{100 * (r[k] / base[k] - 1):+.2f} %" for k in ("camber", "lift_z"))
                                     if same_time else "(not at the same time)")
        alt = "—" if r["alternation"] is None else f"{r['alternation']:.4f}"
        out.append(f"| {r['variant']} ({r['what']}) | {reached} | {r['wall_s']:.0f} | {r['iterations']:.2f} | "
                   f"{alt} | {100 * r['camber']:.3f} | {rel} |")
    return "\n".join(out) + "\n"


def reading(rows):
    """What each knob buys against the shipped case, in words computed from the rows."""
    base = rows[0]
    out = []
    for r in rows[1:]:
        head = f"- {r['variant']}: "
        if not r["reached_end"]:
            out.append(head + f"the run does not survive ({r['stopped']}).")
            continue
        words = [f"{r['wall_s'] / base['wall_s']:.2f}× the wall time, {r['iterations']:.1f} iterations per window "
                 f"against {base['iterations']:.1f}"]
        if r.get("alternation") and base.get("alternation"):
            ratio = r["alternation"] / base["alternation"]
            words.append(f"force alternation {r['alternation']:.4f} against {base['alternation']:.4f} "
                         f"({ratio:.1f}× the shipped case's)" if abs(ratio - 1) > 0.1 else
                         f"the same force alternation ({r['alternation']:.4f})")
        words.append(f"camber {100 * (r['camber'] / base['camber'] - 1):+.2f} %")
        out.append(head + "; ".join(words) + ".")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "results/sail-knobs"))
    ap.add_argument("--only", default=",".join(VARIANTS))
    ap.add_argument("--end", type=float, default=0.6, help="end time of every run [s] (default 0.6)")
    ap.add_argument("--collect", action="store_true")
    ap.add_argument("--docs", action="store_true", help="store the rows under docs/data (see above)")
    a = ap.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    names = chosen(a.only, VARIANTS, "sail_knobs")
    if not a.collect:
        for n in names:
            print(f"sail_knobs: running {n} in {out / n}", flush=True)
            run_variant(n, out, a.end)
    rows = [collect(n, out, a.end) for n in VARIANTS if (out / n / "wall_seconds").exists()]
    if not rows or rows[0]["variant"] != "shipped" or not rows[0]["reached_end"]:
        sys.exit("sail_knobs: the shipped case is the reference and did not reach the end")
    (out / "knobs.json").write_text(json.dumps(rows, indent=1))
    print(table(rows))
    print(reading(rows))
    if a.docs:
        stamp = datetime.datetime.fromtimestamp(max((out / r["variant"] / "wall_seconds").stat().st_mtime
                                                    for r in rows), datetime.timezone.utc)
        meta = {"command": "/usr/bin/python3 studies/sail/sail_knobs.py --docs", "end": a.end, "machine": machine(),
                "finished": stamp.strftime("%Y-%m-%d %H:%M UTC"), "commit": git_commit(), "rows": rows}
        (ROOT / "docs/data").mkdir(exist_ok=True)
        (ROOT / "docs/data/sail_knobs.json").write_text(json.dumps(meta, indent=1) + "\n")


if __name__ == "__main__":
    main()
