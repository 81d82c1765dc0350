#!/usr/bin/python3
"""The flight table of the coupled ram-air wing: from the coupled runs' numbers to a flight file for `fsi fly`.

Reads docs/data/ramair_polar.json (the coupled canopy at four rigging angles: rung 4 of docs/AERODYNAMICS.md),
docs/data/ramair_convergence.json (rung 3: the resolution error bar of the main job's trim) and
docs/data/ramair_brake.json (the right-brake run's loads about the anchor, with their source runs) and
docs/data/ramair_sideslip.json (the trimmed canopy in sideslip: the sideslip derivatives) and writes

  cases/flight/ramair-kt-guided/ramair-kt.flight.yaml   the flight file (system, table, guidance), and
  cases/flight/ramair-kt-guided/flight_table.json       every point the table is built from, its uncertainty,
                                                        the system's derived numbers and the references the
                                                        tests check the flight against.

How (docs/FLIGHT.md, "The coupled ram-air wing in flight"):
- The table's angle of attack is the deformed centre section's (body x = the centre chord). Its rows are the
  four rigging points: alpha_centre, CL, CD of the canopy and Cm about the centre quarter chord, on the design
  projected area 2.948 m^2 and the root chord. The lines' drag (CD_system - CD, 0.0525-0.0529 over the four
  points) is the flight file's line_drag_area = the main job's CD_lines * S.
- The system is the anchored wing set free: its weight is the coupled trim's resultant at 15 m/s
  (W = q S sqrt(CL^2 + CD_system^2)), the payload hangs at the confluence point 3 m below the canopy (line_length
  1.0 x span puts it at the arc's centre, R = 3 m), and the mass centre is placed on the trim's line of action
  (the anchored wing trims where the resultant passes through the confluence point; the free system trims where
  it passes through its mass centre), so the free glide's trim angle is the coupled one.
- Each rigging point gives the direction mu of the canopy point from the mass centre at which that point trims;
  the flight file's `incidence` is mu - mu(13 deg), the glide-slope loop's control.
- The brake: the right toggle's 0.25 m is brake 1. The held yaw and roll moments about the anchor and the side
  force are moved to the canopy point and written in body axes: CY, Cl, Cn per unit differential brake.
- The sideslip derivatives: docs/data/ramair_sideslip.json (studies/ramair/ramair_sideslip.py: the main job's
  trimmed canopy as a rigid wing at sideslip +-5 deg and 0 on the main job's mesh level and wall treatment): the
  force and moment about the case's CofR moved to the canopy point and written in the flight model's body and
  wind axes (flight/FlightSystem.cpp: side force along motion x lift), on q S and q S b as the brake's; the
  slope of the +5/-5 pair. The strip-theory estimates they replace are kept beside them (flight_table.json).
- Not from the coupled runs (stated estimates): the apparent masses (Lissaman & Brown 1993), the rate
  derivatives (strip theory, Helmbold's lift slope; the profile drag's yaw damping), the canopy's mass and
  inertias.
Usage: ramair_flight_table.py [--check]   (--check: exit 1 when the committed files differ from what it writes)
       ramair_flight_table.py --sideslip FILE   (the derivatives and the brake's turn from another sideslip JSON)
"""
import json
import math
import os
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
CASE = os.path.join(ROOT, "cases", "flight", "ramair-kt-guided")
SPEED, RHO, G = 15.0, 1.225, 9.80665
AREA, CHORD = 2.948, 1.0005      # design projected area [m^2], centre chord [m] (docs/RAMAIR.md, forceCoeffs)
SPAN = 2.980                      # projected span of the design canopy [m] (docs/RAMAIR.md "reference areas")
ARC_RADIUS, ARC_SPAN = 3.0, 3.0   # structure.yaml: arc_radius 3, span 3 (along the arc)
LINE_LENGTH = 3.0                 # canopy point to the confluence point: line_length 1.0 x span, at the arc's centre
THICKNESS = 0.15                  # NACA 4415
CANOPY_MASS = 0.9                 # fabric 7.1 m^2 x 40 g/m^2 = 0.29 kg, lines about 0.27 kg, enclosed air 0.37 kg
PAYLOAD_BOX = 0.4                 # the payload as a cube of this side [m] (its own inertia)
MAIN_RIG = 13


