"""A ram-air run's results (part of ramair_fluid.py, the case generator): summary.json and, for a coupled
run, summary.md from checkMesh's logs, the wing patch, postProcessing/forceCoeffs (every run segment joined in
time), structure/coupling.csv (through summarize.py) and the wing engineer's numbers (ramair_wing.py); the
brakes' response and plots/brake.png; the check that stops a run whose Courant number ran away.
"""
import json
import math
import os
import re
import sys

from ramair_geometry import _cross, _norm, v3
from ramair_mesh import check_mesh, patch_area
from ramair_settings import NUMBER, InputError, brake_travel, brake_window, load_record, read_settings


def read_table(path):
    rows, header = [], None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                words = line[1:].split()
                if words and words[0] == "Time":
                    header = words
                continue
            w = line.replace("(", " ").replace(")", " ").split()
            if w:
                rows.append([float(x) for x in w])
    return header, rows


def read_force_coeffs(case):
    """postProcessing/forceCoeffs/START/coefficient.dat of every run segment (a restart or a new mesh starts
    a new START), joined in time: a segment restarted at START writes the steps after it, and replaces what
    an earlier one wrote for them.
    Returns (header, rows, the first file)."""
    base = os.path.join(case, "postProcessing", "forceCoeffs")
    starts = []
    if os.path.isdir(base):
        for name in os.listdir(base):
            if NUMBER.match(name) and os.path.exists(os.path.join(base, name, "coefficient.dat")):
                starts.append((float(name), name))
    header, rows, first = None, [], os.path.join(base, "0", "coefficient.dat")
    for i, (t0, name) in enumerate(sorted(starts)):
        path = os.path.join(base, name, "coefficient.dat")
        h, r = read_table(path)
        if i == 0:
            header, first = h, path
        elif h != header:
            raise InputError(f"{path}: columns {h} differ from those of {first}")
        rows = [row for row in rows if row[0] <= t0 * (1 + 1e-9)] + r
    return header, rows, first


def read_vector_table(path):
    """A forces function object's force.dat or moment.dat: rows of time and the total vector."""
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            w = line.replace("(", " ").replace(")", " ").split()
            if len(w) >= 4:
                rows.append([float(x) for x in w[:4]])
    return rows


