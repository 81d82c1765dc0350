#!/usr/bin/env python3
"""Writes summary.json of a coupled case from its structure/coupling*.csv, structure/timing.json and, when the
case has one, reference.yaml: probe histories reduced to the quantities the reference names, compared with the
published values; without it (a case of one's own) every probe's final value and range. Plus the coupling
statistics, the interface force balance and the wall time; prints the same in a few lines for people.

Usage: summarize.py CASE_DIR WALL_SECONDS [--continued]
         --continued: this run continued an earlier one; its wall time adds to the one in summary.json
       summarize.py --force-check CASE_DIR   (exit 1 unless fluid and structure interface forces agree < 1e-6)
"""
import csv
import glob
import json
import os
import sys



FORCE_TOLERANCE = 1e-6  # relative: the transfer is conservative, fluid and structure totals agree to round-off


def read_csv(path):
    """Rows of one coupling.csv. Lines starting with '#' are comments (a continued run appends
    `# restart at t = ...` and its rows to the same file); a repeated header line is skipped."""
    lines = [l for l in open(path) if l.strip() and not l.startswith("#")]
    if not lines:
        return []
    header = lines[0]
    return list(csv.DictReader([header] + [l for l in lines[1:] if l != header]))


def coupling_rows(case):
    """Windows of all run parts in time order: coupling.csv (continued runs appended to it, or written to
    coupling_from_<time>.csv by older adapters). A run continued from a time before its last logged window
    (the last write time of an interrupted run) logs those windows again: the later rows replace them."""
    rows = []
    for f in sorted(glob.glob(os.path.join(case, "structure", "coupling*.csv")), key=os.path.getmtime):
        for r in read_csv(f):
            t = float(r["time"])
            while rows and float(rows[-1]["time"]) >= t - 1e-12 * max(1.0, abs(t)):
                rows.pop()
            rows.append(r)
    return rows


def history(case, probe):
    rows = coupling_rows(case)
    t = [float(r["time"]) for r in rows]
    v = [float(r[probe]) for r in rows]
    return rows, t, v


def side_difference(rows, quantity):
    """Largest relative difference of an interface total ('F' force, 'M' moment about the origin), fluid side
    vs structure side, over all windows, relative to the window's largest fluid-side component; None if the
    columns are missing (moments: adapters before the Mx_fluid... columns)."""
    if not rows or quantity + "x_fluid" not in rows[0]:
        return None
    worst = 0.0
    for r in rows:
        f = [float(r[quantity + c + "_fluid"]) for c in "xyz"]
        s = [float(r[quantity + c + "_structure"]) for c in "xyz"]
        scale = max(abs(x) for x in f)
        if scale > 0:
            worst = max(worst, max(abs(a - b) for a, b in zip(f, s)) / scale)
    return worst


def force_difference(rows):
    return side_difference(rows, "F") or 0.0


def moment_difference(rows):
    return side_difference(rows, "M")


def force_check(case):
    rows, _, _ = history(case, "time")
    worst = force_difference(rows)
    print(f"{len(rows)} windows, largest relative difference of the interface force fluid/structure {worst:.2e}")
    return 0 if rows and worst < FORCE_TOLERANCE else 1


def local_maxima(t, v):
    return [(t[i], v[i]) for i in range(1, len(v) - 1) if v[i - 1] < v[i] >= v[i + 1]]


def measure(t, v, spec):
    """One scalar from a history: first local maximum after t_min, global max/min in a window, value at t,
    time average over a window."""
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
    if kind == "mean":  # the time average over the window (trapezoidal), reported at the window's end
        if len(sel) < 2:
            return sel[-1]
        area = sum(0.5 * (b[1] + a[1]) * (b[0] - a[0]) for a, b in zip(sel, sel[1:]))
        return sel[-1][0], area / (sel[-1][0] - sel[0][0])
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