def load(name):
    with open(os.path.join(ROOT, "docs", "data", name)) as f:
        return json.load(f)


def apparent_masses(rho, b, c, t, arc_height):
    """Lissaman & Brown (1993) for an arched canopy: span b, chord c, thickness t, arc height a."""
    ar, ts, As = b / c, t / c, arc_height / b
    k = ar / (1 + ar)
    mass = [0.666 * rho * (1 + 8 / 3 * As ** 2) * t ** 2 * b,
            0.267 * rho * (t ** 2 + 2 * arc_height ** 2 * (1 - ts ** 2)) * c,
            0.785 * rho * math.sqrt(1 + 2 * As ** 2 * (1 - ts ** 2)) * k * c ** 2 * b]
    inertia = [0.055 * rho * k * c ** 2 * b ** 3,
               0.0308 * rho * k * (1 + math.pi / 6 * (1 + ar) * ar * As ** 2 * ts ** 2) * c ** 4 * b,
               0.055 * rho * (1 + 8 * As ** 2) * t ** 2 * b ** 3]
    return mass, inertia


def trim_direction(alpha, cl, cd_sys, cm, arm):
    """mu [rad]: the canopy point at arm (-sin mu, 0, -cos mu) from the mass centre (body axes) at which the
    moment about the mass centre vanishes in the steady glide at alpha: q S c Cm - arm |F| sin(mu + phi) = 0,
    phi = alpha - gamma the lean of the resultant ahead of the body's -z axis."""
    phi = alpha - math.atan2(cd_sys, cl)
    return math.asin(CHORD * cm / (arm * math.hypot(cl, cd_sys))) - phi


def lateral_balance(roll_c, yaw_c, side_c, point, coef, qS, theta):
    """The free system's steady turn from loads (roll_c, yaw_c [N m] about the canopy point, side_c [N]; body
    axes) at the canopy point `point` (from the mass centre), as the flight model forms the loads
    (flight/FlightSystem.cpp): the roll and yaw about the mass centre vanish at the sideslip beta of the canopy
    point and the turn rate psi' (body rates psi' (-sin theta, 0, cos theta): a level turn at pitch theta, the
    bank's part left out). The sideslip's side force at the point per rad, Y_b = q S (CY_beta - CD) - q A_lines
    (the side force, and the drag of canopy and lines along the air's sideways motion), rolls by -z Y_b and yaws
    by x Y_b about the mass centre; its own roll and yaw q S b Cl_beta, Cn_beta; the rates' q S b Cl_p p b/2V and
    Cn_r r b/2V. The inertia's gyroscopic part and the apparent mass (munk_moment false) add no roll or yaw here.
    Returns (beta [rad], psi' [rad/s], the yaw left at the roll balance without rates [N m])."""
    cy_b, cl_b, cn_b, cl_p, cn_r, cd, line_area = coef
    q = qS / AREA
    y_b = qS * (cy_b - cd) - q * line_area
    roll_g = roll_c - point[2] * side_c      # r x F: the side force at (x, 0, z) rolls by -z Y, yaws by x Y
    yaw_g = yaw_c + point[0] * side_c
    a11, a21 = qS * SPAN * cl_b - point[2] * y_b, qS * SPAN * cn_b + point[0] * y_b
    k = qS * SPAN * SPAN / (2 * SPEED)
    a12, a22 = k * cl_p * -math.sin(theta), k * cn_r * math.cos(theta)
    det = a11 * a22 - a12 * a21
    beta = (-roll_g * a22 + yaw_g * a12) / det
    rate = (-yaw_g * a11 + roll_g * a21) / det
    return beta, rate, yaw_g - roll_g * a21 / a11


