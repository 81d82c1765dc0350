#!/usr/bin/python3
"""ramair_wing.py (the coupled ram-air wing's summary) on a small generated canopy, in seconds, against
references that do not come from it:
  - the section angle of every rib of the design canopy equals the generator's incidence + twist |2 s / b|,
    with the structure's nodes renumbered (as the model does) and found back by position;
  - the canopy rolled rigidly about the free stream keeps every section angle; pitched nose-up by b about the
    span axis, the centre section's angle grows by b exactly;
  - the lines at the confluence point: as many per row as the generator's cascade makes (per half-span
    ceil(ribs / cascade) and one on the symmetry plane), left and right mirror images, every rib served once
    per row; the brake lines at the toggles (brake_points per side);
  - the projected area of the design skin equals ramair_fluid.py's of the generator's STL (another code path);
  - Helmbold's slope is ramair_fluid.py's formula; the elliptic distribution's cell means sum to its total;
  - the line drag of a single cable across the wind is 1/2 rho C_D d U^2 L;
  - the OpenFOAM readers: a zeroGradient patch takes its owner cells' values, a nonuniform list is read as
    written; a face's area vector and centre;
  - the error against the converged answer is stated for the inputs the convergence study ran and only for
    them (another settings value, another structure.yaml byte: no reference); a broken reference is refused.
Usage: test_ramair_wing.py CASES_COUPLED_DIR FSI_BINARY WORK_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, sys.argv[1])
import ramair_fluid  # noqa: E402
import ramair_wing  # noqa: E402

INCIDENCE, TWIST, CELLS, SPAN = 4.0, -2.0, 6, 3.0
SCENE = f"""\
title: a small canopy for test_ramair_wing.py
materials:
  fabric: {{type: membrane, young: 1.3e9, poisson: 0.3, thickness: 7.6e-5, density: 530}}
  line: {{type: cable, young: 4.3e10, area: 3.0e-6, density: 906}}
meshes:
  wing:
    generator: {{type: parafoil, span: {SPAN}, root_chord: 1.0, cells: {CELLS}, arc_radius: 3.0, section: NACA 4415,
                chordwise_points: 12, span_divisions: 2, incidence: {INCIDENCE}, twist: {TWIST}, bulge: 0.25,
                line_length: 1.0, rigging_angle: 13, brake_slack: 0.05}}
    material: fabric
    cable_material: line
constraints:
  - {{nodes: [wing/confluence, wing/toggle_left, wing/toggle_right], fix: all}}
effects:
  pressure: {{triangles: wing/skin, value: 61.0}}
  line_drag: {{lines: [wing/lines, wing/brakes], diameter: 2.0e-3, cd: 1.1, wind: [15, 0, 0], density: 1.2}}
