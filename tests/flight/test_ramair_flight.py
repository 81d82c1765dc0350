#!/usr/bin/python3
"""ctest flight.ramair-table: the coupled ram-air wing's flight table (cases/flight/ramair_flight_table.py) flown.

Checks, each against a number the flight did not make:
1. The committed flight file and flight_table.json are what the script writes from docs/data (--check).
2. The steady glide: flown at the incidence of each rigging point, the free system settles into that coupled
   point's trim: the angle of attack of its centre section, tan(gamma) = CD_system / CL_system, the coupled
   run's glide angle (CL_system: the canopy's lift and the lines' force normal to the flow), and the airspeed sqrt(2 W / (rho S C_R)) (15 m/s for the main job's point, whose weight W is the trim's
   resultant). Tolerance: 1e-3 relative (0.02 deg for the angle of attack), from the model: the table's rows are
   the trim points themselves (no interpolation error at a trim), and the slowest mode, the phugoid, decays as
   exp(-(CD/CL) g t / V) (Lanchester's damping): after 60 s of glide 1e-5 of the start's error. The other
   points' CD_system differs from the coupled one by their lines' drag spread (the table uses the main job's,
   <= 0.0007 in CD): their tan(gamma) tolerance is that spread / CL.
3. A constant right brake turns the system the way, and at the order of the rate, that the coupled run's loads
   give in the free system's steady turn (flight_table.json's brake.*.turn_rate_rad_s: roll and yaw about the
   mass centre balanced by the canopy point's sideslip, with the sideslip derivatives of the sideslip runs, and
   the turn's rates against the table's damping: ramair_flight_table.py's lateral_balance); within 10 %: the
   balance leaves out the bank's share of the body rates (cos(bank) - 1, the bank V psi'/g about 4 deg: 0.3 %)
   and the sideslip's second-order terms (beta about 1.5 deg). The direction is the sign of the yaw left when the sideslip balances the roll
   (brake.*.yaw_at_roll_balance_Nm): with the end of the held windows' range that yaws most to the right it is
   a right turn (docs/FLIGHT.md).
4. The steady turn's radius against the steady-turn relation for the coefficients used: in a steady turn the
   horizontal aerodynamic force F_h (canopy, lines, payload; trajectory.csv's aero_force_*) turns the impulse
   (m + A_x) V_h of the system: R = (m + A_x) V_h^2 / F_h (1 %: the impulse's parts off the forward axis, A_z V
   sin(alpha) sin(pitch), are below 0.2 %; the rest is what remains of the transient).
Usage: test_ramair_flight.py FSI WORK_DIR
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
CASE = os.path.join(ROOT, "cases", "flight", "ramair-kt-guided")


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def fly(fsi, doc, work, name):
    path = os.path.join(work, name + ".yaml")
    with open(path, "w") as f:
        yaml.safe_dump(doc, f)
    out = os.path.join(work, name)
    r = subprocess.run([fsi, "fly", path, "--out", out, "-q"], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{name}: fsi fly exited {r.returncode}: {r.stderr}")
    return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(open(os.path.join(out, "trajectory.csv")))]


def main(fsi, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    r = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "cases", "flight", "ramair_flight_table.py"), "--check"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        fail("the committed table is stale: " + r.stdout + r.stderr)
    table = json.load(open(os.path.join(CASE, "flight_table.json")))
    base = yaml.safe_load(open(os.path.join(CASE, "ramair-kt.flight.yaml")))
    del base["guidance"]
    base["time"] = {"end": 80, "step": 0.01, "output_interval": 0.1, "stop_at_ground": False}
    sysm = base["system"]
    weight = sysm["mass"] * 9.80665
    S, rho = base["aerodynamics"]["area"], 1.225
    cd_lines = sysm["line_drag_area"] / S
    # 2. The steady glide at each rigging point.
    for p in table["points"]:
        doc = dict(base, brakes={"time": [0, 1], "left": [0, 0], "right": [0, 0],
                                 "incidence": [p["incidence_deg"]] * 2})
        rows = fly(fsi, doc, work, f"rig{p['rigging_angle_deg']}")
        last = [x for x in rows if x["time_s"] >= 70]
        mean = {k: sum(x[k] for x in last) / len(last) for k in last[0]}
        tan_gamma = mean["descent_rate_m_s"] / mean["ground_speed_m_s"]
        gamma = math.degrees(math.atan(tan_gamma))
        tan_ref = p["CD_system"] / p["CL_system"]  # = tan(the coupled glide_angle_deg)
        c_r = math.hypot(p["CL_system"], p["CD_system"])
        v_ref = math.sqrt(2 * weight / (rho * S * c_r))
        tol_tan = 1e-3 + abs(p["CD"] + cd_lines - p["CD_system"]) / p["CD_system"]
        print(f"rigging {p['rigging_angle_deg']} deg (incidence {p['incidence_deg']:+.2f}): alpha {mean['alpha_deg']:.4f} "
              f"(coupled {p['alpha_centre_deg']:.4f}), glide {gamma:.4f} deg (coupled {p['glide_angle_deg']:.4f}), "
              f"airspeed {mean['airspeed_m_s']:.4f} m/s (sqrt(2W/(rho S C_R)) {v_ref:.4f})")
        if abs(mean["alpha_deg"] - p["alpha_centre_deg"]) > 0.02:
            fail(f"rigging {p['rigging_angle_deg']}: trim alpha {mean['alpha_deg']:.4f}, coupled {p['alpha_centre_deg']:.4f}")
        if abs(math.tan(math.radians(p["glide_angle_deg"])) / tan_ref - 1) > 1e-9:
            fail(f"rigging {p['rigging_angle_deg']}: the table's CL_system is not the coupled glide's")
        if abs(tan_gamma / tan_ref - 1) > tol_tan:
            fail(f"rigging {p['rigging_angle_deg']}: tan(gamma) {tan_gamma:.6f}, coupled CD_system/CL_system "
                 f"{tan_ref:.6f} (tolerance {tol_tan:.2g})")
        if abs(mean["airspeed_m_s"] / v_ref - 1) > 1e-3 + 0.5 * tol_tan:
            fail(f"rigging {p['rigging_angle_deg']}: airspeed {mean['airspeed_m_s']:.5f}, steady glide {v_ref:.5f}")
        if p["run"] == "s1-nobend" and abs(mean["airspeed_m_s"] - 15.0) > 0.015:
            fail(f"the main job's point: airspeed {mean['airspeed_m_s']:.4f}, the coupled run's 15 m/s")
    # 3. and 4. A constant right brake, with the coupled loads' held mean (the table's) and with the end of their
    # range that turns most to the right.
    for name in ("mean", "right_end"):
        bset = table["brake"][name]
        doc = dict(base, brakes={"time": [0, 10, 12], "left": [0, 0, 0], "right": [0, 0, 1]})
        doc["aerodynamics"] = dict(base["aerodynamics"], **{k: bset[k] for k in (
            "CY_differential_brake", "Cl_differential_brake", "Cn_differential_brake")})
        doc["time"] = dict(base["time"], end=400)
        rows = fly(fsi, doc, work, f"right-brake-{name}")
        turn = [x for x in rows if x["time_s"] >= 200]
        yaw = [math.radians(x["yaw_deg"]) for x in turn]
        unwrapped = [yaw[0]]
        for a in yaw[1:]:
            unwrapped.append(unwrapped[-1] + (a - unwrapped[-1] + math.pi) % (2 * math.pi) - math.pi)
        rate = (unwrapped[-1] - unwrapped[0]) / (turn[-1]["time_s"] - turn[0]["time_s"])
        ref = bset["turn_rate_rad_s"]
        print(f"right brake ({name}: yaw {bset['yaw_moment_Nm']} N m, roll {bset['roll_moment_Nm']} N m about the "
              f"anchor): turn rate {rate:+.4f} rad/s ({math.degrees(rate):+.2f} deg/s); the loads' steady balance "
              f"{ref:+.4f} rad/s")
        if not (rate * ref > 0 and abs(rate - ref) <= 0.1 * abs(ref)):
            fail(f"{name}: turn rate {rate:+.4f} rad/s, the coupled loads' balance {ref:+.4f} (sign, 10 %)")
        if rate * bset["yaw_at_roll_balance_Nm"] <= 0:
            fail(f"{name}: turn rate {rate:+.4f} rad/s against the yaw left at the roll balance "
                 f"{bset['yaw_at_roll_balance_Nm']:+.3f} N m (the direction)")
        north = [x["north_m"] for x in turn]
        east = [x["east_m"] for x in turn]
        if abs(unwrapped[-1] - unwrapped[0]) < 2 * math.pi:
            fail(f"{name}: less than one circle between 200 and 400 s")
        radius = 0.25 * (max(north) - min(north) + max(east) - min(east))
        vh = sum(x["ground_speed_m_s"] for x in turn) / len(turn)
        fh = sum(math.hypot(x["aero_force_north_N"], x["aero_force_east_N"]) for x in turn) / len(turn)
        m_eff = sysm["mass"] + sysm["added_mass"][0]
        r_rel = m_eff * vh ** 2 / fh
        print(f"  steady turn: track radius {radius:.2f} m, (m + A_x) V_h^2 / F_h = {r_rel:.2f} m")
        if abs(radius / r_rel - 1) > 0.01:
            fail(f"{name}: turn radius {radius:.2f} m against the steady-turn relation {r_rel:.2f} m")
    print("flight.ramair-table: passed")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