def sideslip_derivatives(data, anchor_to_canopy, xb, zb, qS):
    """CY_beta, Cl_beta, Cn_beta from the sideslip runs (docs/data/ramair_sideslip.json), as the flight model
    uses them (flight/FlightSystem.cpp): beta = asin of the y part of the canopy's motion through the air in body
    axes; CY along the side axis motion x lift (lift normal to the motion and to body y) on q S; Cl, Cn the
    body-axis roll and yaw about the canopy point on q S b. Each run's force F and moment M about CofR (the case's
    axes: x downstream, y right, z up) are moved to the canopy point, the anchor (confluence point) plus the
    canopy point's offset from it (anchor_to_canopy, wind axes: x forward, z down). The slope is that of the
    +b/-b pair; the pair's symmetric parts (zero for a mirror-symmetric wing in mirrored flow) measure how far
    the runs' unsteadiness and the mesh's asymmetry reach."""
    def wind(v):  # the case's axes -> wind axes (x forward, y right, z down)
        return (-v[0], v[1], -v[2])

    def body(v):
        return (v[0] * xb[0] + v[2] * xb[2], v[1], v[0] * zb[0] + v[2] * zb[2])

    def cross(a, b):
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])

    def unit(v):
        n = math.sqrt(sum(x * x for x in v))
        return [x / n for x in v]

    points = []
    for r in data["rows"]:
        anchor = r["anchor_m"]
        point = [anchor[0] - anchor_to_canopy[0], anchor[1] + anchor_to_canopy[1], anchor[2] - anchor_to_canopy[2]]
        arm = [c - p for c, p in zip(r["CofR"], point)]
        m_c = [m + x for m, x in zip(r["moment_Nm"], cross(arm, r["force_N"]))]
        motion = unit(body(wind([-v for v in r["flow_dir"]])))
        lift = unit(cross((0.0, 1.0, 0.0), motion))
        side = cross(motion, lift)
        f_b, m_b = body(wind(r["force_N"])), body(wind(m_c))
        beta = math.asin(motion[1])
        points.append({"sideslip_setting_deg": r["sideslip_deg"], "beta_deg": math.degrees(beta),
                       "CY": sum(f * s for f, s in zip(f_b, side)) / qS, "Cl": m_b[0] / (qS * SPAN),
                       "Cn": m_b[2] / (qS * SPAN), "CL_own_area": r["CL"], "CD_own_area": r["CD"],
                       "range_second_half": r["range_second_half"]})
    by = {round(p["sideslip_setting_deg"], 6): p for p in points}
    pos = max(b for b in by if b > 0)
    neg, plus = by[-pos], by[pos]
    db = math.radians(plus["beta_deg"] - neg["beta_deg"])
    out = {k + "_beta": (plus[k] - neg[k]) / db for k in ("CY", "Cl", "Cn")}
    out["symmetric_part"] = {k: 0.5 * (plus[k] + neg[k]) for k in ("CY", "Cl", "Cn")}
    out["antisymmetric_part"] = {k: 0.5 * (plus[k] - neg[k]) for k in ("CY", "Cl", "Cn")}
    if 0.0 in by:
        out["at_zero"] = {k: by[0.0][k] for k in ("CY", "Cl", "Cn")}
    out.update({"points": points, "command": data["command"], "pair_deg": [-pos, pos],
                "is": "per rad; CY on q S (S = the table's area), Cl and Cn body-axis roll and yaw about the canopy "
                      "point on q S b; the slope of the +/- pair; symmetric_part: half the pair's sum (zero for a "
                      "symmetric flow: what the mesh's asymmetry and the runs' unsteadiness leave)"})
    return out


