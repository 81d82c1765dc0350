#!/usr/bin/python3
"""The CI-size check of rungs 3 and 4 (studies/ramair/trim_study.py, docs/AERODYNAMICS.md). The coupled runs
themselves take 4-12 min each and are the study's; CI's main job (fluid.ramair-kt-coupled) is its level s1.
Checked here, in seconds, against references that do not come from the study:
  - the extrapolation to h -> 0: f = f0 + k h^p sampled at the study's h = 1, 2/3, 1/2 gives f0 and p back
    (p = 1.5 and 2); two levels extrapolate at first order; levels that do not converge monotonically give the
    finest value with their largest difference as the error bar, and say so;
  - the committed docs/data/ramair_convergence.json: three structure levels or more, at least two fluid levels,
    each row's trim_reached a boolean; `converged` is the structure levels' value on the main job's fluid mesh,
    its error bar theirs plus the largest change a finer fluid level made; the main job's
    inputs are those of cases/coupled/ramair-kt (structure.yaml's sha256): a changed main job fails here until
    the study is re-run;
  - the committed docs/data/ramair_polar.json: at least four rigging angles, CL and CD with the area they are on.
Usage: test_trim_study.py SOURCE_DIR"""
import hashlib
import json
import sys
from pathlib import Path

ROOT = Path(sys.argv[1]).resolve() if len(sys.argv) > 1 else Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies/ramair"))
import trim_study  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def main():
    h = [1.0, 2.0 / 3.0, 0.5]
    for p in (1.5, 2.0):
        r = trim_study.richardson(h, [0.6 - 0.1 * x ** p for x in h])
        check(abs(r["extrapolated"] - 0.6) < 2e-3 and abs(r["order"] - p) < 0.02,
              f"f = 0.6 - 0.1 h^{p}: extrapolated {r['extrapolated']:.5f}, order {r['order']:.3f}")
        check(abs(r["error_bar"] - 0.1 * 0.5 ** p) < 2e-3, f"error bar = |f0 - f(h = 1/2)| ({r['error_bar']:.5f})")
    r = trim_study.richardson(h, [0.50, 0.56, 0.53])
    check(r["order"] is None and r["extrapolated"] == 0.53 and abs(r["error_bar"] - 0.03) < 1e-12,
          f"non-monotone levels: the finest value 0.53 +- 0.03, no order ({r['order_is']})")
    r = trim_study.richardson(h, [4.34, 5.13, 6.18])
    check(r["order"] is None and r["extrapolated"] == 6.18 and "outside" in r["order_is"],
          f"monotone levels that do not shrink (order below 0.5): the finest value, no order ({r['order_is'][:60]}...)")
    r = trim_study.richardson([1.0, 0.5], [0.50, 0.52])
    check(abs(r["extrapolated"] - 0.54) < 1e-12 and r["order"] == 1.0, "two levels: first order assumed (0.54)")
    check(trim_study.richardson([1.0], [0.5]) is None, "one level: no extrapolation")

    conv = json.loads((ROOT / "docs/data/ramair_convergence.json").read_text())
    rows = [r for r in conv["levels"] if r.get("bending") and "CL" in r]
    levels = {(r["structure"], r["fluid"]) for r in rows}
    fluids = {f for _, f in levels}
    check(len({s for s, _ in levels}) >= 3 and len(fluids) >= 2,
          f"levels run: {sorted(levels)} (three structure levels, two fluid levels asked)")
    check(all(isinstance(r["trim_reached"], bool) for r in conv["levels"]), "every row says whether it trimmed")
    steady = [r for r in rows if "variant" not in r and r["balance"] < 0.01 and r["CL_change_last"] < 0.01]
    for key, c in conv["converged"].items():
        sel = sorted((r for r in steady if r["fluid"] == "f1" and key in r), key=lambda r: -r["h"])
        again = trim_study.richardson([r["h"] for r in sel], [r[key] for r in sel])
        fluid = [abs(r[key] - next(q[key] for q in sel if q["structure"] == r["structure"]))
                 for r in steady if r["fluid"] != "f1" and any(q["structure"] == r["structure"] for q in sel)]
        want = again["error_bar"] + (max(fluid) if fluid else 0.0)
        check(again is not None and abs(again["extrapolated"] - c["extrapolated"]) < 1e-12
              and abs(c["error_bar"] - want) < 1e-12,
              f"converged {key} {c['extrapolated']:.4f} +- {c['error_bar']:.4f}: the structure levels' value on the "
              f"main job's fluid mesh, the bar theirs + the largest fluid-level change")
    sha = hashlib.sha256((ROOT / "cases/coupled/ramair-kt/structure.yaml").read_bytes()).hexdigest()
    check(conv["main_job_inputs"]["structure_yaml_sha256"] == sha,
          "the convergence study ran the main job's structure.yaml as it is now (re-run it after a change: "
          "/usr/bin/python3 studies/ramair/trim_study.py --runs convergence --docs)")

    polar = json.loads((ROOT / "docs/data/ramair_polar.json").read_text())
    done = [r for r in polar["rows"] if "CL" in r]
    check(len({r["rigging_angle_deg"] for r in done}) >= 4,
          f"flexible polar at {sorted(r['rigging_angle_deg'] for r in done)} deg of rigging (four asked)")
    check("design projected area" in polar["coefficients_are"], "the polar names its reference area")
    check(all(r["CD_system"] > r["CD"] > 0 for r in done), "CD system (with the lines) exceeds the canopy's")
    print(json.dumps({"failures": len(failures)}))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