def all_parts(folder, name):
    """Rows of a function object's .dat file over all run parts: OpenFOAM writes FOLDER/<start time>/NAME
    for each run (0 and, after a continued run, its start time); later parts win."""
    rows = {}
    parts = [d for d in glob.glob(os.path.join(folder, "*")) if os.path.isfile(os.path.join(d, name))]
    for d in sorted(parts, key=lambda d: float(os.path.basename(d))):
        rows.update(last_rows(os.path.join(d, name)))
    return rows


def momentum_balance(case, rows, spec):
    """The membrane's load from the channel's momentum balance, against the load the structure received.

    For a steady flow between slip walls, the force of the fluid on everything inside the channel is
    F = -rho * sum(phi U) over inlet and outlet - (pressure + viscous force on inlet and outlet). After the
    inflow ramp the momentum in the channel does not change (incompressible, fixed inflow), so only the
    membrane's own motion is left out. Component `component`, at the times both files hold: the last one, or
    with `average: T` the means over the last T seconds of them (the window-to-window noise of a coupled run
    at its coupling tolerance, about 1e-3 of the load in one window, averages out; the membrane's motion, which
    the balance leaves out, too). Returns (first time, last time, samples, structure, channel)."""
    pp = os.path.join(case, "postProcessing")
    k = "xyz".index(spec.get("component", "z"))
    force = all_parts(os.path.join(pp, spec["force"]), "force.dat")
    flux = [all_parts(os.path.join(pp, name), "surfaceFieldValue.dat") for name in spec["flux"]]
    times = sorted(set(force).intersection(*flux))
    structure = {float(r["time"]): float(r["F" + "xyz"[k] + "_structure"]) for r in rows}
    times = [t for t in times if t in structure]
    if not times:
        return None, None, 0, None, None
    span = spec.get("average", 0.0)
    times = [t for t in times if t >= times[-1] - span - 1e-9 * max(1.0, times[-1])]
    rho = spec.get("rho", 1.0)
    channel = sum(-rho * sum(f[t][k] for f in flux) - force[t][k] for t in times) / len(times)
    return times[0], times[-1], len(times), sum(structure[t] for t in times) / len(times), channel


def coefficient_header(path):
    """The directions and reference values a forceCoeffs object writes at the top of coefficient.dat."""
    head = {}
    for line in open(path):
        if not line.startswith("#"):
            break
        key, _, value = line[1:].partition(":")
        value = value.strip()
        if value.startswith("("):
            head[key.strip()] = [float(x) for x in value.strip("()").split()]
        elif value:
            try:
                head[key.strip()] = float(value)
            except ValueError:
                pass
    return head


def openfoam_coefficients(case, rows, spec):
    """OpenFOAM's own integration of the interface patches (a forceCoeffs object: lift and drag coefficients
    along its liftDir and dragDir) against the load the structure received in the same window, projected on
    the same directions: the largest difference over the windows, relative to the window's larger coefficient.
    An independent check of the transfer (the adapter's fluid-side sum is compared in every window anyway)."""
    folder = os.path.join(case, "postProcessing", spec["coefficients"])
    files = sorted(glob.glob(os.path.join(folder, "*", "coefficient.dat")))
    if not files:
        return {"windows": 0, "relative_difference": None, "within": False, "tolerance": spec["tolerance"]}
    head = coefficient_header(files[0])
    data = all_parts(folder, "coefficient.dat")  # columns after time: Cd Cs Cl ...
    qa = 0.5 * spec.get("rho", 1.0) * head["magUInf"] ** 2 * head["Aref"]
    worst, n = 0.0, 0
    for r in rows:
        t = float(r["time"])
        c = next((v for k, v in data.items() if abs(k - t) <= 1e-9 * max(1.0, t)), None)
        if c is None:
            continue
        f = [float(r["F" + a + "_structure"]) for a in "xyz"]
        cl = sum(a * b for a, b in zip(f, head["liftDir"])) / qa
        cd = sum(a * b for a, b in zip(f, head["dragDir"])) / qa
        worst = max(worst, max(abs(cl - c[2]), abs(cd - c[0])) / max(abs(c[2]), abs(c[0])))
        n += 1
    return {"windows": n, "relative_difference": worst if n else None, "tolerance": spec["tolerance"],
            "within": n > 0 and worst <= spec["tolerance"]}


