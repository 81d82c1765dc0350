#!/usr/bin/env python3
"""The coupled round canopy's own numbers (cases/coupled/round-canopy, docs/ROUND_CANOPY.md "Coupled descent"),
added to the summary.json that summarize.py wrote, and its plots.

From structure/coupling.csv (the structure's probes per window) and postProcessing/ (OpenFOAM's function
objects), averaged over the run's last `average_last` seconds (reference.yaml, round_canopy):
  C_D0 = D / (q S0) on the nominal area, and C_D on the canopy's projected area (the 12-gon across the skirt
  ends), blockage-corrected (Maskell) and checked against the rigid hollow hemisphere;
  D_p/D0, D_p the projected diameter: twice the largest distance of a cloth node from the axis (the canopy's
  frames in structure/results.h5);
  the vent's mean axial velocity against Bernoulli's speed sqrt(2 dp / rho) from the pressure drop across it
  (the probes, fixed in space); the velocity is the volume flux through the vent's own mesh faces (the
  faceZone `vent`, controlDict's ventFlux: they move with the mesh, so a restart or a new mesh reads the same
  opening) over their area, the opening as the mesh has it (about 0.92 of the vent polygon's area);
  the force balance at the held confluence point (its reaction against the fluid's axial force);
  breathing: the axial force's and the skirt radius's fluctuation over the window, the dominant period
  (Strouhal number on D_p), the lateral force.
Each checked entry goes into summary.json's results (the format of summarize.py) and all_checks_within_tolerance.
A remeshing run (system/remeshing) reads its histories across the meshes (coupling.csv goes on, postProcessing/
holds one <start time>/ folder per mesh); round_canopy.remeshes lists the new meshes (structure/remesh.N/request:
the time and the reason, stageN/ the case before it) with the histories across each: the axial force's jump
(the first window on the new mesh against the last one on the old, relative, beside the largest change between
two windows in the 10 windows before), its mean over the 10 windows after against the 10 before (the restart
on mapped fields shakes the force for a few windows; a lost or misplaced field would shift it), and the
skirt radius's jump (the structure goes on from its state: one window's motion).
Plots: plots/round_canopy_history.png (C_D0, D_p/D0, vent velocity ratio against time),
plots/round_canopy_flow.png (pressure across the cloth; the axial velocity in the plane y = 0), when the
surfaces function object wrote them.

Usage: round_canopy_summary.py CASE_DIR
"""
import glob
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from summarize import all_parts, coupling_rows  # noqa: E402


def mean_over(t, v, t0):
    """Time average (trapezoidal) of v over t >= t0, its standard deviation, the samples used."""
    sel = [(a, b) for a, b in zip(t, v) if a >= t0 - 1e-12]
    if len(sel) < 2:
        return None, None, len(sel)
    area = sum(0.5 * (b[1] + a[1]) * (b[0] - a[0]) for a, b in zip(sel, sel[1:]))
    m = area / (sel[-1][0] - sel[0][0])
    sd = math.sqrt(sum((b - m) ** 2 for _, b in sel) / len(sel))
    return m, sd, len(sel)