def build():
    polar = load("ramair_polar.json")
    conv = load("ramair_convergence.json")
    brake = load("ramair_brake.json")
    rows = sorted(polar["rows"], key=lambda r: r["alpha_centre_deg"])
    for r in rows:  # the lift of canopy and lines: the lines' force has a part normal to the flow (downwards)
        r["CL_system"] = r["CD_system"] * r["L_over_D_system"]
    main = next(r for r in rows if r.get("main_job"))
    q = 0.5 * RHO * SPEED ** 2
    cd_lines = main["CD_system"] - main["CD"]
    weight = q * AREA * math.hypot(main["CL_system"], main["CD_system"])
    mass = weight / G
    payload = mass - CANOPY_MASS
    arm = LINE_LENGTH * payload / mass          # canopy point to mass centre
    below = LINE_LENGTH - arm                    # mass centre to payload (the confluence point)
    mus = {r["rigging_angle_deg"]: trim_direction(math.radians(r["alpha_centre_deg"]), r["CL_system"],
                                                  r["CD"] + cd_lines, r["Cm"], arm) for r in rows}
    mu0 = mus[MAIN_RIG]
    canopy = [-arm * math.sin(mu0), 0.0, -arm * math.cos(mu0)]
    payload_pt = [below * math.sin(mu0), 0.0, below * math.cos(mu0)]
    # Apparent mass at the canopy, moved to the mass centre: the diagonal plus the parallel-axis terms of the
    # masses that a roll or pitch about the mass centre sets moving (the cross terms are not modelled).
    half = ARC_SPAN / (2 * ARC_RADIUS)
    arc_height = ARC_RADIUS * (1 - math.cos(half))
    am, ai = apparent_masses(RHO, SPAN, CHORD, THICKNESS * CHORD, arc_height)
    added_inertia = [ai[0] + am[1] * arm ** 2, ai[1] + am[0] * arm ** 2, ai[2]]
    box = payload * PAYLOAD_BOX ** 2 / 6
    inertia = [CANOPY_MASS * (arm ** 2 + SPAN ** 2 / 12) + payload * below ** 2 + box,
               CANOPY_MASS * (arm ** 2 + CHORD ** 2 / 12) + payload * below ** 2 + box,
               CANOPY_MASS * (SPAN ** 2 + CHORD ** 2) / 12 + box]
    # Rate and sideslip derivatives (estimates, strip theory): Helmbold's lift slope for the loaded aspect
    # ratio; the arc's sections see beta sin(theta): CY_beta = -a (t0 - sin t0 cos t0) / (2 t0), acting at the
    # sin^2-weighted depth of the arc below the canopy point; roll damping -a/6; yaw damping of the profile drag
    # -CD/3 (per b/2V rates).
    ar = SPAN ** 2 / AREA
    slope = 2 * math.pi * ar / (2 + math.sqrt(ar ** 2 + 4))
    cy_beta = -slope * (half - math.sin(half) * math.cos(half)) / (2 * half)
    depth = ARC_RADIUS * (1 - (math.sin(half) ** 3 / 3) / ((half - math.sin(half) * math.cos(half)) / 2))
    cl_beta = -depth * cy_beta / SPAN
    cl_p, cn_r = -slope / 6, -main["CD"] / 3
    # The brake: held loads about the anchor (x downstream, y right, z up) -> wind axes (x forward, z down) ->
    # about the canopy point -> body axes (rotated by the trim's alpha). Three sets: the held windows' mean (the
    # table's), and the two ends of their range that turn the free system most to the right and to the left.
    rb = brake["right_brake"]
    held, before = rb["held"], rb["before"]
    a0 = math.radians(main["alpha_centre_deg"])
    xb, zb = (math.cos(a0), 0, -math.sin(a0)), (math.sin(a0), 0, math.cos(a0))  # body axes in wind axes

    def to_wind(v):
        return (v[0] * xb[0] + v[2] * zb[0], v[1], v[0] * xb[2] + v[2] * zb[2])

    anchor_to_canopy = to_wind([c - p for c, p in zip(canopy, payload_pt)])
    qS = q * AREA
    slip = sideslip_derivatives(load("ramair_sideslip.json"), anchor_to_canopy, xb, zb, qS)
    cy_b, cl_b, cn_b = slip["CY_beta"], slip["Cl_beta"], slip["Cn_beta"]
    # Yaw damping of the table, about the mass centre [N m s]: -Cn_r q S b^2 / (2V).
    damping = -cn_r * qS * SPAN * SPAN / (2 * SPEED)
    coef = (cy_b, cl_b, cn_b, cl_p, cn_r, main["CD"], cd_lines * AREA)
    theta0 = a0 - math.atan2(main["CD_system"], main["CL_system"])  # the glide's pitch attitude

    def brake_set(side, roll, yaw, source):
        d_side, d_roll, d_yaw = side - before["side_force_N"], roll - before["roll_moment_Nm"], yaw - before["yaw_moment_Nm"]
        r, f = anchor_to_canopy, (0.0, d_side, 0.0)
        rxf = (r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0])
        m_c = [m - x for m, x in zip((-d_roll, 0.0, -d_yaw), rxf)]
        m_body = (sum(m_c[i] * xb[i] for i in range(3)), sum(m_c[i] * zb[i] for i in range(3)))
        # The free system's steady turn: roll and yaw about the mass centre balanced by the sideslip and the
        # turn's rates (lateral_balance).
        roll_g = m_body[0] - canopy[2] * d_side
        yaw_g = m_body[1] + canopy[0] * d_side
        beta, rate, yaw_eq = lateral_balance(m_body[0], m_body[1], d_side, canopy, coef, qS, theta0)
        return {"source": source, "side_force_N": side, "roll_moment_Nm": roll, "yaw_moment_Nm": yaw,
                "CY_differential_brake": d_side / qS, "Cl_differential_brake": m_body[0] / (qS * SPAN),
                "Cn_differential_brake": m_body[1] / (qS * SPAN),
                "about_mass_centre": {"side_force_N": d_side, "roll_moment_Nm": roll_g, "yaw_moment_Nm": yaw_g},
                "sideslip_of_turn_deg": math.degrees(beta), "yaw_at_roll_balance_Nm": yaw_eq,
                "turn_rate_rad_s": rate}

    sets = {
        "mean": brake_set(held["side_force_N"]["mean"], held["roll_moment_Nm"]["mean"], held["yaw_moment_Nm"]["mean"],
                          "the held windows' means (the table's)"),
        "right_end": brake_set(held["side_force_N"]["mean"], held["roll_moment_Nm"]["min"], held["yaw_moment_Nm"]["min"],
                               "the held windows' largest yaw to the right and smallest roll"),
        "left_end": brake_set(held["side_force_N"]["mean"], held["roll_moment_Nm"]["max"], held["yaw_moment_Nm"]["max"],
                              "the held windows' smallest yaw to the right and largest roll"),
        "ci_run": brake_set(rb["ci_run"]["side_force_N"], rb["ci_run"]["roll_moment_Nm"]["mean"],
                            rb["ci_run"]["yaw_moment_Nm"]["mean"], rb["ci_run"]["source"]),
    }
    cy_da, cl_da, cn_da = (sets["mean"][k] for k in ("CY_differential_brake", "Cl_differential_brake",
                                                      "Cn_differential_brake"))
    # the held mean's turn with the strip-theory estimates in place of the sideslip runs (for comparison)
    est_coef = (cy_beta, cl_beta, 0.0) + coef[3:]
    est = lateral_balance(cl_da * qS * SPAN, cn_da * qS * SPAN, cy_da * qS, canopy, est_coef, qS, theta0)
    # The same balance at another incidence: the canopy point at mu = mu0 + incidence keeps its coefficients
    # (N_c, L_c, Y_c the canopy point's yaw, roll and side force of the brake, body axes).
    n_c, l_c, y_c = cn_da * qS * SPAN, cl_da * qS * SPAN, cy_da * qS

    def turn_rate_at(incidence_deg, theta=theta0):
        mu = mu0 + math.radians(incidence_deg)
        point = [-arm * math.sin(mu), 0.0, -arm * math.cos(mu)]
        return lateral_balance(l_c, n_c, y_c, point, coef, qS, theta)[1]

    def pitch(r):
        return math.radians(r["alpha_centre_deg"]) - math.atan2(r["CD"] + cd_lines, r["CL_system"])
    # where the turn changes direction: the rate's numerator, the yaw left at the roll balance, changes sign
    # (it does not depend on the pitch); bisection over +-20 deg of incidence, None if it keeps its sign
    def yaw_left(incidence_deg):
        mu = mu0 + math.radians(incidence_deg)
        point = [-arm * math.sin(mu), 0.0, -arm * math.cos(mu)]
        return lateral_balance(l_c, n_c, y_c, point, coef, qS, theta0)[2]
    lo_i, hi_i = -20.0, 20.0
    crossover = None
    if yaw_left(lo_i) * yaw_left(hi_i) < 0:
        for _ in range(60):
            mid = 0.5 * (lo_i + hi_i)
            lo_i, hi_i = (mid, hi_i) if yaw_left(mid) * yaw_left(lo_i) > 0 else (lo_i, mid)
        crossover = 0.5 * (lo_i + hi_i)
    cbar = conv["converged"]

    def point(r):
        return {"run": r["run"], "rigging_angle_deg": r["rigging_angle_deg"], "alpha_centre_deg": r["alpha_centre_deg"],
                "CL": r["CL"], "CL_system": r["CL_system"], "CD": r["CD"], "CD_system": r["CD_system"], "Cm": r["Cm"],
                "glide_angle_deg": r["glide_angle_deg"], "trim_reached": r["trim_reached"],
                "incidence_deg": math.degrees(mus[r["rigging_angle_deg"]] - mu0),
                "last_fifth_change": {"CL": r["CL_change_last"], "CD": r["CD_change_last"]},
                "uncertainty": {
                    "CL": max(r["CL_change_last"] * r["CL"], 0.0),
                    "CD": max(r["CD_change_last"] * r["CD"], 0.0),
                    "is": "the drift of the halves of the last fifth of the run's windows (its trim criterion's "
                          "numbers, relative x value): the spread of the run itself, not its resolution error"}}

    table = {
        "command": "/usr/bin/python3 cases/flight/ramair_flight_table.py",
        "sources": {"polar": "docs/data/ramair_polar.json (" + polar["command"] + ")",
                    "resolution": "docs/data/ramair_convergence.json (" + conv["command"] + ")",
                    "brake": "docs/data/ramair_brake.json (" + brake["source"] + ")",
                    "sideslip": "docs/data/ramair_sideslip.json (" + slip["command"] + ")"},
        "points": [point(r) for r in rows],
        "resolution_uncertainty": {
            "CL": cbar["CL"]["error_bar"], "CD": cbar["CD"]["error_bar"],
            "CD_system": cbar["CD_system"]["error_bar"], "alpha_centre_deg": cbar["alpha_centre_deg"]["error_bar"],
            "is": "rung 3's error bar of the converged trim (structure levels s1-s3 and the off-skin fluid level): "
                  "the main job's point is " + f"{100 * conv['main_job_error']['CL']['relative']:+.1f} % in CL and "
                  f"{100 * conv['main_job_error']['CD_system']['relative']:+.1f} % in CD_system from it; not "
                  "included: the wall treatment (docs/AERODYNAMICS.md rung 3)"},
        "lines": {"CD_lines": cd_lines, "line_drag_area_m2": cd_lines * AREA,
                  "spread_over_points": [r["CD_system"] - r["CD"] for r in rows]},
        "system": {"weight_N": weight, "mass_kg": mass, "canopy_mass_kg": CANOPY_MASS, "payload_kg": payload,
                   "canopy_to_mass_centre_m": arm, "mass_centre_to_payload_m": below,
                   "mu_main_deg": math.degrees(mu0), "added_mass_kg": am, "added_inertia_canopy_kg_m2": ai,
                   "arc_height_m": arc_height, "lift_slope_helmbold": slope},
        "brake": dict(sets, yaw_damping_N_m_s=damping,
                      mean_with_estimated_sideslip_derivatives={"turn_rate_rad_s": est[1],
                                                                "sideslip_of_turn_deg": math.degrees(est[0])}, turn_direction_changes_at_incidence_deg=crossover,
                      turn_rate_at_rigging_points_rad_s={str(r["rigging_angle_deg"]): turn_rate_at(
                          math.degrees(mus[r["rigging_angle_deg"]] - mu0), pitch(r)) for r in rows},
                      turn_rate_is="the free system's steady turn from the coupled loads (lateral_balance): roll and "
                                   "yaw about the mass centre balanced by the canopy point's sideslip (the table's "
                                   "CY_beta, Cl_beta, Cn_beta, and the drag of canopy and lines along the sideways "
                                   "motion) and the turn's rates (Cl_p, Cn_r) at the glide's pitch; positive: a "
                                   "right turn. yaw_at_roll_balance_Nm: the yaw left when the sideslip alone "
                                   "balances the roll (what decides the direction)"),
        "sideslip": slip,
        "estimates": {"CY_beta": cy_beta, "Cl_beta": cl_beta, "Cn_beta": 0.0, "Cl_p": cl_p, "Cn_r": cn_r,
                      "is": "strip theory over the arc with Helmbold's slope; yaw damping of the profile drag; "
                            "the sideslip's three are not flown (the table's are the sideslip runs')"},
        "references": {
            "trim": {"airspeed_m_s": SPEED, "glide_angle_deg": main["glide_angle_deg"],
                     "tan_glide": main["CD_system"] / main["CL_system"], "alpha_centre_deg": main["alpha_centre_deg"],
                     "CL_system": main["CL_system"], "CD_system": main["CD_system"]},
            "turn_rate_rad_s": sets["mean"]["turn_rate_rad_s"]},
    }
    return table, {"turn_rate_at": turn_rate_at, "mass": mass, "inertia": inertia, "added_mass": am, "added_inertia": added_inertia,
                   "canopy": canopy, "payload": payload_pt, "line_drag_area": cd_lines * AREA,
                   "rows": rows, "cy_beta": cy_b, "cl_beta": cl_b, "cn_beta": cn_b, "cl_p": cl_p, "cn_r": cn_r,
                   "cy_beta_estimate": cy_beta, "cl_beta_estimate": cl_beta,
                   "cy_da": cy_da, "cl_da": cl_da, "cn_da": cn_da, "incidences": [p["incidence_deg"] for p in table["points"]]}