def lateral(case, d):
    """The rigid wing's side force and its roll and yaw moments (postProcessing/forces: the total force and its
    moment about CofR, the case's axes), averaged over the second half of the steps (a time-accurate run's
    settled part; docs/RAMAIR.md "Sideslip"). None when the forces function object wrote nothing."""
    base = os.path.join(case, "postProcessing", "forces", "0")
    if not all(os.path.exists(os.path.join(base, n)) for n in ("force.dat", "moment.dat")):
        return None
    fr, mr = read_vector_table(os.path.join(base, "force.dat")), read_vector_table(os.path.join(base, "moment.dat"))
    n = min(len(fr), len(mr))
    if n < 2:
        return None
    tail = range(n - n // 2, n)

    def mean(rows, i):
        return sum(rows[k][i] for k in tail) / len(tail)

    force, moment = [mean(fr, i) for i in (1, 2, 3)], [mean(mr, i) for i in (1, 2, 3)]
    flow = d["flow_dir"]
    # the flight model's wind axes (flight/FlightSystem.cpp): the wing moves along -flow; lift normal to that and
    # to the span (y), side = motion x lift (to the right at zero sideslip)
    motion = [-v for v in flow]
    up = _cross((0.0, 1.0, 0.0), motion)
    up = [v / _norm(up) for v in up]
    side = _cross(motion, up)
    qS, b = d["q"] * d["Aref"], d["span_projected"]

    def series(rows, vec):
        return [sum(r[1 + i] * vec[i] for i in range(3)) for r in rows[:n]]

    side_n = sum(force[i] * side[i] for i in range(3))
    roll, yaw = -moment[0], -moment[2]
    return {"axes": "x forward (-x of the case), y right (+y), z down (-z); moments about CofR; positive roll: right "
                    "wing down, positive yaw: nose to the right (the flight model's body axes at zero angle of attack)",
            "side_direction": side, "side_is": "the flight model's: motion x lift, lift normal to the motion and to y",
            "averaged_over": f"the last {len(tail)} of {n} steps", "CofR": d["CofR"],
            "force_N": force, "moment_Nm": moment, "force_moment_axes": "the case's (x downstream, y right, z up)",
            "side_force_N": side_n, "roll_moment_Nm": roll, "yaw_moment_Nm": yaw,
            "CY": side_n / qS, "Cl_roll": roll / (qS * b), "Cn_yaw": yaw / (qS * b),
            "coefficients_is": "CY on q Aref, Cl_roll and Cn_yaw on q Aref b (b: the projected span)",
            "history": {"time": [r[0] for r in fr[:n]], "side_force_N": series(fr, side),
                        "roll_moment_Nm": [-r[1] for r in mr[:n]], "yaw_moment_Nm": [-r[3] for r in mr[:n]]}}


def remeshes(case):
    """The new meshes of a run with remesh_below: time, window and reason of each (structure/remesh.N/request),
    and the checkMesh of each new mesh (log.checkMesh.remeshN)."""
    out = []
    n = 1
    while os.path.exists(os.path.join(case, "structure", f"remesh.{n}", "request")):
        with open(os.path.join(case, "structure", f"remesh.{n}", "request")) as f:
            r = dict(line.rstrip("\n").split(" ", 1) for line in f if " " in line)
        item = {"time": float(r.get("time", "nan")), "window": int(r.get("window", "-1")), "reason": r.get("reason", "")}
        log = f"log.checkMesh.remesh{n}"
        if os.path.exists(os.path.join(case, log)):
            item["mesh"] = check_mesh(case, log)
        out.append(item)
        n += 1
    return out


def summary(case):
    rec = load_record(case)
    s, d = rec["settings"], rec["derived"]
    out = {"case": os.path.basename(os.path.abspath(case)), "settings": s,
           "reference": {"Aref_m2": d["Aref"], "Aref_is": "wing area projected on the plane normal to the lift direction",
                         "lRef_m": d["lRef"], "CofR": d["CofR"], "aspect_ratio": d["aspect_ratio"],
                         "span_projected_m": d["span_projected"], "Re": d["Re"], "q_Pa": d["q"]},
           "mesh": check_mesh(case)}
    area, nf = patch_area(case, "wing")
    stl = rec["wing"]["area"] / (2 if s.get("half_domain") == "yes" else 1)  # half_domain: the half wing
    out["mesh"].update({"wing_faces": nf, "wing_patch_area": area, "stl_area": stl,
                        "area_relative_difference": (area - stl) / stl})
    est = {"formula": "Helmbold: CL = a0 a / (sqrt(1 + (a0/(pi AR))^2) + a0/(pi AR)), a0 = 2 pi, "
                      "a = incidence + inflow angle - zero-lift angle",
           "attitude": "design: the rigid design skin's centre chord and aspect ratio (a coupled run's estimate at "
                       "the flown attitude: wing.estimate)",
           "incidence_deg": rec["wing"]["incidence_deg"], "alpha_effective_deg": d["alpha_effective_deg"],
           "CL": d["CL_helmbold"]}
    out["estimate"] = est
    header, rows, coeff = read_force_coeffs(case)
    if rows and not (header and all(k in header for k in ("Time", "Cd", "Cl", "Cs", "CmPitch"))):
        raise InputError(f"{coeff}: no 'Time Cd Cs Cl ... CmPitch' header")
    if rows:
        col = {name: i for i, name in enumerate(header)}
        hist = {k: [r[col[k]] for r in rows] for k in ("Cl", "Cd", "Cs", "CmPitch")}
        n = len(rows)
        tail = max(2, n // 5)

        def spread(x):
            last = x[-tail:]
            return (max(last) - min(last)) / max(abs(x[-1]), 1e-30)

        finite = all(math.isfinite(v) for k in hist for v in hist[k])
        out["flow"] = {"steps": n, "time": rows[-1][0], "CL": hist["Cl"][-1], "CD": hist["Cd"][-1],
                       "CS": hist["Cs"][-1], "CmPitch": hist["CmPitch"][-1],
                       "L_over_D": hist["Cl"][-1] / hist["Cd"][-1] if hist["Cd"][-1] else None,
                       "lift_N": hist["Cl"][-1] * d["q"] * d["Aref"], "drag_N": hist["Cd"][-1] * d["q"] * d["Aref"],
                       "CL_spread_last_fifth": spread(hist["Cl"]), "CD_spread_last_fifth": spread(hist["Cd"]),
                       "finite": finite, "CL_over_estimate": hist["Cl"][-1] / d["CL_helmbold"],
                       "history": {"CL": hist["Cl"], "CD": hist["Cd"]}}
        for log in ("log.pimpleFoam", "log.simpleFoam"):
            p = os.path.join(case, log)
            if os.path.exists(p):
                with open(p) as f:
                    times = [float(x) for x in re.findall(r"^ExecutionTime = ([\d.eE+-]+) s", f.read(), re.M)]
                if len(times) > 2:
                    out["flow"]["wall_s_per_step"] = (times[-1] - times[0]) / (len(times) - 1)
                    out["flow"]["wall_s"] = times[-1]
    if s.get("coupled") != "yes":
        lat = lateral(case, d)
        if lat:
            out["lateral"] = lat
    if s.get("coupled") == "yes":
        out["coupled"] = coupled_summary(case, d)
        if os.path.exists(os.path.join(case, "log.checkMesh.final")):
            out["mesh_final"] = check_mesh(case, "log.checkMesh.final")
        out["remeshes"] = remeshes(case)
        if brake_window(s) and out["coupled"].get("windows"):
            out["coupled"]["brake"] = brake_response(case, s, d, out["remeshes"])
        if out["coupled"].get("windows"):
            sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
            import ramair_wing  # the wing engineer's numbers and plots (same folder)
            try:
                out["wing"] = ramair_wing.analyse(case, rec, out["coupled"])
            except ramair_wing.InputError as e:
                raise InputError(str(e))
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(out, f, indent=1)
    m = out["mesh"]
    print(f"mesh: {m['cells']} cells, checkMesh {'OK' if m['ok'] else 'failed ' + str(m['failed_checks'])}"
          f"{' (only skewness: ' + str(m['max_skewness']) + ')' if m['only_skewness'] else ''}, max non-ortho "
          f"{m['max_non_orthogonality']}; wing patch {area:.5g} m^2 vs STL {stl:.5g} m^2 "
          f"({100 * m['area_relative_difference']:+.2f} %)")
    if "mesh_final" in out:
        mf = out["mesh_final"]
        print(f"moved mesh at the end: checkMesh {'OK' if mf['ok'] else 'failed ' + str(mf['failed_checks'])}, "
              f"max non-ortho {mf['max_non_orthogonality']}, max skewness {mf['max_skewness']}")
    if "coupled" in out and out["coupled"].get("windows"):
        write_table(case, out)
        c = out["coupled"]
        print(f"coupled: {c['windows']} windows, {c['iterations_mean']:.2f} iterations per window (at most "
              f"{c['iterations_max']}, {c['not_converged']} not converged); interface force fluid vs structure "
              f"{c['force_fluid_vs_structure_max_relative']:.1e}, moment "
              f"{c['moment_fluid_vs_structure_max_relative'] or float('nan'):.1e}")
        print(f"  canopy: lift {c['lift_N']:.2f} N, drag {c['drag_N']:.2f} N, side {c['side_N']:.3f} N")
        if "wing" in out:
            import ramair_wing
            for line in ramair_wing.headline(out["wing"]):
                print(line)
        print(f"  anchor + toggles {v3(c['support_reaction_N'])} N vs applied {v3(c['applied_load_N'])} N "
              f"(balance {c['equilibrium_relative']:.1e})")
        print(f"  skin stress mean {c['skin_stress_mean_Pa'] / 1e3:.1f} kPa, max "
              f"{c['skin_stress_max_Pa'] / 1e3:.1f} kPa (ratio {c['stress_max_over_mean']:.2f})")
    for i, r in enumerate(out.get("remeshes", []), 1):
        m = r.get("mesh", {})
        print(f"remesh {i}: t = {r['time']:g} s (window {r['window']}), {r['reason']}; new mesh {m.get('cells', '?')} "
              f"cells, max skewness {m.get('max_skewness', '?')}")
    b = out.get("coupled", {}).get("brake")
    if b and b["held"]:
        h, p = b["held"], b["before"]
        turn = "a right turn" if h["yaw_Nm"] < 0 else "a left turn"
        print(f"brakes left/right {b['travel_left_m']:g} / {b['travel_right_m']:g} m (asks for a "
              f"{b['turn_asked']} turn), held for {b['held_windows']} windows: load about the anchor yaw "
              f"{h['yaw_Nm']:.3f} N m ({turn}; before "
              f"{p['yaw_Nm']:.3f}), roll {h['roll_Nm']:.3f} N m (before {p['roll_Nm']:.3f}), side force "
              f"{h['side_N']:.2f} N, brake lines right/left {h['brake_right_N']:.1f} / {h['brake_left_N']:.1f} N; "
              f"{len(b['new_meshes'])} new meshes since the pull began; plots/brake.png")
    elif b:
        print("brakes: the run ended before the pull did (plots/brake.png)")
    if "flow" in out:
        fl = out["flow"]
        print(f"flow: {fl['steps']} steps, CL {fl['CL']:.4f}, CD {fl['CD']:.4f}, L/D {fl['L_over_D']:.2f} "
              f"(spread over the last fifth: CL {100 * fl['CL_spread_last_fifth']:.2f} %, CD "
              f"{100 * fl['CD_spread_last_fifth']:.2f} %); Helmbold CL {est['CL']:.3f} at the design attitude (AR "
              f"{d['aspect_ratio']:.2f}, alpha {d['alpha_effective_deg']:.2f} deg from zero lift); "
              f"{fl.get('wall_s_per_step', float('nan')):.3f} s per step")


def brake_response(case, s, d, new_meshes):
    """What the pulled brakes do (brake_left, brake_right or brake_table): the loads on the wing before the pull
    (the mean of the last 20 windows before it starts) and while the toggles are held (the mean of the windows
    after the ramp or the table's last row), and their histories in plots/brake.png. Signs as a pilot reads them, for the flow's load on the
    wing about the anchor (the supports' reaction with the opposite sign; x downstream, y to the right, z up):
    yaw < 0 turns the nose (-x) towards +y, a right turn; roll > 0 lifts the right wing."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import summarize

    rows = summarize.coupling_rows(case)
    t0, t1 = brake_window(s)
    left, right = brake_travel(s)
    lift_dir, flow_dir = d["lift_dir"], d["flow_dir"]

    def dot(a, b):
        return sum(x * y for x, y in zip(a, b))

    def series(r):
        f = [float(r[f"F{c}_fluid"]) for c in "xyz"]
        return {"yaw_Nm": -float(r["anchor_moment_z"]), "roll_Nm": -float(r["anchor_moment_x"]),
                "side_N": f[1], "lift_N": dot(f, lift_dir), "drag_N": dot(f, flow_dir),
                "brake_right_N": float(r["brake_tension_right"]), "brake_left_N": float(r["brake_tension_left"])}

    t = [float(r["time"]) for r in rows]
    v = [series(r) for r in rows]
    before = [x for x, tt in zip(v, t) if tt <= t0][-20:]
    held = [x for x, tt in zip(v, t) if tt >= t1]

    def mean(part):
        return {k: sum(x[k] for x in part) / len(part) for k in part[0]} if part else None

    out = {"start_s": t0, "end_of_ramp_s": t1, "travel_m": right, "travel_left_m": left, "travel_right_m": right,
           "before": mean(before),
           "held": mean(held), "held_windows": len(held),
           "new_meshes": [m["time"] for m in new_meshes if m["time"] >= t0 - 1e-9]}
    if held:
        h = out["held"]
        out["right_turn"] = h["yaw_Nm"] < 0 and h["brake_right_N"] > h["brake_left_N"]
        out["left_turn"] = h["yaw_Nm"] > 0 and h["brake_left_N"] > h["brake_right_N"]
        # the turn the inputs ask for: the side pulled further (a symmetric pull asks for none)
        out["turn_asked"] = "right" if right > left else "left" if left > right else "none"
        out["held_range"] = {k: [min(x[k] for x in held), max(x[k] for x in held)] for k in held[0]}
    plot_brake(case, t, v, out)
    return out


def plot_brake(case, t, v, b):
    """plots/brake.png: yaw and roll of the load about the anchor, side force, lift and drag, brake line
    tensions, from shortly before the pull to the end; the ramp shaded, new meshes marked."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("ramair_fluid: no matplotlib: plots/brake.png not written", file=sys.stderr)
        return
    lo = b["start_s"] - 0.5 * (b["end_of_ramp_s"] - b["start_s"])
    keep = [i for i, tt in enumerate(t) if tt >= lo]
    tt = [t[i] for i in keep]
    panels = [("moments [N m]", [("yaw_Nm", "yaw of the load about the anchor (< 0: nose to the right)"),
                                 ("roll_Nm", "roll (> 0: right wing up)")]),
              ("side force [N]", [("side_N", "side force (+y: right)")]),
              ("lift and drag [N]", [("lift_N", "lift"), ("drag_N", "drag")]),
              ("brake lines [N]", [("brake_right_N", "right"), ("brake_left_N", "left")])]
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 9), sharex=True)
    for ax, (label, curves) in zip(axes, panels):
        for key, name in curves:
            ax.plot(tt, [v[i][key] for i in keep], label=name)
        ax.axvspan(b["start_s"], b["end_of_ramp_s"], color="0.9", label="pull (ramp)")
        for i, tm in enumerate(b["new_meshes"]):
            ax.axvline(tm, color="tab:red", ls=":", lw=0.8, label="new mesh" if i == 0 else None)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    axes[-1].set_xlabel("time [s]")
    fig.suptitle(f"brakes left {b['travel_left_m']:g} m, right {b['travel_right_m']:g} m down, from "
                 f"{b['start_s']:g} to {b['end_of_ramp_s']:g} s")
    fig.tight_layout()
    os.makedirs(os.path.join(case, "plots"), exist_ok=True)
    fig.savefig(os.path.join(case, "plots", "brake.png"), dpi=110)
    plt.close(fig)


