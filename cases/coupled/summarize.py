#!/usr/bin/env python3
"""Writes summary.json of a coupled case from its structure/coupling*.csv, structure/timing.json and
reference.yaml: probe histories reduced to the quantities the reference names, compared with the published
values, plus the coupling statistics and the wall time.

Usage: summarize.py CASE_DIR WALL_SECONDS
       summarize.py --force-check CASE_DIR   (exit 1 unless fluid and structure interface forces agree < 1e-6)
"""
import csv
import glob
import json
import os
import sys



def history(case, probe):
    rows = []
    for f in sorted(glob.glob(os.path.join(case, "structure", "coupling*.csv")), key=os.path.getmtime):
        rows += list(csv.DictReader(open(f)))
    t = [float(r["time"]) for r in rows]
    v = [float(r[probe]) for r in rows]
    return rows, t, v


def force_difference(rows):
    """Largest relative difference of the interface force, fluid side vs structure side, over all windows."""
    worst = 0.0
    for r in rows:
        f = [float(r[k + "_fluid"]) for k in ("Fx", "Fy", "Fz")]
        s = [float(r[k + "_structure"]) for k in ("Fx", "Fy", "Fz")]
        scale = max(abs(x) for x in f)
        if scale > 0:
            worst = max(worst, max(abs(a - b) for a, b in zip(f, s)) / scale)
    return worst


def force_check(case):
    rows, _, _ = history(case, "time")
    worst = force_difference(rows)
    print(f"{len(rows)} windows, largest relative difference of the interface force fluid/structure {worst:.2e}")
    return 0 if rows and worst < 1e-6 else 1


def local_maxima(t, v):
    return [(t[i], v[i]) for i in range(1, len(v) - 1) if v[i - 1] < v[i] >= v[i + 1]]


def measure(t, v, spec):
    """One scalar from a history: first local maximum after t_min, global max/min in a window, value at t."""
    kind = spec["measure"]
    lo, hi = spec.get("from", -1e300), spec.get("to", 1e300)
    sel = [(a, b) for a, b in zip(t, v) if lo <= a <= hi]
    if not sel:
        return None, None
    if kind == "first_peak":
        peaks = [p for p in local_maxima(t, v) if lo <= p[0] <= hi]
        return peaks[0] if peaks else (None, None)
    if kind == "max":
        return max(sel, key=lambda p: p[1])
    if kind == "min":
        return min(sel, key=lambda p: p[1])
    if kind == "final":
        return sel[-1]
    raise ValueError(f"unknown measure {kind}")


def last_rows(path):
    """Rows of an OpenFOAM function-object .dat file as {time: [numbers]}: vectors are flattened, and a time
    written twice (a repeated coupling iteration) keeps its last row."""
    rows = {}
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        nums = [float(x) for x in line.replace("(", " ").replace(")", " ").split()]
        rows[nums[0]] = nums[1:]
    return rows


def momentum_balance(case, rows, spec):
    """The membrane's load from the channel's momentum balance, against the load the structure received.

    For a steady flow between slip walls, the force of the fluid on everything inside the channel is
    F = -rho * sum(phi U) over inlet and outlet - (pressure + viscous force on inlet and outlet). After the
    inflow ramp the momentum in the channel does not change (incompressible, fixed inflow), so only the
    membrane's own motion is left out. Compared at the last time both files hold, component `component`."""
    pp = os.path.join(case, "postProcessing")
    k = "xyz".index(spec.get("component", "z"))
    force = last_rows(os.path.join(pp, spec["force"], "0", "force.dat"))
    flux = [last_rows(os.path.join(pp, name, "0", "surfaceFieldValue.dat")) for name in spec["flux"]]
    times = sorted(set(force).intersection(*flux))
    structure = {float(r["time"]): float(r["F" + "xyz"[k] + "_structure"]) for r in rows}
    times = [t for t in times if t in structure]
    if not times:
        return None, None, None
    t = times[-1]
    channel = -spec.get("rho", 1.0) * sum(f[t][k] for f in flux) - force[t][k]
    return t, structure[t], channel


def mesh_quality(case, spec):
    """checkMesh of the last time (log.checkMesh): 'Mesh OK.' and the largest non-orthogonality/skewness."""
    log = open(os.path.join(case, "log.checkMesh")).read()
    out = {"mesh_ok": "Mesh OK." in log}
    for key, pattern in (("max_non_orthogonality", "Mesh non-orthogonality Max:"),
                         ("max_skewness", "Max skewness =")):
        line = next((l for l in log.splitlines() if pattern in l), None)
        out[key] = float(line.split(pattern)[1].split()[0]) if line else None
    out["within"] = out["mesh_ok"] and all(
        out[k] is not None and out[k] <= spec[k] for k in ("max_non_orthogonality", "max_skewness"))
    out["limits"] = {k: spec[k] for k in ("max_non_orthogonality", "max_skewness")}
    return out


def main():
    if sys.argv[1] == "--force-check":
        return force_check(sys.argv[2])
    case, wall = sys.argv[1], float(sys.argv[2])
    import yaml  # only the full summary needs it

    ref = yaml.safe_load(open(os.path.join(case, "reference.yaml")))
    timing = json.load(open(os.path.join(case, "structure", "timing.json")))
    out = {"case": os.path.basename(os.path.abspath(case)), "wall_seconds": wall, "coupling": timing,
           "results": {}, "all_within_tolerance": True, "all_checks_within_tolerance": True}
    rows, t, v = history(case, ref["probe"])
    out["interface_force_relative_difference"] = force_difference(rows)
    out["end_time"] = t[-1] if t else None
    for name, spec in ref.get("quantities", {}).items():
        when, value = measure(t, v, spec)
        entry = {"value": value, "time": when, "published": spec["published"]}
        pub = [p["value"] for p in spec["published"]]
        lo, hi = min(pub), max(pub)
        tol = spec.get("tolerance", 0.1)
        entry["accepted_range"] = [lo - tol * abs(lo), hi + tol * abs(hi)]
        entry["within"] = value is not None and entry["accepted_range"][0] <= value <= entry["accepted_range"][1]
        entry["check"] = bool(spec.get("check", False))
        out["all_within_tolerance"] &= entry["within"]
        if entry["check"]:
            out["all_checks_within_tolerance"] &= entry["within"]
        out["results"][name] = entry
    checks = ref.get("checks", {})
    if "momentum_balance" in checks:
        spec = checks["momentum_balance"]
        when, structure, channel = momentum_balance(case, rows, spec)
        rel = abs(structure - channel) / abs(channel) if channel else None
        out["momentum_balance"] = {"time": when, "structure": structure, "channel": channel,
                                   "relative_difference": rel, "tolerance": spec["tolerance"],
                                   "within": rel is not None and rel <= spec["tolerance"]}
        out["all_checks_within_tolerance"] &= out["momentum_balance"]["within"]
    if "mesh_quality" in checks:
        out["mesh_quality"] = mesh_quality(case, checks["mesh_quality"])
        out["all_checks_within_tolerance"] &= out["mesh_quality"]["within"]
    json.dump(out, open(os.path.join(case, "summary.json"), "w"), indent=2)
    print(json.dumps({k: (v["value"], v["time"], v["within"]) for k, v in out["results"].items()}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