def fmt_list(values, digits=6):
    return "[" + ", ".join(f"{v:.{digits}g}" for v in values) + "]"


def flight_yaml(t, s):
    rows = s["rows"]
    inc = s["incidences"]
    rates = t["brake"]["turn_rate_at_rigging_points_rad_s"]
    if rates["9"] * rates["11"] < 0:
        raise SystemExit("ramair_flight_table: the brake turns the system different ways at the 9 and 11 deg rigging "
                         "points: the glide-slope range between them needs another choice")
    return f"""# GENERATED by cases/flight/ramair_flight_table.py from docs/data/ramair_polar.json, ramair_convergence.json,
# ramair_brake.json and ramair_sideslip.json - do not edit; run the script (docs/FLIGHT.md, "The coupled ram-air wing in flight").
# The main job's ram-air wing (cases/coupled/ramair-kt) set free: {t['system']['payload_kg']:.2f} kg of payload at the
# confluence point, the weight the coupled trim carries at 15 m/s, released at 400 m and guided to a target 1.2 km
# away through a waypoint, the glide path held by the incidence (the rigging points of the polar).
system:
  mass: {s['mass']:.6g}                    # kg: W = q S sqrt(CL^2 + CD_system^2) of the trim / g
  inertia: {fmt_list(s['inertia'], 5)}   # kg m^2 about the mass centre
  added_mass: {fmt_list(s['added_mass'], 5)}     # kg: Lissaman & Brown (1993)
  added_inertia: {fmt_list(s['added_inertia'], 5)}
  canopy_point: {fmt_list(s['canopy'], 6)}   # m: on the trim's line of action
  payload_point: {fmt_list(s['payload'], 6)}  # m: the confluence point
  payload_drag_area: 0            # the anchored wing had no payload: its glide is the canopy's and the lines'
  line_drag_area: {s['line_drag_area']:.6g}         # m^2: CD_lines x S of the main job
  munk_moment: false              # the table's Cm is the steady flow's: it holds the steady apparent-mass moment
aerodynamics:
  area: {AREA}
  span: {SPAN}
  chord: {CHORD}
  alpha: {fmt_list([r['alpha_centre_deg'] for r in rows], 7)}   # deg: centre section, rigging {', '.join(str(r['rigging_angle_deg']) for r in rows)} deg
  CL: {fmt_list([r['CL_system'] for r in rows], 7)}   # canopy + lines (CD_system x L/D_system)
  CD: {fmt_list([r['CD'] for r in rows], 7)}
  Cm: {fmt_list([r['Cm'] for r in rows], 7)}
  CY_beta: {s['cy_beta']:.5g}   # per rad, the sideslip runs (strip-theory estimate {s['cy_beta_estimate']:.3g})
  Cl_beta: {s['cl_beta']:.5g}   # about the canopy point (estimate {s['cl_beta_estimate']:.3g})
  Cn_beta: {s['cn_beta']:.5g}   # (estimate 0)
  Cl_p: {s['cl_p']:.5g}
  Cn_r: {s['cn_r']:.5g}
  CY_differential_brake: {s['cy_da']:.5g}   # the coupled right brake, 0.25 m = 1
  Cl_differential_brake: {s['cl_da']:.5g}
  Cn_differential_brake: {s['cn_da']:.5g}
start:
  position: [0, 0, 400]   # north, east, altitude [m]
  heading: 0
  pitch: {math.degrees(math.radians(rows[1]['alpha_centre_deg']) - math.atan2(t['references']['trim']['CD_system'], t['references']['trim']['CL_system'])):.3f}
  airspeed: 15
guidance:
  waypoints: [[750, 300], [1500, 0]]   # north, east [m]; the last is the target (a glide path of 13.9 deg)
  acceptance_radius: 30
  max_yaw_rate: 0.15
  max_brake: 0.5
  right_turn_brake: {'right' if rates['9'] > 0 and rates['11'] > 0 else 'left'}   # the brake that turns right there (the loads' balance)
  course_gains: {{kp: 0.5, ki: 0, kd: 0}}
  yaw_rate_gains: {{kp: 5, ki: 1, kd: 0, integral_limit: 0.5}}
  glide_slope:            # between the rigging points 9 and 11 deg, where a full right brake turns the system at
    control: incidence    # {rates['9']:+.3f} and {rates['11']:+.3f} rad/s (the loads' balance; + right)
    min: {min(inc):.3f}
    max: {inc[-2]:.3f}
    gains: {{kp: 2.0, ki: 0.2, kd: 0, integral_limit: 20}}
monte_carlo:              # the landing dispersion: steady winds up to 3 m/s from any side, release points scattered
  runs: 50
  seed: 1
  wind_speed: [0, 3]       # m/s, uniform
  wind_from: [0, 360]      # deg from north, uniform
  release_sd: [30, 30, 10] # m: north, east, altitude (normal)
time: {{end: 300, step: 0.01, output_interval: 0.1}}
"""