def mesh_quality(case, spec):
    """checkMesh of the last time (log.checkMesh): 'Mesh OK.' and the largest non-orthogonality/skewness."""
    log = open(os.path.join(case, "log.checkMesh")).read()
    out = {"mesh_ok": "Mesh OK." in log}
    for key, pattern in (("max_non_orthogonality", "Mesh non-orthogonality Max:"),
                         ("max_skewness", "Max skewness =")):
        line = next((l for l in log.splitlines() if pattern in l), None)
        # a failed check writes '***Max skewness = 4.2, 1 highly skew faces ...': the number ends at the comma
        out[key] = float(line.split(pattern)[1].split()[0].rstrip(",")) if line else None
    out["within"] = out["mesh_ok"] and all(
        out[k] is not None and out[k] <= spec[k] for k in ("max_non_orthogonality", "max_skewness"))
    out["limits"] = {k: spec[k] for k in ("max_non_orthogonality", "max_skewness")}
    return out


def force_smoothness(rows, spec):
    """How much of an interface force's window-to-window change is a two-window alternation: the RMS of its
    second difference F[k+1] - 2 F[k] + F[k-1] over the windows from `from` on, divided by 4 x the RMS of F
    itself. A force that changes sign every window (F[k] = (-1)^k a) gives 1, a constant or linear one 0, and
    a sine of n windows per period sin^2(pi/n) (0.011 at 30 windows per period)."""
    col, start = spec["column"], spec.get("from", -1e300)
    f = [float(r[col]) for r in rows if float(r["time"]) >= start]
    out = {"column": col, "from": start, "windows": len(f), "limit": spec["max_alternation"]}
    if len(f) < 3:
        out.update(alternation=None, within=False)
        return out
    d2 = [f[k + 1] - 2 * f[k] + f[k - 1] for k in range(1, len(f) - 1)]
    rms = lambda x: (sum(a * a for a in x) / len(x)) ** 0.5
    out["alternation"] = rms(d2) / (4 * rms(f)) if rms(f) > 0 else None
    out["within"] = out["alternation"] is not None and out["alternation"] <= spec["max_alternation"]
    return out


def iteration_statistics(rows):
    """Coupling iterations per window over all windows of all run parts (timing.json has the last part)."""
    it = [int(r["iterations"]) for r in rows]
    return {"windows": len(it), "mean_iterations": sum(it) / len(it) if it else None,
            "max_iterations": max(it, default=None),
            "not_converged": sum(1 for r in rows if r["converged"].strip() == "0")}


def number(x):
    return "-" if x is None else f"{x:.4g}"


# The columns of coupling.csv that are the coupling's own (the rest are the scene's probes)
COUPLING_COLUMNS = {"time", "iterations", "converged", "residual", "subcycles", "kinetic_resets",
                    "equilibrium_residual"} | {f"{q}{c}_{side}" for q in "FM" for c in "xyz" for side in ("fluid", "structure")}


def probe_summary(rows):
    """Every probe column of coupling.csv: its value at the last window, its smallest and largest."""
    out = {}
    if not rows:
        return out
    for key in rows[0]:
        if key in COUPLING_COLUMNS or key is None:
            continue
        try:
            v = [float(r[key]) for r in rows]
        except (TypeError, ValueError):
            continue
        out[key] = {"final": v[-1], "min": min(v), "max": max(v)}
    return out