def dominant_period(t, v):
    """The period of the strongest Fourier component of v (mean removed) on a uniform series; None if flat."""
    n = len(v)
    if n < 8:
        return None
    m = sum(v) / n
    dt = (t[-1] - t[0]) / (n - 1)
    best, k_best = 0.0, 0
    for k in range(1, n // 2):
        c = sum((x - m) * math.cos(2 * math.pi * k * i / n) for i, x in enumerate(v))
        s = sum((x - m) * math.sin(2 * math.pi * k * i / n) for i, x in enumerate(v))
        if c * c + s * s > best:
            best, k_best = c * c + s * s, k
    return n * dt / k_best if k_best else None


def frames_radius(case):
    """Times of the canopy's frames and, for each, the largest distance of a cloth node from the z axis."""
    import h5py

    path = os.path.join(case, "structure", "results.h5")
    if not os.path.exists(path):
        return [], []
    with h5py.File(path, "r") as f:
        nodes = sorted(set(int(i) for tri in f["mesh/triangles"][:] for i in tri))
        times, radii = [], []
        for k in sorted(f["steps"].keys()):
            x = f["steps"][k]["coordinates"][:]
            times.append(float(f["steps"][k].attrs["time"]))
            radii.append(max(math.hypot(x[i][0], x[i][1]) for i in nodes))
    return times, radii


def interp(ts, vs, x):
    """Linear interpolation of the series (ts, vs) at x (held constant beyond its ends)."""
    if x <= ts[0]:
        return vs[0]
    for a, b, va, vb in zip(ts, ts[1:], vs, vs[1:]):
        if x <= b:
            return va + (vb - va) * (x - a) / (b - a) if b > a else vb
    return vs[-1]


def entry(value, when, spec, end):
    pub = spec["published"]
    lo, hi = min(pub), max(pub)
    tol = spec.get("tolerance", 0.1)
    rng = [lo - tol * abs(lo), hi + tol * abs(hi)]
    return {"value": value, "time": when, "published": [{"value": p} for p in pub], "accepted_range": rng,
            "within": value is not None and rng[0] <= value <= rng[1], "check": bool(spec.get("check", False)),
            "complete": True}


def vent_series(case, ref):
    """Times; the vent's mean axial velocity, the volume flux through the vent's faces (the faceZone `vent`,
    controlDict's ventFlux: relative to the moving mesh) over their area; that flux and area; Bernoulli's speed
    from the probes' pressure drop; and the fixed plane's reading (ventFlow: kept for comparison, not checked;
    None where it was not written)."""
    pp = os.path.join(case, "postProcessing")
    q = all_parts(os.path.join(pp, "ventFlux"), "surfaceFieldValue.dat")
    plane = all_parts(os.path.join(pp, "ventFlow"), "surfaceFieldValue.dat")
    p = {}
    for d in glob.glob(os.path.join(pp, "pressureProbes", "*", "p")):
        for line in open(d):
            if line.startswith("#") or not line.strip():
                continue
            x = [float(a) for a in line.split()]
            p[x[0]] = x[1:]
    times = sorted(set(q) & set(p))
    area = [q[t][0] for t in times]
    flux = [q[t][1] for t in times]
    uz = [f / a for f, a in zip(flux, area)]
    # kinematic pressure (p / rho): Bernoulli's speed is sqrt(2 dp)
    bern = [math.sqrt(max(0.0, 2 * (p[t][0] - p[t][1]))) for t in times]
    uplane = [plane[t][2] if t in plane else None for t in times]
    return times, uz, bern, flux, area, uplane


def cloth_setting(case):
    """The cloth's permeability from constant/cloth: None (impermeable) or {"a": .., "b": .., "relaxation": ..}."""
    path = os.path.join(case, "constant", "cloth")
    if not os.path.exists(path):
        return None
    for line in open(path):
        code = line.split("//")[0]
        if "clothU" in code and "fsiPorousWall" in code:
            words = code.replace("{", " ").replace("}", " ").replace(";", " ").split()
            get = lambda k, d=None: float(words[words.index(k) + 1]) if k in words else d
            return {"a": get("a"), "b": get("b"), "relaxation": get("relaxation", 1.0)}
    return None


def cloth_flow(case, t0):
    """Mean volume flux through the cloth (out of the `canopy` side, relative to the moving cloth) after t0."""
    q = all_parts(os.path.join(case, "postProcessing", "clothFlow"), "surfaceFieldValue.dat")
    times = sorted(q)
    return mean_over(times, [q[x][0] for x in times], t0)[0] if times else None


def remeshes(case, t, fz, skirt):
    """The new meshes of a remeshing run: number, time, reason, stage folder, the axial force's jump across it."""
    out = []
    for d in glob.glob(os.path.join(case, "structure", "remesh.*")):
        n = os.path.basename(d).split(".", 1)[1]
        req = os.path.join(d, "request")
        if not n.isdigit() or not os.path.exists(req):
            continue
        info = dict(line.rstrip("\n").split(" ", 1) for line in open(req) if " " in line)
        tr = float(info["time"])
        e = {"mesh": int(n), "time": tr, "reason": info.get("reason", ""), "stage": f"stage{n}",
             "stage_exists": os.path.isdir(os.path.join(case, f"stage{n}"))}
        # the windows ending at T (the old mesh's last) and the next one (the new mesh's first)
        k = next((i for i, x in enumerate(t) if abs(x - tr) <= 1e-6 * max(1.0, tr)), None)
        if k is not None and k + 1 < len(t) and fz[k]:
            e["force_before"], e["force_after"] = fz[k], fz[k + 1]
            e["force_jump"] = abs(fz[k + 1] - fz[k]) / abs(fz[k])
            steps = [abs(fz[i + 1] - fz[i]) / abs(fz[i]) for i in range(max(0, k - 10), k) if fz[i]]
            e["largest_step_before"] = max(steps) if steps else None
            before, after = fz[max(0, k - 9):k + 1], fz[k + 1:k + 11]
            e["force_mean_before"], e["force_mean_after"] = sum(before) / len(before), sum(after) / len(after)
            e["force_mean_change"] = e["force_mean_after"] / e["force_mean_before"] - 1
            e["skirt_radius_jump"] = abs(skirt[k + 1] - skirt[k])
        out.append(e)
    return sorted(out, key=lambda e: e["mesh"])


def main():
    case = sys.argv[1]
    import yaml

    ref = yaml.safe_load(open(os.path.join(case, "reference.yaml")))["round_canopy"]
    path = os.path.join(case, "summary.json")
    if not os.path.exists(path):
        print(f"round_canopy_summary.py: {path} is missing (summarize.py failed, above)", file=sys.stderr)
        return 1
    out = json.load(open(path))
    rows = coupling_rows(case)
    if not rows:
        print("round_canopy_summary.py: no windows in structure/coupling.csv", file=sys.stderr)
        return 1
    t = [float(r["time"]) for r in rows]
    col = lambda k: [float(r[k]) for r in rows]
    d0, u, rho = ref["nominal_diameter"], ref["speed"], ref["rho"]
    q, s0 = 0.5 * rho * u * u, math.pi * d0 * d0 / 4
    end = t[-1]
    t0 = end - ref["average_last"]
    fz = col("Fz_structure")
    cd0 = [f / (q * s0) for f in fz]
    ft, fr = frames_radius(case)
    dp = [2 * r / d0 for r in fr]
    # the projected area: the disc of the projected diameter
    ap = [math.pi * r * r for r in fr]
    cd_p = [f / (q * a) for f, a in zip(fz, (interp(ft, ap, x) for x in t))] if ft else [None] * len(t)
    rc = {"reynolds": u * d0 / ref["nu"], "speed": u, "q": q, "nominal_area": s0,
          "geometric_porosity": ref["vent_area"] / s0, "cloth_porosity": 0.0,
          "average_from": t0, "average_to": end, "windows_averaged": None}
    rc["remeshes"] = remeshes(case, t, fz, col("skirt_radius"))
    for e in rc["remeshes"]:
        jump = (f": the axial force {e['force_before']:.4g} -> {e['force_after']:.4g} N across it "
                f"({100 * e['force_jump']:.2g} %; the largest change between two windows before it "
                f"{100 * e['largest_step_before']:.2g} %), its mean over 10 windows {e['force_mean_before']:.4g} -> "
                f"{e['force_mean_after']:.4g} N ({100 * e['force_mean_change']:+.2g} %), the skirt radius "
                f"{1000 * e['skirt_radius_jump']:.2g} mm" if "force_jump" in e and e["largest_step_before"] is not None
                else "")
        print(f"new mesh {e['mesh']} at t = {e['time']:g} s ({e['reason']}), the case before it in {e['stage']}/{jump}")
    when = ", ".join(f"{e['time']:g}" for e in rc["remeshes"])
    print(f"new meshes: {len(rc['remeshes'])}" + (f" (at t = {when} s)" if when else
                                                  " (remeshing off, or the mesh followed the canopy to the end)"))
    results = out.setdefault("results", {})
    if t0 < ref["average_last"]:
        rc["note"] = f"the run ends at t = {end} s, too short to average over its last {ref['average_last']} s after as long a start: nothing measured"
        out["round_canopy"] = rc
        json.dump(out, open(path, "w"), indent=2)
        print(f"round canopy: {rc['note']}")
        return 0
    if not ft:
        print("round_canopy_summary.py: no canopy frames in structure/results.h5", file=sys.stderr)
        return 1
    m_cd0, sd_cd0, nw = mean_over(t, cd0, t0)
    m_dp, sd_dp, _ = mean_over(ft, dp, t0)
    m_cdp, _, _ = mean_over(t, cd_p, t0)
    m_ap, _, _ = mean_over(ft, ap, t0)
    blockage = 1 + 2.5 * m_cdp * m_ap / ref["section_area"]
    rc.update(windows_averaged=nw, C_D0=m_cd0, C_D0_std=sd_cd0, Dp_D0=m_dp, Dp_D0_std=sd_dp,
              C_D_projected_measured=m_cdp, maskell_factor=blockage, C_D_projected=m_cdp / blockage,
              C_D0_blockage_corrected=m_cd0 / blockage)
    # breathing / oscillation over the window
    sel = [i for i, a in enumerate(t) if a >= t0 - 1e-12]
    # a period only where the force does oscillate (more than 1 % RMS); below that the strongest Fourier
    # component of what is left (a slow drift) would name the window's length
    period = dominant_period([t[i] for i in sel], [fz[i] for i in sel]) if sd_cd0 > 0.01 * m_cd0 else None
    lat = [math.hypot(float(rows[i]["Fx_structure"]), float(rows[i]["Fy_structure"])) for i in sel]
    rc["breathing"] = {"axial_force_std_over_mean": sd_cd0 / m_cd0, "skirt_diameter_std_over_mean": sd_dp / m_dp,
                       "dominant_period": period,
                       "strouhal_on_Dp": (d0 * m_dp / (u * period)) if period else None,
                       "lateral_force_max_over_axial": max(lat) / (m_cd0 * q * s0)}
    # the confluence point's balance (Newton): its reaction + the fluid's axial force = 0 at rest
    m_r, _, _ = mean_over(t, col("confluence_force_z"), t0)
    m_f, _, _ = mean_over(t, fz, t0)
    bal = abs(m_r + m_f) / abs(m_f)
    rc["confluence_balance"] = {"reaction_z": m_r, "fluid_force_z": m_f, "relative_imbalance": bal,
                                "tolerance": ref["confluence_balance_tolerance"],
                                "within": bal <= ref["confluence_balance_tolerance"]}
    # the vent
    # the vent: the flux through its faces over their area (the opening as the mesh has it: its rim on the
    # cloth's vent edge); the structure's vent polygon (vent_area) for comparison
    vt, vu, vb, vq, va, vp = vent_series(case, ref)
    m_vu, _, _ = mean_over(vt, vu, t0)
    m_vb, _, _ = mean_over(vt, vb, t0)
    if m_vu is not None:
        m_vq, _, _ = mean_over(vt, vq, t0)
        m_va, _, _ = mean_over(vt, va, t0)
        rc["vent"] = {"axial_velocity": m_vu, "bernoulli_velocity": m_vb, "ratio": m_vu / m_vb if m_vb else None,
                      "measured_as": "volume flux through the faceZone vent over its area",
                      "flow_rate": m_vq, "zone_area": m_va, "zone_area_over_vent_area": m_va / ref["vent_area"],
                      "flux_over_vent_area": m_vq / ref["vent_area"],
                      "flow_over_mouth_flow": m_vq / (u * m_ap)}
        if all(x is not None for x in vp):
            m_vp, _, _ = mean_over(vt, vp, t0)
            rc["vent"]["fixed_plane_axial_velocity"] = m_vp
    porous = cloth_setting(case)
    flow = cloth_flow(case, t0)
    if porous is not None or flow:
        rc["cloth"] = dict(porous or {}, flow_rate=flow,
                           flow_over_mouth_flow=abs(flow) / (u * m_ap) if flow is not None else None)
    results["C_D_projected"] = entry(rc["C_D_projected"], end, ref["cd_projected"], end)
    results["C_D0_vs_flat_circular"] = entry(m_cd0, end, ref["cd0_flat_circular"], end)
    results["Dp_D0_vs_flat_circular"] = entry(m_dp, end, ref["dp_d0_flat_circular"], end)
    if "vent" in rc and rc["vent"]["ratio"] is not None:
        results["vent_velocity_ratio"] = entry(rc["vent"]["ratio"], end, ref["vent_velocity_ratio"], end)
    for name in ("C_D_projected", "C_D0_vs_flat_circular", "Dp_D0_vs_flat_circular", "vent_velocity_ratio"):
        e = results.get(name)
        if e is None:
            continue
        if e["check"]:
            out["all_checks_within_tolerance"] = bool(out["all_checks_within_tolerance"] and e["within"])
        elif not e["within"] and name not in out["reported_outside_range"]:
            out["reported_outside_range"].append(name)
    out["all_checks_within_tolerance"] = bool(out["all_checks_within_tolerance"] and rc["confluence_balance"]["within"])
    if "vent_velocity_ratio" not in results:
        out["all_checks_within_tolerance"] = False
    out["round_canopy"] = rc
    json.dump(out, open(path, "w"), indent=2)
    b = rc["breathing"]
    cloth = (f"porous cloth a = {porous['a']:g} 1/m, b = {porous['b']:g}" if porous else "cloth impermeable")
    print(f"round canopy (Re = {rc['reynolds']:.3g}, vent {100 * rc['geometric_porosity']:.2g} % of S0, {cloth}), "
          f"t = {t0:g} .. {end:g} s ({nw} windows):")
    print(f"  C_D0 = {m_cd0:.4g} (+- {sd_cd0:.2g}); D_p/D0 = {m_dp:.4g}; C_D on the projected area {m_cdp:.4g}, "
          f"blockage-corrected {rc['C_D_projected']:.4g} (rigid cup 1.33 .. 1.42): "
          f"{'PASS' if results['C_D_projected']['within'] else 'outside'}")
    print(f"  flat circular canopy [K]: C_D0 0.75 .. 0.80, D_p/D0 0.67 .. 0.70 (a hemispherical canopy: reported)")
    if "vent" in rc:
        v = rc["vent"]
        print(f"  vent: {v['axial_velocity']:.3g} m/s through it ({v['flow_rate']:.3g} m3/s over its faces' "
              f"{v['zone_area']:.3g} m2, {v['zone_area_over_vent_area']:.2g} of the vent polygon), Bernoulli "
              f"{v['bernoulli_velocity']:.3g} m/s, ratio {v['ratio']:.3g} (orifice 0.61 .. 1): "
              f"{'PASS' if results['vent_velocity_ratio']['within'] else 'outside'}; "
              f"{100 * v['flow_over_mouth_flow']:.2g} % of the flow the mouth faces")
    if rc.get("cloth", {}).get("flow_rate") is not None:
        print(f"  cloth: {abs(rc['cloth']['flow_rate']):.3g} m3/s through it, "
              f"{100 * rc['cloth']['flow_over_mouth_flow']:.2g} % of the flow the mouth faces")
    c = rc["confluence_balance"]
    print(f"  confluence: reaction {c['reaction_z']:.4g} N against the fluid's {c['fluid_force_z']:.4g} N, imbalance "
          f"{c['relative_imbalance']:.2g} (limit {c['tolerance']}): {'PASS' if c['within'] else 'outside'}")
    per = (f"{b['dominant_period']:.3g} s (St = {b['strouhal_on_Dp']:.3g})" if b["dominant_period"]
           else "none (steady within 1 %)")
    print(f"  breathing: axial force +- {100 * b['axial_force_std_over_mean']:.2g} %, skirt diameter +- "
          f"{100 * b['skirt_diameter_std_over_mean']:.2g} %, dominant period {per}, lateral force up to "
          f"{100 * b['lateral_force_max_over_axial']:.2g} % of the drag")
    plot(case, t, cd0, ft, dp, vt, vu, vb, t0, rc)
    return 0


def read_raw(path):
    pts = []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        pts.append([float(x) for x in line.split()])
    return pts


def plot(case, t, cd0, ft, dp, vt, vu, vb, t0, rc):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("  (no matplotlib: no plots)")
        return
    os.makedirs(os.path.join(case, "plots"), exist_ok=True)
    fig, ax = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
    ax[0].plot(t, cd0, lw=1)
    ax[0].axhspan(0.75, 0.80, color="0.85", label="flat circular canopy [Knacke]")
    ax[0].axvspan(t0, t[-1], color="C1", alpha=0.1, label="averaged")
    ax[0].set_ylabel("C_D0 = D / (q S0)")
    ax[0].set_ylim(0, 1.5)
    ax[0].legend(loc="upper right", fontsize=8)
    ax[1].plot(ft, dp, ".-", lw=1)
    ax[1].axhspan(0.67, 0.70, color="0.85")
    ax[1].set_ylabel("D_p / D0")
    if vt:
        ax[2].plot(vt, [a / b if b > 0 else float("nan") for a, b in zip(vu, vb)], lw=1)
        ax[2].axhspan(0.61, 1.0, color="0.85", label="orifice law")
        ax[2].set_ylim(0, 1.5)
        ax[2].legend(loc="upper right", fontsize=8)
    ax[2].set_ylabel("vent u / sqrt(2 dp/rho)")
    ax[2].set_xlabel("t [s]")
    fig.suptitle(f"round canopy, hemispherical, Re = {rc['reynolds']:.2g}: C_D0 {rc.get('C_D0', float('nan')):.3f}, "
                 f"D_p/D0 {rc.get('Dp_D0', float('nan')):.3f}", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(case, "plots", "round_canopy_history.png"), dpi=110)
    plt.close(fig)
    # the flow at the last time the surfaces were written
    dirs = sorted(glob.glob(os.path.join(case, "postProcessing", "surfaces", "*")), key=lambda d: float(os.path.basename(d)))
    if not dirs:
        return
    d = dirs[-1]
    files = {k: os.path.join(d, k) for k in ("p_canopyOut.raw", "p_canopyIn.raw", "U_midPlane.raw")}
    if not all(os.path.exists(f) for f in files.values()):
        return
    pout, pin, um = (read_raw(files[k]) for k in ("p_canopyOut.raw", "p_canopyIn.raw", "U_midPlane.raw"))
    u = rc["speed"]
    qk = 0.5 * u * u  # kinematic dynamic pressure U^2/2 (p is kinematic)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.6))
    ang = lambda p: math.degrees(math.atan2(math.hypot(p[0], p[1]), p[2]))
    ax[0].plot([ang(p) for p in pout], [p[3] / qk for p in pout], ".", ms=3, label="patch canopy")
    ax[0].plot([ang(p) for p in pin], [p[3] / qk for p in pin], ".", ms=3, label="patch canopy_slave")
    ax[0].set_xlabel("angle from the axis at the skirt centre [deg] (0: apex, 90: skirt)")
    ax[0].set_ylabel("(p - p_outlet) / (U^2 / 2)")
    ax[0].legend(fontsize=8)
    ax[0].set_title(f"pressure on both sides of the cloth, t = {os.path.basename(d)} s", fontsize=10)
    sel = [p for p in um if abs(p[0]) < 1.5 and -0.8 < p[2] < 2.0]
    import matplotlib.tri as mtri
    tri = mtri.Triangulation([p[0] for p in sel], [p[2] for p in sel])
    c = ax[1].tricontourf(tri, [p[5] / u for p in sel], levels=21, cmap="RdBu_r", vmin=-1.2, vmax=1.2)
    fig.colorbar(c, ax=ax[1], label="U_z / U")
    ax[1].plot([p[0] for p in pout if abs(p[1]) < 0.02], [p[2] for p in pout if abs(p[1]) < 0.02], "k.", ms=2)
    ax[1].set_xlim(-1.5, 1.5)
    ax[1].set_aspect("equal")
    ax[1].set_xlabel("x [m]")
    ax[1].set_ylabel("z [m] (the air blows along +z)")
    ax[1].set_title("axial velocity in the plane y = 0", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(case, "plots", "round_canopy_flow.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