time: {{end: 1.0e-3}}
"""

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def rot(axis, deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    if axis == "x":
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])  # about +y: +x turns towards -z, the nose (-x) up


def write_results(path, perm, ref, lines, tris, frames):
    """A results.h5 as the model writes it: nodes renumbered (model node perm[i] = mesh node i)."""
    import h5py
    n = len(ref)
    inv = np.empty(n, dtype=int)
    inv[perm] = np.arange(n)
    with h5py.File(path, "w") as f:
        f["mesh/lines"] = perm[lines].astype(np.int32)
        f["mesh/triangles"] = perm[tris].astype(np.int32)
        for k, (t, X, T) in enumerate(frames):
            g = f.create_group(f"steps/{k:06d}")
            g.attrs["time"] = t
            g["coordinates"] = X[inv]
            g["displacement"] = (X - ref)[inv]
            g["velocity"] = np.zeros((n, 3))
            g["cable_force"] = T


def main():
    cases, fsi, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "structure"))
    with open(os.path.join(work, "structure-coupled.yaml"), "w") as f:
        f.write(SCENE)
    r = subprocess.run([fsi, "generate", os.path.join(work, "structure-coupled.yaml"), "--out",
                        os.path.join(work, "constant", "structure")], capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        return 1
    msh = os.path.join(work, "constant", "structure", "wing.msh")
    pts, groups = ramair_wing.read_msh(msh)
    lines = np.array([e for e in {tuple(sorted(l)) for g in groups["line"].values() for l in g}])
    tris = np.array([t for t in {tuple(t) for g in groups["tri"].values() for t in g}])
    perm = np.random.default_rng(1).permutation(len(pts))
    conf = pts[groups["node"]["confluence"][0]]
    e_d = np.array([1.0, 0.0, 0.0])
    T = np.arange(len(lines), dtype=float) + 1.0
    rolled = (pts - conf) @ rot("x", 10.0).T + conf
    pitched = (pts - conf) @ rot("y", 3.0).T + conf
    h5 = os.path.join(work, "structure", "results.h5")
    write_results(h5, perm, pts, lines, tris, [(0.0, pts, T), (0.1, rolled, T), (0.2, pitched, T)])
    res = ramair_wing.Results(h5)
    canopy = ramair_wing.Canopy(msh, res)
    check(len(canopy.ribs) == CELLS + 1, f"{len(canopy.ribs)} ribs found, the generator makes {CELLS + 1}")

    design = ramair_wing.section_frames(res.field(0, "coordinates"), canopy, e_d)
    want = [INCIDENCE + TWIST * abs(2 * (-SPAN / 2 + i * SPAN / CELLS) / SPAN) for i in range(CELLS + 1)]
    worst = max(abs(f["alpha"] - a) for f, a in zip(design, want))
    check(worst < 1e-9, f"design section angles = incidence + twist |2s/b| (largest difference {worst:.1e} deg)")
    roll = ramair_wing.section_frames(res.field(1, "coordinates"), canopy, e_d)
    worst = max(abs(f["alpha"] - a) for f, a in zip(roll, want))
    check(worst < 1e-9, f"rolled 10 deg about the free stream: section angles unchanged ({worst:.1e} deg)")
    pitch = ramair_wing.section_frames(res.field(2, "coordinates"), canopy, e_d)
    c = CELLS // 2
    check(abs(pitch[c]["alpha"] - (want[c] + 3.0)) < 1e-9,
          f"pitched 3 deg nose-up: centre section {pitch[c]['alpha']:.12f} deg = {want[c] + 3.0} deg")
    check(all(p["alpha"] > d["alpha"] for p, d in zip(pitch, design)), "pitched nose-up: every section's angle grows")

    mains, attach, brakes = canopy.suspension()
    rows = sorted({m["row"] for m in mains})
    per_half = math.ceil((CELLS // 2) / 2)  # ribs 0..CELLS/2-1 on each half, cascade 2; the centre rib alone
    check(rows == ["A", "B", "C", "D"], f"rows at the confluence {rows}")
    for row in rows:
        ms = [m for m in mains if m["row"] == row]
        sides = sorted(m["side"] for m in ms)
        check(sides == ["centre"] + ["left"] * per_half + ["right"] * per_half, f"row {row}: sides {sides}")
        served = sorted(r for m in ms for r in m["ribs"])
        check(served == list(range(CELLS + 1)), f"row {row}: ribs served {served}")
        check(sorted(a["rib"] for a in attach if a["row"] == row) == list(range(CELLS + 1)),
              f"row {row}: one attachment line per rib")
    check(sorted(b["side"] for b in brakes) == ["left"] * 3 + ["right"] * 3, "three brake lines per toggle")
    check(sorted(b["rib"] for b in brakes) == [0, 1, 2, CELLS - 2, CELLS - 1, CELLS], "brakes at the outer ribs")

    # projected area: the design skin vs ramair_fluid.py's of the STL fsi generate wrote from the same set
    e_l = np.array([0.0, 0.0, 1.0])
    area = ramair_wing.projected_area(res.reference(), canopy.skin, e_l)
    stl = ramair_fluid.wing_geometry(ramair_fluid.read_stl(os.path.join(work, "constant", "structure", "wing.stl")),
                                     (0.0, 0.0, 1.0))
    check(abs(area / stl["projected_area"] - 1) < 1e-12,
          f"projected area {area:.9f} m^2 = the STL's {stl['projected_area']:.9f} m^2 (ramair_fluid.wing_geometry)")

    # Helmbold and the elliptic distribution
    ar = 3.05
    k = 2 * math.pi / (math.pi * ar)
    check(abs(ramair_wing.helmbold_slope(ar) - 2 * math.pi / (math.sqrt(1 + k * k) + k)) < 1e-15, "Helmbold slope")
    check(abs(ramair_wing.helmbold_slope(1e9) - 2 * math.pi) < 1e-6, "Helmbold slope -> 2 pi for a long wing")
    edges = np.linspace(-1.4, 1.6, 9)
    tot = sum(ramair_wing.elliptic_mean(100.0, 3.0, 0.1, a, b) * (b - a) for a, b in zip(edges[:-1], edges[1:]))
    check(abs(tot - 100.0) < 1e-9, f"elliptic cell means sum to the total ({tot:.12f})")

    # line drag of one cable across the wind: the model's 1/2 rho C_D d U^2 L
    class One:
        lines = np.array([[0, 1]])

        def field(self, i, name):
            return np.array([[0.0, 0, 0], [0, 0, 2.0]]) if name == "coordinates" else np.zeros((2, 3))

    f = ramair_wing.line_drag((0.5 * 1.2 * 1.1 * 2e-3, np.array([15.0, 0, 0]), np.array([0])), One(), 0)
    check(np.allclose(f, [0.5 * 1.2 * 1.1 * 2e-3 * 15 ** 2 * 2.0, 0, 0], rtol=1e-14, atol=0),
          f"line drag of a 2 m cable across 15 m/s: {f[0]:.6f} N")
    model = ramair_wing.line_drag_model(work, canopy)
    check(len(model[2]) == len(lines), f"line_drag sets of the scene: {len(model[2])} of {len(lines)} cables")

    # OpenFOAM readers
    fld = os.path.join(work, "p")
    with open(fld, "w") as fo:
        fo.write("FoamFile { class volScalarField; }\ninternalField nonuniform List<scalar> \n4\n(\n1\n2\n3\n4\n)\n;\n"
                 "boundaryField\n{\n    farfield { type fixedValue; value uniform 0; }\n"
                 "    wing\n    {\n        type            zeroGradient;\n    }\n}\n")
    v = ramair_wing.read_patch_field(fld, "wing", 3, np.array([3, 0, 2]))
    check(v.tolist() == [4.0, 1.0, 3.0], f"zeroGradient patch takes its owner cells' values: {v.tolist()}")
    with open(fld, "w") as fo:
        fo.write("FoamFile { class volVectorField; }\ninternalField uniform (0 0 0);\nboundaryField\n{\n"
                 "    wing\n    {\n        type calculated;\n        value nonuniform List<vector> \n2\n(\n(1 2 3)\n(4 5 6)\n)\n;\n"
                 "    }\n}\n")
    v = ramair_wing.read_patch_field(fld, "wing", 2)
    check(v.tolist() == [[1, 2, 3], [4, 5, 6]], "nonuniform vector list read")
    try:
        ramair_wing.read_patch_field(fld, "wing", 3)
        check(False, "a patch list of the wrong length is refused")
    except ramair_wing.InputError as e:
        check("2 values" in str(e) and fld in str(e), f"a patch list of the wrong length is refused: {e}")
    cen, area = ramair_wing.face_geometry(np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]]), [[0, 1, 2, 3]])
    check(np.allclose(area[0], [0, 0, 2]) and np.allclose(cen[0], [1, 0.5, 0]), "face area vector and centre")
    try:
        ramair_wing.read_msh(os.path.join(work, "missing.msh"))
        check(False, "a missing mesh is refused")
    except ramair_wing.InputError as e:
        check("missing.msh" in str(e), f"a missing mesh is refused naming it")
    converged_reference(work)
    print(json.dumps({"failures": len(failures)}))
    return 1 if failures else 0


def converged_reference(work):
    """The summary's error against the converged answer: stated only for the inputs the study ran."""
    import hashlib
    case = os.path.join(work, "ref-case")
    os.makedirs(case, exist_ok=True)
    with open(os.path.join(case, "structure.yaml"), "w") as f:
        f.write(SCENE)
    sha = hashlib.sha256(SCENE.encode()).hexdigest()
    ref = os.path.join(work, "ramair_convergence.json")
    conv = {"CL": {"extrapolated": 0.5, "error_bar": 0.01}, "alpha_centre_deg": {"extrapolated": 3.0, "error_bar": 0.2}}
    with open(ref, "w") as f:
        json.dump({"commit": "abc", "converged": conv,
                   "main_job_inputs": {"structure_yaml_sha256": sha, "settings": {"speed": 15.0}}}, f)
    w = {"coefficients": {"design_area": {"CL_canopy": 0.55, "CD_canopy": 0.1, "CD_system": 0.15}},
         "section_alpha": {"centre_deg": 2.5, "span_average_deg": 4.0}}
    r = ramair_wing.converged_reference(case, {"settings": {"speed": 15.0}}, w, ref)
    check(r["available"] and abs(r["CL"]["relative"] - 0.1) < 1e-12 and abs(r["alpha_centre_deg"]["error"] + 0.5) < 1e-12
          and "CD" not in r, f"the main job's inputs: CL +10 % and the centre angle -0.5 deg against the reference")
    line = ramair_wing.converged_lines(r)[0]
    check("+10.0 %" in line and "-0.50 deg" in line, f"the summary's line states them: {line.strip()}")
    r = ramair_wing.converged_reference(case, {"settings": {"speed": 15.0, "wall_split": 0}}, w, ref)
    check(r["available"], "a setting the study did not record, at its default, changes nothing")
    r = ramair_wing.converged_reference(case, {"settings": {"speed": 15.0, "wall_split": 1}}, w, ref)
    check(not r["available"], "the same setting away from its default: no reference")
    r = ramair_wing.converged_reference(case, {"settings": {"speed": 12.0}}, w, ref)
    check(not r["available"] and "settings" in r["why"], f"other settings: no reference ({r['why']})")
    with open(os.path.join(case, "structure.yaml"), "a") as f:
        f.write("# a comment is a change\n")
    r = ramair_wing.converged_reference(case, {"settings": {"speed": 15.0}}, w, ref)
    check(not r["available"] and "structure.yaml" in r["why"], "another structure.yaml: no reference")
    with open(ref, "w") as f:
        f.write("{not json")
    try:
        ramair_wing.converged_reference(case, {"settings": {"speed": 15.0}}, w, ref)
        check(False, "a broken reference file is refused")
    except ramair_wing.InputError as e:
        check(ref in str(e), f"a broken reference file is refused naming it: {e}")


if __name__ == "__main__":
    sys.exit(main())
