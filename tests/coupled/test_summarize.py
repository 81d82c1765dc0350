#!/usr/bin/python3
"""summarize.py reads the coupling history of continued runs: comment lines ('#', e.g. `# restart at t = ...`
before the rows a continued run appends to coupling.csv) are skipped, so is a repeated header, and rows that a
continued run logs again (it restarted before the last logged window) replace the earlier ones; the older
layout (coupling_from_<time>.csv per continued part) gives the same history.
Usage: test_summarize.py SUMMARIZE_DIR WORK_DIR"""
import os
import shutil
import sys

sys.path.insert(0, sys.argv[1])
import summarize  # noqa: E402

HEADER = "time,iterations,converged,residual,Fx_fluid,Fy_fluid,Fz_fluid,Fx_structure,Fy_structure,Fz_structure,mid_z\n"


def quiet_summary(summarize, d):
    """summarize.main() on case d (1 s of wall time), its printed summary silenced; its exit code"""
    with open(os.devnull, "w") as null:
        saved, sys.stdout = sys.stdout, null
        sys.argv[1:] = [d, "1"]
        try:
            return summarize.main()
        finally:
            sys.stdout = saved


def row(t, iterations, z, converged=1):
    # fluid and structure forces equal except in window t = 0.3 of the first part (replaced later)
    fz_s = 2.0 if t == 0.3 and z < 0 else 1.0
    return f"{t},{iterations},{converged},1e-5,0,0,1.0,0,0,{fz_s},{z}\n"


def case(work, name, files):
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(os.path.join(d, "structure"))
    for i, (fname, text) in enumerate(files):
        path = os.path.join(d, "structure", fname)
        with open(path, "w") as f:
            f.write(text)
        os.utime(path, (1e9 + i, 1e9 + i))  # the parts in order of writing
    return d