def main():
    if "--sideslip" in sys.argv[1:]:
        # the sideslip derivatives another set of sideslip runs gives (a check; nothing written)
        path = sys.argv[sys.argv.index("--sideslip") + 1]
        with open(path) as f:
            data = json.load(f)
        global load
        committed = load
        load = lambda name: data if name == "ramair_sideslip.json" else committed(name)  # noqa: E731
        table, _ = build()
        s = table["sideslip"]
        print(f"{path}: CY_beta {s['CY_beta']:+.4f}, Cl_beta {s['Cl_beta']:+.4f}, Cn_beta {s['Cn_beta']:+.4f} per rad "
              f"(symmetric part of the pair: {s['symmetric_part']}); the held mean's right brake: "
              f"{table['brake']['mean']['turn_rate_rad_s']:+.4f} rad/s")
        return
    table, system = build()
    outputs = {os.path.join(CASE, "flight_table.json"): json.dumps(table, indent=1) + "\n",
               os.path.join(CASE, "ramair-kt.flight.yaml"): flight_yaml(table, system)}
    if "--check" in sys.argv[1:]:
        stale = [p for p, text in outputs.items() if not os.path.isfile(p) or open(p).read() != text]
        for p in stale:
            print(f"{os.path.relpath(p, ROOT)} differs from what cases/flight/ramair_flight_table.py writes")
        sys.exit(1 if stale else 0)
    for p, text in outputs.items():
        with open(p, "w") as f:
            f.write(text)
        print("wrote", os.path.relpath(p, ROOT))


if __name__ == "__main__":
    main()
