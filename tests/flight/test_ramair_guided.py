#!/usr/bin/python3
"""ctest flight.ramair-guided: cases/flight/ramair-kt-guided (the main job's coefficients in flight) by its Allrun.

Checks:
1. The Allrun flies the case and plots it: summary.json, summary.md, trajectory.csv/.vtk, monte_carlo.csv and the
   PNGs (3D path, ground track, history, landing scatter).
2. Guidance: homing through the waypoint with the glide path held by the incidence lands within R_CALM of the
   target in calm air and within R_WIND in the 3 m/s cross wind of the CIMNE paper's test (radii and their
   reasons in docs/FLIGHT.md "Guidance"); the glide-slope loop moved the incidence (it is used); without the
   glide-slope loop the same flight misses by more than R_CALM (the loop is what lands it there).
3. The Monte Carlo: the same seed gives the same monte_carlo.csv byte for byte, another seed another one; the
   statistics in summary.json are those of the CSV's rows (recomputed here); the drawn winds lie in their range
   and their mean speed is the range's middle within 4 standard errors; without wind and release spread every
   run lands where the nominal flight lands (1e-6 m) and the spread is 0.
4. A misspelt glide control, gain key or guidance key, a bad turn brake, no runs, a reversed wind range and a
   negative spread end with exit 2 naming the file, line and key.
Usage: test_ramair_guided.py FSI WORK_DIR
"""
import csv
import json
import math
import os
import shutil
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
CASE = os.path.join(ROOT, "cases", "flight", "ramair-kt-guided")
# Calm air: the glide-slope loop corrects the path down to the ground (10 Hz): 5 m is a third of a second of
# flight. Cross wind 3 m/s: crabbing into it costs 1 - sqrt(1 - (3/14.4)^2) = 2.2 % of the reach over the
# ground, 36 m of the 1.65 km that the shallowest incidence reaches from 400 m, which the glide-slope loop cannot
# win back when the path's margin is smaller: 40 m.
R_CALM, R_WIND = 5.0, 40.0
RUNS = 20


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def allrun(fsi, out, *sets, plots=False):
    """The case's Allrun (with its plots) or, for the variants, its `fsi fly` alone."""
    args = ["--set", f"monte_carlo.runs={RUNS}"] + [a for s in sets for a in ("--set", s)]
    if plots:
        env = dict(os.environ, FSI=fsi, FSI_FLY_ARGS=" ".join(args))
        r = subprocess.run([os.path.join(CASE, "Allrun"), out], capture_output=True, text=True, env=env)
    else:
        r = subprocess.run([fsi, "fly", os.path.join(CASE, "ramair-kt.flight.yaml"), "--out", out, "-q"] + args,
                           capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{sets}: exit {r.returncode}: {r.stdout} {r.stderr}")
    return json.load(open(os.path.join(out, "summary.json")))


def rows(path):
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(path))]