def report(out):
    """The summary in a few lines: what was measured against what was published, coupling, wall time."""
    it = out["iterations"]
    lines = [f"{out['case']}: {it['windows']} windows to t = {number(out['end_time'])} s, "
             f"{number(it['mean_iterations'])} coupling iterations per window (at most "
             f"{it['max_iterations']}, {it['not_converged']} not converged)"]
    if out.get("reference") is None:
        lines.append("  no reference.yaml: nothing compared with published values; the structure's probes (final, "
                     "smallest .. largest):")
        for name, p in out.get("probes", {}).items():
            lines.append(f"  {name:<24} {number(p['final'])} ({number(p['min'])} .. {number(p['max'])})")
    for name, e in out["results"].items():
        if e["value"] is None:
            lines.append(f"  {name:<14} not reached (the run ends at t = {number(out['end_time'])} s)")
            continue
        lo, hi = e["accepted_range"]
        pub = [p["value"] for p in e["published"]]
        verdict = "PASS" if e["within"] else "outside" + ("" if e["check"] else " (reported, not a check)")
        if not e["complete"]:
            verdict += f" (its window ends at t = {number(e['window_end'])} s, the run at {number(out['end_time'])} s)"
        published = number(pub[0]) if min(pub) == max(pub) else f"{number(min(pub))} .. {number(max(pub))}"
        lines.append(f"  {name:<14} {number(e['value'])} at t = {number(e['time'])} s; published {published}, "
                     f"accepted {number(lo)} .. {number(hi)}: {verdict}")
    if "momentum_balance" in out:
        m = out["momentum_balance"]
        when = (f"t = {number(m['time'])} s" if m.get("samples", 1) <= 1 else
                f"the mean over t = {number(m['from'])} .. {number(m['time'])} s ({m['samples']} samples)")
        lines.append(f"  momentum balance at {when}: structure load {number(m['structure'])}, "
                     f"channel {number(m['channel'])}, relative difference {number(m['relative_difference'])} "
                     f"(limit {m['tolerance']}): {'PASS' if m['within'] else 'outside'}")
    if "mesh_quality" in out:
        q = out["mesh_quality"]
        lines.append(f"  mesh at the end: {'Mesh OK' if q['mesh_ok'] else 'checkMesh FAILED'}, non-orthogonality "
                     f"{number(q['max_non_orthogonality'])} (limit {q['limits']['max_non_orthogonality']}), "
                     f"skewness {number(q['max_skewness'])} (limit {q['limits']['max_skewness']}): "
                     f"{'PASS' if q['within'] else 'outside'}")
    if "openfoam_coefficients" in out:
        q = out["openfoam_coefficients"]
        lines.append(f"  OpenFOAM's forceCoeffs vs the structure's load over {q['windows']} windows: largest relative "
                     f"difference {number(q['relative_difference'])} (limit {q['tolerance']}): "
                     f"{'PASS' if q['within'] else 'outside'}")
    if "force_smoothness" in out:
        q = out["force_smoothness"]
        lines.append(f"  {q['column']} window to window from t = {number(q['from'])} s: alternation "
                     f"{number(q['alternation'])} (RMS second difference / 4 RMS; limit {q['limit']}): "
                     f"{'PASS' if q['within'] else 'outside'}")
    d = out["interface_force_relative_difference"]
    lines.append(f"  interface force, fluid vs structure side: largest relative difference {d:.1e} over all "
                 f"windows: {'PASS' if d < FORCE_TOLERANCE else 'outside'} (conservative transfer: < {FORCE_TOLERANCE:g})")
    m = out.get("interface_moment_relative_difference")
    if m is not None:
        lines.append(f"  interface moment, fluid vs structure side: largest relative difference {m:.1e} over all "
                     f"windows: {'PASS' if m < FORCE_TOLERANCE else 'outside'} (conserveMoment: < {FORCE_TOLERANCE:g})")
    part = f" ({out['wall_seconds_last_part']:.1f} s in this part)" if "wall_seconds_last_part" in out else ""
    lines.append(f"  wall time {out['wall_seconds']:.1f} s{part}")
    return "\n".join(lines)