def write_table(case, out):
    """summary.md: the coupled run's answers in one table, with the references they are compared with."""
    c, e, d = out["coupled"], out["estimate"], out["reference"]
    rows = [("windows (fluid steps), coupling", f"{c['windows']}, {c['iterations_mean']:.2f} iterations per window", "")]
    if "wing" in out:
        import ramair_wing
        rows += ramair_wing.table_rows(out["wing"])
    else:  # a run without the structure's mesh and frames: the flow's force on the design area only
        rows.append(("CL, CD of the canopy, L/D (design projected area)",
                     f"{c['CL']:.4f}, {c['CD']:.4f}, {c['L_over_D']:.2f}", f"A = {d['Aref_m2']:.3f} m^2"))
    rows += [
        ("side force [N]", f"{c['side_N']:.3f}", "mirror symmetry: 0"),
        ("anchor + toggles reaction [N]", v3(c["support_reaction_N"]), "minus the applied load at equilibrium"),
        ("applied load (flow + ram pressure + line drag) [N]", v3(c["applied_load_N"]),
         f"balance {c['equilibrium_relative']:.1e}"),
        ("supports' moments about the anchor (confluence point) [N m]", v3(c["anchor_moment_Nm"]), "x: roll, z: yaw"),
        ("interface force fluid vs structure (max over windows)", f"{c['force_fluid_vs_structure_max_relative']:.1e}",
         "conservative transfer: round-off"),
        ("interface moment fluid vs structure (max over windows)",
         f"{c['moment_fluid_vs_structure_max_relative'] or float('nan'):.1e}", "round-off with conserve_moment yes (default); the surfaces' gap with no"),
        ("skin principal stress mean, max [kPa]", f"{c['skin_stress_mean_Pa'] / 1e3:.1f}, {c['skin_stress_max_Pa'] / 1e3:.1f}",
         "Kalro-Tezduyar: 758, 4337 (110, 629 lb/in^2)"),
        ("max / mean", f"{c['stress_max_over_mean']:.2f}", "Kalro-Tezduyar: 5.7"),
    ]
    b = c.get("brake")
    if b and b["held"]:
        h, p = b["held"], b["before"]
        rows += [
            (f"brakes held (left {b['travel_left_m']:g} m, right {b['travel_right_m']:g} m): yaw, roll of the load "
             "about the anchor [N m]",
             f"{h['yaw_Nm']:.3f}, {h['roll_Nm']:.3f} (before the pull {p['yaw_Nm']:.3f}, {p['roll_Nm']:.3f})",
             "yaw < 0: the nose turns right (a right turn), > 0 left; roll > 0: the right wing lifted"),
            ("brakes held: side force, lift, drag [N]",
             f"{h['side_N']:.2f}, {h['lift_N']:.2f}, {h['drag_N']:.2f} (before {p['side_N']:.2f}, {p['lift_N']:.2f}, "
             f"{p['drag_N']:.2f})", f"means over the {b['held_windows']} windows after the ramp; plots/brake.png"),
        ]
    elif b:
        rows.append(("brakes", "the run ended before the pull did", "plots/brake.png"))
    if c.get("skin_folds") is not None:
        rows.append(("skin edges turned > 90 deg from the design (folds probe)", f"{c['skin_folds']:.0f}",
                     "the trailing edge's crumple (docs/RAMAIR.md)"))
    with open(os.path.join(case, "summary.md"), "w") as f:
        f.write(f"# {out['case']}: coupled ram-air wing, {out['settings']['speed']:g} m/s, q = {d['q_Pa']:.4g} Pa, "
                f"Re {d['Re']:.3g}\n\n| quantity | this run | reference |\n|---|---|---|\n")
        for r in rows:
            f.write(f"| {r[0]} | {r[1]} | {r[2]} |\n")


