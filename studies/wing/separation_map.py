#!/usr/bin/python3
"""Where the flow leaves the wing: the upper skin of finished rigid-wing runs (studies/wing/wing_polar.py cases),
coloured by the wall shear stress along the free stream (negative: reversed flow, the separated region) and by
Cp, seen from above. For rung 2 of docs/AERODYNAMICS.md: the arced wing with flat panels beside the one with
bulged cells, at the same angle.

  /usr/bin/python3 studies/wing/separation_map.py CASE [CASE ...] --png docs/img/wing_separation.png

Each CASE is a finished run folder (its last time holds U, p; the wall shear stress is computed here by the
case's own solver with -postProcess -func wallShearStress -latestTime, if the time holds none). Needs the
OpenFOAM environment (WM_PROJECT_DIR) as the case's Allrun does; reads ASCII fields and polyMesh.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent.parent / "cases/coupled"))
import ramair_fluid  # noqa: E402  (the polyMesh patch reader)


def latest_time(case):
    times = [d for d in os.listdir(case) if ramair_fluid.NUMBER.match(d) and float(d) > 0]
    if not times:
        sys.exit(f"separation_map: {case} has no time folder after 0")
    return max(times, key=float)


def boundary_values(path, patch):
    """The values of a field's patch entry (nonuniform List<scalar|vector>, or uniform)."""
    text = Path(path).read_text()
    m = re.search(r"\b" + re.escape(patch) + r"\s*\{", text[text.index("boundaryField"):])
    if not m:
        sys.exit(f"separation_map: {path}: no boundary entry '{patch}'")
    start = text.index("boundaryField") + m.end()
    body = text[start:]
    v = re.search(r"value\s+(nonuniform\s+List<(\w+)>\s*(\d+)\s*\(|uniform\s+)", body)
    if not v:
        sys.exit(f"separation_map: {path}: '{patch}' has no value")
    if v.group(1).startswith("uniform"):
        return None
    kind, n = v.group(2), int(v.group(3))
    rest = body[v.end():]
    if kind == "vector":
        vals = re.findall(r"\(([^()]+)\)", rest)[:n]
        return [tuple(map(float, x.split())) for x in vals]
    return [float(x) for x in rest.split(")")[0].split()[:n]]


def wall_pressure(case, time):
    """p on the wing's faces: zeroGradient there, so the owner cells' values (a zeroGradient patch writes none)."""
    text = Path(case, time, "p").read_text()
    m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\(", text)
    if not m:
        sys.exit(f"separation_map: {case}/{time}/p: no nonuniform internal field (ASCII expected)")
    cells = [float(x) for x in text[m.end():].split(")")[0].split()]
    start, n, _, _ = ramair_fluid._patch_range(os.path.join(case, "constant", "polyMesh"), "wing")
    own = Path(case, "constant/polyMesh/owner").read_text()
    count, pos = ramair_fluid._foam_list(own, own.index("}") if "FoamFile" in own else 0)
    owner = own[pos:].split(")")[0].split()
    return [cells[int(owner[f])] for f in range(start, start + n)]


def face_geometry(case, time):
    """Face centres and area vectors of the wing patch (the mesh of `time` if it moved, else constant/)."""
    pts, faces, start, n = ramair_fluid.read_patch(case, "wing")
    out = []
    for fi in range(start, start + n):
        ids = [int(i) for i in faces[fi].split()]
        p0 = pts[ids[0]]
        cx = [sum(pts[i][k] for i in ids) / len(ids) for k in range(3)]
        sv = [0.0, 0.0, 0.0]
        for i in range(1, len(ids) - 1):
            cr = ramair_fluid._cross(ramair_fluid._sub(pts[ids[i]], p0), ramair_fluid._sub(pts[ids[i + 1]], p0))
            sv = [sv[k] + 0.5 * cr[k] for k in range(3)]
        out.append((cx, sv))
    return out


def load(case):
    case = str(case)
    t = latest_time(case)
    rec = json.loads(Path(case, "constant/fluidSettings.json").read_text())
    if not Path(case, t, "wallShearStress").exists():
        app = "simpleFoam" if rec["settings"].get("solver") == "simple" else "pimpleFoam"
        with open(Path(case, "log.wallShearStress"), "w") as log:
            rc = subprocess.run([app, "-postProcess", "-func", "wallShearStress", "-latestTime"], cwd=case,
                                stdout=log, stderr=subprocess.STDOUT).returncode
        if rc != 0:
            sys.exit(f"separation_map: {app} -postProcess failed in {case} (log.wallShearStress)")
    tau = boundary_values(Path(case, t, "wallShearStress"), "wing")
    p = wall_pressure(case, t)
    geo = face_geometry(case, t)
    d = rec["derived"]
    flow = d["flow_dir"]
    q_kin = 0.5 * rec["settings"]["speed"] ** 2  # p is kinematic
    faces = []
    for (c, sv), tw, pv in zip(geo, tau, p):
        # the patch normal points out of the fluid, into the wing: the upper skin's faces point down. OpenFOAM's
        # wallShearStress is the stress on the fluid (it points against the flow where the flow is attached):
        # its negative is the fluid's drag on the skin, along the stream where the flow is attached
        a = math.sqrt(sum(x * x for x in sv))
        nz = sv[2] / a
        faces.append({"x": c[0], "y": c[1], "z": c[2], "upper": nz < -0.3, "tau_flow": -sum(tw[k] * flow[k] for k in range(3)),
                      "cp": pv / q_kin, "area": a})
    return rec, faces


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--png", required=True)
    ap.add_argument("--labels", help="titles separated by semicolons, one per case")
    a = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = a.labels.split(";") if a.labels else [str(c) for c in a.cases]
    if len(labels) != len(a.cases):
        ap.error("--labels: one title per case")
    fig, ax = plt.subplots(2, len(a.cases), figsize=(5.2 * len(a.cases), 8.5), squeeze=False)
    for j, case in enumerate(a.cases):
        rec, faces = load(case)
        up = [f for f in faces if f["upper"]]
        sep = sum(f["area"] for f in up if f["tau_flow"] < 0) / sum(f["area"] for f in up)
        xs, ys = [f["y"] for f in up], [f["x"] for f in up]
        tmax = max(abs(f["tau_flow"]) for f in up)
        s0 = ax[0][j].scatter(xs, ys, c=[f["tau_flow"] for f in up], s=4, cmap="RdBu", vmin=-0.3 * tmax, vmax=0.3 * tmax)
        ax[0][j].set_title(f"{labels[j]}\nupper skin: wall shear along the stream\n(red: reversed flow, "
                           f"{100 * sep:.0f} % of the upper skin)", fontsize=9)
        s1 = ax[1][j].scatter(xs, ys, c=[f["cp"] for f in up], s=4, cmap="viridis", vmin=-2.5, vmax=0.5)
        ax[1][j].set_title("upper skin: Cp", fontsize=9)
        for k, s in ((0, s0), (1, s1)):
            ax[k][j].set_xlabel("y [m] (half wing, symmetry plane at 0)")
            ax[k][j].set_ylabel("x [m] (stream ->)")
            ax[k][j].invert_yaxis()
            ax[k][j].set_aspect("equal")
            fig.colorbar(s, ax=ax[k][j], shrink=0.7)
        print(f"{case}: reversed flow on {100 * sep:.1f} % of the upper skin")
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print(f"separation_map: {a.png}")


if __name__ == "__main__":
    main()
