#!/usr/bin/env python3
"""Checks the wing engineer's numbers of a finished coupled ram-air case (summary.json's `wing`, written by
cases/coupled/ramair_wing.py) against references computed here from the raw outputs, not from that code:

  confluence   the axial forces of every cable at the confluence point (found here by the generator's formula
               for its position, not by the sets: the written elastic tension plus the bulk viscosity's part,
               recomputed from the written velocities with the mass-scaled wave speed), summed as vectors with
               the line drag that node carries itself, balance the anchor's reaction probe (the node's
               equilibrium, 1e-9 of the reaction); the viscous part is under 1e-4 of the reaction (the end
               state is still); the summary's vector sum is that of the elastic tensions (1e-9)
  line drag    the line drag recomputed here from the deformed lines of the last frame (the line_drag model of
               structure/effects/AerodynamicDrag.hpp: 1/2 rho C_D d |U_n| U_n per unit length, every cable)
               equals the summary's (1e-3): CD system = CD canopy + CD lines on both reference areas
  design       the design section angle of every rib equals the generator's incidence + twist |2 s / b| (1e-9 deg)
  glide        tan(glide angle) = CD / CL of the system; CL and CD of both areas from the summary's forces
  surface      the wing patch's pressure + shear summed equals the interface lift (0.5 %)
  trim         trim_reached, and the centre section's angle changed by less than 0.25 deg over the last fifth
  plots        the wing_*.png exist and are not blank
Usage: check_ramair_wing.py CASE_DIR   (exit 1 naming each failed check)
"""
import json
import math
import os
import sys

import numpy as np
import yaml