def main():
    work = sys.argv[2]
    # first part: windows 0.1, 0.2, 0.3 (0.3 written, then the run was killed before its write time);
    # continued from t = 0.2: 0.3 and 0.4 again, with other values
    first = HEADER + row(0.1, 3, 0.01) + row(0.2, 4, 0.02) + row(0.3, 9, -1.0, converged=0)
    second = row(0.3, 2, 0.03) + row(0.4, 5, 0.04)
    appended = case(work, "appended", [("coupling.csv", first + "# restart at t = 0.2\n" + second)])
    appended_header = case(work, "appended-header",
                           [("coupling.csv", first + "# restart at t = 0.2\n" + HEADER + second)])
    split = case(work, "split", [("coupling.csv", first), ("coupling_from_0.2.csv", HEADER + second)])
    ok = True
    for d in (appended, appended_header, split):
        rows, t, v = summarize.history(d, "mid_z")
        stats = summarize.iteration_statistics(rows)
        force = summarize.force_difference(rows)
        good = (t == [0.1, 0.2, 0.3, 0.4] and v == [0.01, 0.02, 0.03, 0.04] and stats["windows"] == 4
                and stats["mean_iterations"] == (3 + 4 + 2 + 5) / 4 and stats["max_iterations"] == 5
                and stats["not_converged"] == 0 and force == 0.0)
        print(f"{os.path.basename(d)}: times {t}, values {v}, {stats}, force difference {force}:"
              f" {'ok' if good else 'WRONG'}")
        ok &= good
    # the window-to-window alternation measure against its closed forms: a force changing sign every window
    # gives 1, a linear ramp 0, a sine of n windows per period sin^2(pi/n); windows before `from` are ignored
    import math
    def rows_of(values):
        return [{"time": str(0.01 * k), "Fz_fluid": str(v)} for k, v in enumerate(values)]
    spec = {"column": "Fz_fluid", "max_alternation": 0.05}
    cases = [("alternating", [(-1) ** k * 0.3 for k in range(40)], 1.0),
             ("ramp", [1 + 0.1 * k for k in range(40)], 0.0),
             ("sine n=30", [math.sin(2 * math.pi * k / 30) for k in range(300)], math.sin(math.pi / 30) ** 2)]
    for name, values, expect in cases:
        got = summarize.force_smoothness(rows_of(values), spec)["alternation"]
        good = abs(got - expect) < 1e-2 * max(expect, 1e-3)  # the sine: end windows
        print(f"alternation of {name}: {got:.6g} (closed form {expect:.6g}): {'ok' if good else 'WRONG'}")
        ok &= good
    spiky = [1.0 + (5.0 if k == 3 else 0.0) for k in range(40)]  # a start-up spike before `from`
    late = summarize.force_smoothness(rows_of(spiky), dict(spec, **{"from": 0.05}))
    good = late["alternation"] == 0.0 and late["within"] and late["windows"] == 35
    print(f"alternation after the start-up: {late}: {'ok' if good else 'WRONG'}")
    ok &= good
    # the time average over a window: exact for a linear history (trapezoidal rule), on uneven steps too
    t = [0.0, 0.5, 1.0, 1.7, 2.0, 2.2, 3.0, 3.5]
    when, mean = summarize.measure(t, [3 * a + 1 for a in t], {"measure": "mean", "from": 0.9, "to": 3.1})
    good = when == 3.0 and abs(mean - (3 * 2.0 + 1)) < 1e-12
    print(f"time average of 3 t + 1 over 1 .. 3: {mean} at t = {when} (exact 7 at 3): {'ok' if good else 'WRONG'}")
    ok &= good
    # the momentum balance from the channel's function objects: at the last common time, or the means over the
    # last `average` seconds; hand-made .dat files whose z columns give channel = -(flux_in + flux_out) - force
    d = os.path.join(work, "momentum")
    shutil.rmtree(d, ignore_errors=True)
    times = [0.2 * k for k in range(11)]
    noise = [0.0, 0.01, -0.01, 0.02, -0.02, 0.01, -0.01, 0.02, -0.02, 0.01, -0.01]  # zero mean over any pair
    for folder, name, line in (("inletOutletForce", "force.dat", lambda t: f"{t} (0 0 {-t}) (0 0 0)"),
                               ("inletMomentum", "surfaceFieldValue.dat", lambda t: f"{t} (0 0 1)"),
                               ("outletMomentum", "surfaceFieldValue.dat", lambda t: f"{t} (0 0 -2)")):
        os.makedirs(os.path.join(d, "postProcessing", folder, "0"))
        with open(os.path.join(d, "postProcessing", folder, "0", name), "w") as f:
            f.write("# Time value\n" + "".join(line(t) + "\n" for t in times))
    rows = [{"time": str(t), "Fz_structure": str(1 + t + n)} for t, n in zip(times, noise)]  # channel 1 + t
    spec = {"force": "inletOutletForce", "flux": ["inletMomentum", "outletMomentum"], "component": "z"}
    last = summarize.momentum_balance(d, rows, spec)
    mean = summarize.momentum_balance(d, rows, dict(spec, average=0.4))
    good = (last[1:3] == (2.0, 1) and abs(last[3] - 2.99) < 1e-12 and abs(last[4] - 3.0) < 1e-12
            and mean[0] == times[8] and mean[2] == 3 and abs(mean[4] - 2.8) < 1e-12
            and abs(mean[3] - (2.8 + (-0.02 + 0.01 - 0.01) / 3)) < 1e-12)
    print(f"momentum balance at the end {last}, mean over the last 0.4 s {mean}: {'ok' if good else 'WRONG'}")
    ok &= good
    # a checked quantity counts only once the run has reached its measuring window: a short run (the test's
    # END) reports it as not reached, a run that reached it must be within the accepted range
    import json
    for end, value, expect in ((0.4, 0.5, True), (1.0, 0.5, False), (1.0, 2.0, True)):
        d = case(work, f"window-{end}-{value}", [("coupling.csv", HEADER + "".join(
            row(0.1 * k, 2, value if 0.1 * k > 0.55 else 0.0) for k in range(1, int(round(end * 10)) + 1)))])
        with open(os.path.join(d, "structure", "timing.json"), "w") as f:
            json.dump({}, f)
        with open(os.path.join(d, "reference.yaml"), "w") as f:
            f.write("probe: mid_z\nquantities:\n  settled: {measure: mean, from: 0.6, to: 1.0, tolerance: 0.1, "
                    "check: true, published: [{source: test, value: 2.0}]}\n")
        quiet_summary(summarize, d)
        got = json.load(open(os.path.join(d, "summary.json")))["all_checks_within_tolerance"]
        good = got == expect
        print(f"run to {end} s, settled value {value}: checks pass {got} (expected {expect}): {'ok' if good else 'WRONG'}")
        ok &= good
    # a quantity only reported (check: false) outside its range is listed apart and does not make a verdict
    # false beside a passing one
    d = case(work, "reported", [("coupling.csv", HEADER + "".join(row(0.1 * k, 2, 2.0) for k in range(1, 11)))])
    with open(os.path.join(d, "structure", "timing.json"), "w") as f:
        json.dump({}, f)
    with open(os.path.join(d, "reference.yaml"), "w") as f:
        f.write("probe: mid_z\nquantities:\n  settled: {measure: final, tolerance: 0.1, check: true, "
                "published: [{source: test, value: 2.0}]}\n  later: {measure: final, tolerance: 0.1, "
                "published: [{source: a longer run, value: 5.0}]}\n")
    quiet_summary(summarize, d)
    got = json.load(open(os.path.join(d, "summary.json")))
    good = (got["all_checks_within_tolerance"] is True and got["reported_outside_range"] == ["later"]
            and "all_within_tolerance" not in got)
    print(f"a reported quantity outside its range: checks {got['all_checks_within_tolerance']}, listed "
          f"{got['reported_outside_range']}: {'ok' if good else 'WRONG'}")
    ok &= good
    # a case of one's own has no reference.yaml: the summary still works, with every probe's final value
    d = case(work, "own", [("coupling.csv", HEADER + "".join(row(0.1 * k, 2, 0.1 * k) for k in range(1, 11)))])
    with open(os.path.join(d, "structure", "timing.json"), "w") as f:
        json.dump({}, f)
    rc = quiet_summary(summarize, d)
    got = json.load(open(os.path.join(d, "summary.json")))
    p = got.get("probes", {}).get("mid_z", {})
    good = (rc == 0 and got["reference"] is None and abs(p.get("final", 0) - 1.0) < 1e-12
            and abs(p.get("min", 0) - 0.1) < 1e-12 and got["iterations"]["windows"] == 10)
    print(f"no reference.yaml: exit {rc}, probes {got.get('probes')}: {'ok' if good else 'WRONG'}")
    ok &= good
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