def coupled_summary(case, d):
    """The coupled run from structure/coupling.csv (one row per window: interface force on both sides, the
    structure's probes): coupling statistics, the forces on the wing and on its anchor at the last window, the
    balance of the two (static equilibrium: the supports hold everything applied), line tensions, stresses."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import summarize  # the coupled cases' reader of coupling.csv (same folder)

    rows = summarize.coupling_rows(case)
    if not rows:
        return {"windows": 0}
    last = {k: float(v) for k, v in rows[-1].items()}
    q, aref = d["q"], d["Aref"]
    lift_dir, flow_dir = d["lift_dir"], d["flow_dir"]

    def vec(prefix, suffix=""):
        return [last.get(f"{prefix}{c}{suffix}", float("nan")) for c in "xyz"]

    def dot(a, b):
        return sum(x * y for x, y in zip(a, b))

    fluid = [last[f"F{c}_fluid"] for c in "xyz"]  # the flow's force on the wing (pressure + shear)
    applied = vec("applied_load_")  # everything applied to the structure: flow, ram pressure, line drag
    support = [a + b for a, b in zip(vec("anchor_force_"), vec("toggles_force_"))]
    # the applied load minus the flow's force on the skin: the line drag, and the difference between the relaxed
    # load the structure carries (load_relaxation) and the flow's latest (the line drag alone: wing.forces)
    applied_minus_flow = [a - f for a, f in zip(applied, fluid)]
    scale = max(_norm(applied), 1e-30)
    iters = [int(r["iterations"]) for r in rows]
    hist = {k: [float(r[k]) for r in rows] for k in ("time", "Fx_fluid", "Fz_fluid", "anchor_force_x",
                                                      "anchor_force_z", "residual")}
    if rows and "chord_pitch_angle" in rows[0]:
        hist["chord_pitch_angle"] = [float(r["chord_pitch_angle"]) for r in rows]
    # per window: the flow's lift and drag on the canopy
    f_w = [[float(r[f"F{k}_fluid"]) for k in "xyz"] for r in rows]
    hist["lift_N"] = [dot(f, lift_dir) for f in f_w]
    hist["drag_N"] = [dot(f, flow_dir) for f in f_w]
    lift = dot(fluid, lift_dir)
    drag = dot(fluid, flow_dir)
    smean, smax = last.get("skin_stress_mean", float("nan")), last.get("skin_stress_max", float("nan"))
    return {
        "windows": len(rows), "time": last["time"],
        "iterations_mean": sum(iters) / len(iters), "iterations_max": max(iters),
        "not_converged": sum(1 for r in rows if r["converged"] == "0"),
        "force_fluid_vs_structure_max_relative": summarize.force_difference(rows),
        "moment_fluid_vs_structure_max_relative": summarize.moment_difference(rows),
        "moment_fluid_Nm": vec("M", "_fluid"), "moment_structure_Nm": vec("M", "_structure"),
        "fluid_force_N": fluid, "lift_N": lift, "drag_N": drag, "side_N": fluid[1],
        "CL": lift / (q * aref), "CD": drag / (q * aref), "L_over_D": lift / drag if drag else None,
        "applied_minus_flow_N": applied_minus_flow, "applied_load_N": applied, "support_reaction_N": support,
        "anchor_force_N": vec("anchor_force_"), "toggles_force_N": vec("toggles_force_"),
        "equilibrium_relative": _norm([a + b for a, b in zip(applied, support)]) / scale,
        "anchor_moment_Nm": vec("anchor_moment_"),
        # the x-z angle between the mean of all leading-edge and all trailing-edge nodes: a probe of the whole
        # canopy's pitch, not a section's angle of attack (those: summary.json's wing.section_alpha)
        "mean_chord_pitch_deg": last.get("chord_pitch_angle"),
        "line_tension_max_N": last.get("line_tension_max"),
        "lines_left_sum_N": last.get("lines_left_sum"), "lines_right_sum_N": last.get("lines_right_sum"),
        "brake_tension_left_N": last.get("brake_tension_left"),
        "brake_tension_right_N": last.get("brake_tension_right"),
        "skin_stress_mean_Pa": smean, "skin_stress_max_Pa": smax,
        "stress_max_over_mean": smax / smean if smean else None,
        "enclosed_volume_m3": last.get("enclosed_volume"),
        "skin_folds": last.get("skin_folds"),
        "history": hist,
    }


def courant_check(log_path, settings_path):
    """A pimpleFoam log whose Courant number ran away (past 100 times the settings' `courant`, or not a number):
    the message naming the log, the worst Courant number and its time; None when the run stayed sane."""
    limit = 100 * read_settings(settings_path)["courant"]
    worst, when, t = None, None, None
    try:
        with open(log_path, errors="replace") as f:
            for line in f:
                if line.startswith("Time = "):
                    t = line.split()[2]
                elif line.startswith("Courant Number mean:"):
                    v = float(line.split()[-1])
                    if worst is None or (worst == worst and not v <= worst):  # a NaN is the worst and stays
                        worst, when = v, t
    except (OSError, ValueError, IndexError) as e:
        raise InputError(f"{log_path}: cannot read its Courant numbers ({e})")
    if worst is not None and not worst <= limit:
        return (f"{log_path}: the flow diverged: Courant number {worst:.4g} at t = {when} s, more than 100 times the "
                f"asked {limit / 100:g}: lower courant in {settings_path} (thin wall cells, wall_split, need a "
                "smaller step)")
    return None