def main(case):
    bad = []

    def check(ok, what):
        if not ok:
            bad.append(what)

    s = json.load(open(os.path.join(case, "summary.json")))
    w, c = s["wing"], s["coupled"]
    scene = yaml.safe_load(open(os.path.join(case, "structure-coupled.yaml")))
    gen = scene["meshes"]["wing"]["generator"]
    rec = json.load(open(os.path.join(case, "constant", "fluidSettings.json")))
    e_d, e_l = np.array(rec["derived"]["flow_dir"]), np.array(rec["derived"]["lift_dir"])
    q = rec["derived"]["q"]

    import h5py
    with h5py.File(os.path.join(case, "structure", "results.h5"), "r") as f:
        steps = sorted(f["steps"].values(), key=lambda g: float(g.attrs["time"]))
        g = steps[-1]
        x, v, T = g["coordinates"][()], g["velocity"][()], g["cable_force"][()]
        x0 = steps[0]["coordinates"][()] - steps[0]["displacement"][()]
        lines = f["mesh/lines"][()]

    # confluence point: the generator's formula (structure/parafoil/ParafoilGeometry.cpp)
    span, L = gen["span"], gen["line_length"] * gen["span"]
    mu = math.radians(gen.get("rigging_angle", 5.0))
    conf = np.array([0.25 * gen["root_chord"] - L * math.sin(mu), 0.0, -L * math.cos(mu)])
    k = int(np.argmin(np.linalg.norm(x0 - conf, axis=1)))
    check(np.linalg.norm(x0[k] - conf) < 1e-9 * span, "no structure node at the generator's confluence point")
    ld = scene["effects"]["line_drag"]
    half_rho_cd_d = 0.5 * ld["density"] * ld["cd"] * ld["diameter"]
    wind = np.array(ld["wind"], float)

    def drag(e):
        i, j = lines[e]
        d = x[j] - x[i]
        rel = wind - 0.5 * (v[i] + v[j])
        wn = rel - (rel @ d) / (d @ d) * d
        return half_rho_cd_d * np.linalg.norm(wn) * np.linalg.norm(d) * wn  # the element's whole force

    # The cables' viscous axial force (structure/elements/AxialKernel.hpp): (beta + b1 L0 / c) E A dL/dt / L0,
    # with c the element's wave speed after mass scaling (structure/elements/TwoNodeElements.hpp raises an
    # element's density until L0 / c reaches the needed step mass_scaling_min_dt / safety).
    line_mat = scene["materials"][scene["meshes"]["wing"]["cable_material"]]
    # (float(): PyYAML reads 4.3e10, without a dot in the mantissa's sense of YAML 1.1, as a string)
    young, density = float(line_mat["young"]), float(line_mat["density"])
    ea = young * float(line_mat["area"])
    b1 = float((scene["effects"]["bulk_viscosity"] or {}).get("b1", 0.06)) if "bulk_viscosity" in scene["effects"] else 0.0
    beta = float(line_mat.get("beta", 0.0))
    tcfg = scene.get("time", {})
    need = float(tcfg.get("mass_scaling_min_dt", 0.0)) / float(tcfg.get("safety", 0.9))

    def viscous(e):
        i, j = lines[e]
        d = x[j] - x[i]
        l0 = np.linalg.norm(x0[j] - x0[i])
        l_over_c = max(l0 * math.sqrt(density / young), need)
        return (beta + b1 * l_over_c) * ea * ((v[j] - v[i]) @ d) / np.linalg.norm(d) / l0

    at = [e for e in range(len(lines)) if k in lines[e]]

    def toward_other_end(e):
        o = lines[e][1] if lines[e][0] == k else lines[e][0]
        return (x[o] - x[k]) / np.linalg.norm(x[o] - x[k])

    pull = sum(T[e] * toward_other_end(e) for e in at)
    pull_viscous = sum(viscous(e) * toward_other_end(e) for e in at)
    node_drag = sum(0.5 * drag(e) for e in at)
    reaction = np.array(c["anchor_force_N"])
    res = np.linalg.norm(pull + pull_viscous + node_drag + reaction) / np.linalg.norm(reaction)
    still = np.linalg.norm(pull_viscous) / np.linalg.norm(reaction)
    wl = w["lines"]
    summ = np.array(wl["vector_sum_at_confluence_N"])
    print(f"confluence: {len(at)} cables, tensions + viscous part + own line drag + anchor reaction = {res:.2e} of "
          f"the reaction (the viscous part {still:.2e}); the summary's vector sum vs this one "
          f"{np.linalg.norm(summ - pull) / np.linalg.norm(pull):.1e}; {len(wl['at_confluence'])} named lines")
    check(res < 1e-9, f"the confluence node is not in equilibrium with the anchor's reaction ({res:.2e})")
    # The bulk viscosity damps only the lines' axial vibration; at a trimmed end state it is a small fraction
    # of the load (1e-6 here). 1e-4 of the reaction marks lines still ringing from the last window.
    check(still < 1e-4, f"the lines at the confluence still vibrate: their viscous force is {still:.2e} of the reaction")
    check(np.linalg.norm(summ - pull) < 1e-9 * np.linalg.norm(pull), "the summary's vector sum is not the sum of the "
          "tensions of the cables at the confluence point")
    check(len(wl["at_confluence"]) == len(at), f"{len(wl['at_confluence'])} lines named at the confluence, {len(at)} there")
    per_row = {r["lines"] for r in wl["rows"].values()}
    check(len(per_row) == 1 and len(wl["rows"]) == len(gen.get("rows", [0.1, 0.3, 0.6, 0.8])),
          f"rows at the confluence {wl['rows']}: every row should have as many lines")

    # line drag from the deformed lines (every cable is in the line_drag sets of the main job's scene)
    total = sum(drag(e) for e in range(len(lines)))
    fo = w["forces"]
    summary_drag = np.array(fo["line_drag_N"])
    diff = np.linalg.norm(total - summary_drag) / np.linalg.norm(total)
    print(f"line drag recomputed ({', '.join(f'{a:.3f}' for a in total)}) N vs the summary's "
          f"({', '.join(f'{a:.3f}' for a in summary_drag)}) N: {diff:.1e}")
    check(diff < 1e-3, f"line drag differs from the one recomputed from the deformed lines by {diff:.1e}")
    for name, co in w["coefficients"].items():
        if not isinstance(co, dict):
            continue
        cd_lines = float(total @ e_d) / (q * co["area_m2"])
        check(abs(co["CD_system"] - (co["CD_canopy"] + cd_lines)) < 1e-3 * co["CD_system"],
              f"{name}: CD system {co['CD_system']:.5f} is not CD canopy {co['CD_canopy']:.5f} + CD lines {cd_lines:.5f}")
        check(abs(co["CL_canopy"] - fo["lift_canopy_N"] / (q * co["area_m2"])) < 1e-9,
              f"{name}: CL canopy is not the lift over q A")
        check(abs(math.tan(math.radians(w["coefficients"]["glide_angle_deg"])) - co["CD_system"] / co["CL_system"]) < 1e-9,
              f"{name}: tan(glide angle) is not CD / CL of the system")
    check(w["reference"]["deformed_projected_area_m2"] < w["reference"]["design_projected_area_structure_m2"] * 1.05,
          "the loaded canopy's projected area grew by more than 5 %")

    # design section angles: the generator's incidence + twist |2 s / b| on every rib
    inc, twist, cells = gen.get("incidence", 0.0), gen.get("twist", 0.0), gen["cells"]
    ribs = w["section_alpha"]["ribs"]
    check(len(ribs) == cells + 1, f"{len(ribs)} ribs, the generator has {cells + 1}")
    worst = max(abs(r["alpha_design_deg"] - (inc + twist * abs(2 * (-span / 2 + i * span / cells) / span)))
                for i, r in enumerate(ribs))
    print(f"design section angles vs incidence {inc} + twist {twist}: largest difference {worst:.1e} deg")
    check(worst < 1e-9, f"the design section angles differ from the generator's incidence by {worst:.1e} deg")

    fs = w["fluid_surface"]
    print(f"wing patch lift vs the interface's: {100 * fs['lift_sum_vs_interface']:+.3f} % ({fs['load_is']})")
    check(abs(fs["lift_sum_vs_interface"]) < 0.005, "the wing patch's pressure and shear do not sum to the interface lift")

    # the pitching moment about the deformed centre quarter chord, moved to forceCoeffs' CofR (the design's),
    # against OpenFOAM's own CmPitch there (its forces function object, the same last window)
    ref, cofr = fs["Cm_reference_point_m"], s["reference"]["CofR"]
    a_design = s["reference"]["Aref_m2"]
    F = fs["force_sum_N"]
    arm = [ref[i] - cofr[i] for i in range(3)]
    transfer_y = arm[2] * F[0] - arm[0] * F[2]  # ((ref - CofR) x F) . (0 1 0)
    m_cofr = fs["Cm_quarter_chord"] * q * a_design * fs["Cm_reference_chord_m"] + transfer_y
    cm_cofr = m_cofr / (q * a_design * s["reference"]["lRef_m"])
    cm_foam = s["flow"]["CmPitch"]
    print(f"Cm about the deformed centre quarter chord {fs['Cm_quarter_chord']:.4f}; moved to CofR {cm_cofr:.4f}, "
          f"forceCoeffs' CmPitch {cm_foam:.4f}")
    check(abs(cm_cofr - cm_foam) < 0.002 + 0.02 * abs(cm_foam),
          "the pitching moment of the patch's faces disagrees with forceCoeffs' CmPitch about CofR")
    check(-0.3 < fs["Cm_quarter_chord"] < 0.0,
          "Cm about the quarter chord is not nose-down (a positively cambered section's, thin-aerofoil theory "
          "-0.106 for the NACA 44xx camber line)")

    t = w["trim"]
    print(f"trim reached {t['trim_reached']}: CL {100 * t['CL_change']:.2f} %, CD {100 * t['CD_change']:.2f} %, centre "
          f"alpha {t['centre_alpha_change_deg'] if t['centre_alpha_change_deg'] is None else round(t['centre_alpha_change_deg'], 3)} deg, balance {100 * t['balance']:.3f} %")
    check(t["trim_reached"], "trim not reached: " + t["criterion"])
    check(t["centre_alpha_change_deg"] is not None and t["centre_alpha_change_deg"] < 0.25,
          "the centre section's angle changed by 0.25 deg or more over the last fifth")

    # the main job states its error against the converged answer of its own inputs (docs/data/ramair_convergence
    # .json, installed beside ramair_wing.py); a changed main job must re-run studies/ramair/trim_study.py
    r = w.get("converged_reference", {})
    if os.environ.get("FSI_EXPECT_CONVERGED_REFERENCE") == "1":
        check(r.get("available") is True, "the summary states no error against the converged answer: "
              + r.get("why", "no converged_reference"))
    if r.get("available"):
        print(f"error against the converged answer: CL {100 * r['CL']['relative']:+.1f} % "
              f"({r['CL']['this_run']:.4f} vs {r['CL']['converged']:.4f} +- {r['CL']['error_bar']:.4f})")
        check(abs(r["CL"]["this_run"] - w["coefficients"]["design_area"]["CL_canopy"]) < 1e-12,
              "the converged reference's 'this run' CL is not the summary's")

    import matplotlib.image
    for name in ("wing_alpha", "wing_lift", "wing_cp", "wing_cp_map", "wing_sections", "wing_convergence", "wing_lines"):
        path = os.path.join(case, "plots", name + ".png")
        ok = os.path.exists(path) and float(matplotlib.image.imread(path)[..., :3].std()) > 0.01
        check(ok, f"plots/{name}.png missing or blank")
    for b in bad:
        print("FAIL:", b)
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__.split("\n\n")[-1], file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