def main():
    if sys.argv[1] == "--force-check":
        return force_check(sys.argv[2])
    case, wall = sys.argv[1], float(sys.argv[2])
    continued = "--continued" in sys.argv[3:]
    import yaml  # only the full summary needs it

    ref_path = os.path.join(case, "reference.yaml")
    ref = yaml.safe_load(open(ref_path)) if os.path.exists(ref_path) else None
    timing_path = os.path.join(case, "structure", "timing.json")
    if not os.path.exists(timing_path):
        print(f"summarize.py: {timing_path} is missing: the coupled run wrote no structure output (see log.pimpleFoam)",
              file=sys.stderr)
        return 1
    timing = json.load(open(timing_path))
    path = os.path.join(case, "summary.json")
    # all_checks_within_tolerance: the checks the reference marks (check: true) that the run reached; quantities
    # only reported (check: false) that fall outside their range are listed apart, not in a second verdict
    out = {"case": os.path.basename(os.path.abspath(case)), "wall_seconds": wall, "coupling": timing,
           "reference": "reference.yaml" if ref else None, "results": {}, "all_checks_within_tolerance": True,
           "reported_outside_range": []}
    if continued and os.path.exists(path):
        out["wall_seconds"] = json.load(open(path))["wall_seconds"] + wall
        out["wall_seconds_last_part"] = wall
    if ref:
        rows, t, v = history(case, ref["probe"])
    else:
        rows, t, _ = history(case, "time")
        out["probes"] = probe_summary(rows)
        ref = {}
    out["interface_force_relative_difference"] = force_difference(rows)
    out["interface_moment_relative_difference"] = moment_difference(rows)
    out["iterations"] = iteration_statistics(rows)
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
        # a run that ends inside the measuring window (a short test run) measured only part of it
        entry["complete"] = bool(t) and t[-1] >= spec.get("to", -1e300)
        if not entry["complete"]:
            entry["window_end"] = spec.get("to")
        if value is not None and not entry["within"] and not entry["check"]:
            out["reported_outside_range"].append(name)
        # A checked quantity whose measuring window starts after the run's end (a short test run) cannot be
        # measured: it is reported as not reached and does not count; one the run did reach must be within.
        reached = bool(t) and t[-1] >= spec.get("from", -1e300)
        if entry["check"] and reached:
            out["all_checks_within_tolerance"] &= entry["within"]
        out["results"][name] = entry
    checks = ref.get("checks", {})
    if "momentum_balance" in checks:
        spec = checks["momentum_balance"]
        first, when, samples, structure, channel = momentum_balance(case, rows, spec)
        rel = abs(structure - channel) / abs(channel) if channel else None
        out["momentum_balance"] = {"time": when, "from": first, "samples": samples, "structure": structure,
                                   "channel": channel,
                                   "relative_difference": rel, "tolerance": spec["tolerance"],
                                   "within": rel is not None and rel <= spec["tolerance"]}
        out["all_checks_within_tolerance"] &= out["momentum_balance"]["within"]
    if "mesh_quality" in checks:
        out["mesh_quality"] = mesh_quality(case, checks["mesh_quality"])
        out["all_checks_within_tolerance"] &= out["mesh_quality"]["within"]
    if "openfoam_coefficients" in checks:
        out["openfoam_coefficients"] = openfoam_coefficients(case, rows, checks["openfoam_coefficients"])
        out["all_checks_within_tolerance"] &= out["openfoam_coefficients"]["within"]
    if "force_smoothness" in checks:
        out["force_smoothness"] = force_smoothness(rows, checks["force_smoothness"])
        out["all_checks_within_tolerance"] &= out["force_smoothness"]["within"]
    json.dump(out, open(path, "w"), indent=2)
    print(report(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