def main(fsi, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    calm = os.path.join(work, "calm")
    s = allrun(fsi, calm, plots=True)
    for f in ("summary.md", "trajectory.csv", "trajectory.vtk", "monte_carlo.csv"):
        if not os.path.isfile(os.path.join(calm, f)):
            fail(f"no {f}")
    for png in ("flight_path.png", "ground_track.png", "flight_history.png", "landing_scatter.png"):
        if not os.path.getsize(os.path.join(calm, "plots", png)) > 10000:
            fail(f"no {png}")
    traj = rows(os.path.join(calm, "trajectory.csv"))
    inc = [r["incidence_deg"] for r in traj]
    print(f"calm: lands {s['miss_distance_m']:.1f} m from the target (allowed {R_CALM}); incidence "
          f"{min(inc):.2f} ... {max(inc):.2f} deg")
    if not (s["landed"] and s["waypoint_reached"] == 1 and s["miss_distance_m"] <= R_CALM):
        fail(f"calm: landed {s['landed']}, waypoint {s['waypoint_reached']}, miss {s['miss_distance_m']:.1f} m")
    if not max(inc) - min(inc) > 1.0:
        fail("the glide-slope loop did not move the incidence")
    w = allrun(fsi, os.path.join(work, "wind"), "wind.steady=[0,-3,0]", "monte_carlo.runs=1")
    print(f"3 m/s cross wind: lands {w['miss_distance_m']:.1f} m from the target (allowed {R_WIND})")
    if not (w["landed"] and w["miss_distance_m"] <= R_WIND):
        fail(f"cross wind: miss {w['miss_distance_m']:.1f} m")
    off = allrun(fsi, os.path.join(work, "no-glide-slope"), "guidance.glide_slope.min=-3.651",
                 "guidance.glide_slope.max=-3.649", "guidance.glide_slope.trim=-3.65", "monte_carlo.runs=1")
    print(f"glide-slope loop held at the middle incidence: lands {off['miss_distance_m']:.1f} m from the target")
    if not off["miss_distance_m"] > R_CALM:
        fail(f"without the glide-slope loop the flight still lands within {R_CALM} m: the check cannot fail")
    # 3. The Monte Carlo.
    again = os.path.join(work, "again")
    allrun(fsi, again)
    text = open(os.path.join(calm, "monte_carlo.csv")).read()
    if open(os.path.join(again, "monte_carlo.csv")).read() != text:
        fail("the same seed gave another monte_carlo.csv")
    other = os.path.join(work, "seed2")
    allrun(fsi, other, "monte_carlo.seed=2")
    if open(os.path.join(other, "monte_carlo.csv")).read() == text:
        fail("seed 2 gave the same monte_carlo.csv as seed 1")
    mc, runs = s["monte_carlo"], rows(os.path.join(calm, "monte_carlo.csv"))
    if len(runs) != RUNS or mc["runs"] != RUNS or mc["landed"] != sum(r["landed"] for r in runs):
        fail(f"{len(runs)} rows, summary {mc['runs']} runs")
    north = [r["landing_north_m"] for r in runs]
    east = [r["landing_east_m"] for r in runs]
    miss = [r["miss_m"] for r in runs]
    expect = {"mean_landing_ne_m": [statistics.mean(north), statistics.mean(east)],
              "sd_ne_m": [statistics.stdev(north), statistics.stdev(east)],
              "miss_median_m": statistics.median(miss), "miss_max_m": max(miss), "miss_mean_m": statistics.mean(miss)}
    for key, value in expect.items():
        got = mc[key] if isinstance(value, list) else [mc[key]]
        ref = value if isinstance(value, list) else [value]
        if any(abs(g - e) > 1e-4 * (1 + abs(e)) for g, e in zip(got, ref)):
            fail(f"monte_carlo.{key}: summary {got}, from the CSV {ref}")
    for r in runs:
        if not (0 <= r["wind_speed_m_s"] <= 3 and 0 <= r["wind_from_deg"] <= 360):
            fail(f"run {r['run']:.0f}: wind {r['wind_speed_m_s']} m/s from {r['wind_from_deg']} deg out of range")
        a = math.radians(r["wind_from_deg"])
        if abs(r["wind_north_m_s"] + r["wind_speed_m_s"] * math.cos(a)) > 1e-5:
            fail(f"run {r['run']:.0f}: the wind does not blow from {r['wind_from_deg']} deg")
    speed = statistics.mean(r["wind_speed_m_s"] for r in runs)
    if abs(speed - 1.5) > 4 * 3 / math.sqrt(12 * RUNS):
        fail(f"mean drawn wind {speed:.3f} m/s, uniform on [0, 3] gives 1.5 +- {3 / math.sqrt(12 * RUNS):.3f}")
    print(f"Monte Carlo ({RUNS} runs): mean landing {mc['mean_landing_ne_m']}, sd {mc['sd_ne_m']}, miss median "
          f"{mc['miss_median_m']:.1f} m, 95 % {mc['miss_95_m']:.1f} m, largest {mc['miss_max_m']:.1f} m")
    still = os.path.join(work, "still")
    z = allrun(fsi, still, "monte_carlo.runs=3", "monte_carlo.wind_speed=[0,0]", "monte_carlo.release_sd=[0,0,0]")
    end = z["end_point_ned_m"]
    for r in rows(os.path.join(still, "monte_carlo.csv")):
        if math.hypot(r["landing_north_m"] - end[0], r["landing_east_m"] - end[1]) > 1e-6:
            fail(f"no spread: run {r['run']:.0f} lands at ({r['landing_north_m']}, {r['landing_east_m']}), nominal {end}")
    if max(z["monte_carlo"]["sd_ne_m"]) > 1e-6:
        fail(f"no spread: standard deviations {z['monte_carlo']['sd_ne_m']}")
    # 4. Bad guidance and Monte Carlo input: exit 2, the file, line and key.
    text = open(os.path.join(CASE, "ramair-kt.flight.yaml")).read()
    bad = os.path.join(work, "bad.yaml")
    for old, new, expect in (("    control: incidence", "    control: incidance", "incidance"),
                             ("gains: {kp: 2.0,", "gains: {kq: 2.0,", "kq"),
                             ("  yaw_rate_gains: {kp: 5,", "  yaw_rate_gain: {kp: 5,", "yaw_rate_gain"),
                             ("  right_turn_brake: right", "  right_turn_brake: up", "right_turn_brake"),
                             ("  runs: 50", "  runs: 0", "runs"),
                             ("  wind_speed: [0, 3]", "  wind_speed: [3, 0]", "wind_speed"),
                             ("  release_sd: [30, 30, 10]", "  release_sd: [30, -30, 10]", "release_sd")):
        if old not in text:
            fail(f"the case file has no {old!r}")
        open(bad, "w").write(text.replace(old, new))
        r = subprocess.run([fsi, "fly", bad, "--out", os.path.join(work, "bad")], capture_output=True, text=True)
        if r.returncode != 2 or "bad.yaml:" not in r.stderr or expect not in r.stderr:
            fail(f"{new.strip()!r}: exit {r.returncode}, {r.stderr.strip()!r}")
    print("flight.ramair-guided: passed")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
