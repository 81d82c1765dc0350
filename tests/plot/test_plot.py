#!/usr/bin/python3
"""ctest for `fsi plot` (label plot). Usage: test_plot.py MODE FSI WORK_DIR
  structure  a short structure run (tests/plot/scene.yaml): the PNGs exist and are images, and index.json's
             point counts are the rows of the tables in results.h5 and the mesh sizes
  relaxation a dynamic-relaxation run: the convergence plot has the rows of /tables/residual
  coupled    a coupled case folder made here: coupling.csv with a '#' restart note (and rows the restart
             replaces), structure/results.h5 from a structure run; counts, restart time, superseded rows
  errors     exit code 2 and a message naming what is missing, for folders that are not runs
Prints 'N passed, N failed' and exits 1 on any failure.
"""

import json
import os
import shutil
import struct
import subprocess
import sys

import h5py

HERE = os.path.dirname(os.path.abspath(__file__))
MODE, FSI, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
passed, failed = 0, 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print(f"FAIL: {what}")


def run(*args):
    p = subprocess.run([FSI, *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def structure_run(out, scene="scene.yaml"):
    rc, so, se = run("run", os.path.join(HERE, scene), "--out", out, "--quiet")
    if rc != 0:
        print(so, se)
        sys.exit(f"fsi run {scene} failed with {rc}")


def png_size(path):
    """(width, height) from the PNG signature and IHDR chunk; None if the file is not a PNG."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def check_pngs(plots_dir, index, expected_files):
    files = [p["file"] for p in index["plots"]]
    check(sorted(files) == sorted(expected_files), f"plots {files}, expected {expected_files}")
    for name in expected_files:
        path = os.path.join(plots_dir, name)
        if not os.path.isfile(path):
            check(False, f"{path} missing")
            continue
        size = png_size(path)
        check(size is not None, f"{path} is not a PNG")
        check(os.path.getsize(path) > 20_000, f"{path}: {os.path.getsize(path)} bytes, expected a real plot")
        if size:
            check(size[0] >= 700 and size[1] >= 500, f"{path}: {size[0]} x {size[1]} pixels")


def series(index, file):
    for p in index["plots"]:
        if p["file"] == file:
            return {s["name"]: s["points"] for s in p["series"]}
    check(False, f"{file} not in index.json")
    return {}


def load_index(plots_dir):
    path = os.path.join(plots_dir, "index.json")
    if not os.path.isfile(path):
        check(False, f"{path} not written")
        return {"kind": None, "plots": []}
    with open(path) as f:
        return json.load(f)


def test_structure():
    run_dir = os.path.join(WORK, "run")
    structure_run(run_dir)
    rc, so, se = run("plot", run_dir)
    check(rc == 0, f"fsi plot exit {rc}: {se}")
    plots = os.path.join(run_dir, "plots")
    index = load_index(plots)
    check(index["kind"] == "structure", f"kind {index['kind']}")
    if rc != 0:
        return
    check_pngs(plots, index, ["energy.png", "probes.png", "structure.png"])
    with h5py.File(os.path.join(run_dir, "results.h5"), "r") as h5:
        energy_rows = len(h5["tables/energy/time"])
        probe_rows = len(h5["tables/probes/time"])
        probe_names = sorted(k for k in h5["tables/probes"].keys() if k != "time")
        triangles = h5["mesh/triangles"].shape[0]
        lines = h5["mesh/lines"].shape[0]
        last = sorted(h5["steps"].keys())[-1]
    check(energy_rows > 20, f"the test run should monitor often: {energy_rows} energy rows")
    e = series(index, "energy.png")
    for name in ("kinetic", "strain", "external_work", "internal_work", "dissipation", "balance_error"):
        check(e.get(name) == energy_rows, f"energy series {name}: {e.get(name)} points, table has {energy_rows}")
    p = series(index, "probes.png")
    check(sorted(p) == probe_names, f"probe series {sorted(p)}, table columns {probe_names}")
    for name in probe_names:
        check(p[name] == probe_rows, f"probe {name}: {p[name]} points, table has {probe_rows}")
    s = series(index, "structure.png")
    check(s == {"triangles": triangles, "cables": lines}, f"structure series {s}, mesh {triangles}/{lines}")
    picture = next(x for x in index["plots"] if x["file"] == "structure.png")
    check(picture["frame"] == last, f"picture of frame {picture['frame']}, last is {last}")
    check(picture["color"] == "major principal stress", f"colour {picture['color']}")
    # --out and --color
    other = os.path.join(WORK, "elsewhere")
    rc, so, se = run("plot", run_dir, "--out", other, "--color", "displacement")
    check(rc == 0, f"fsi plot --out exit {rc}: {se}")
    index2 = load_index(other)
    check_pngs(other, index2, ["energy.png", "probes.png", "structure.png"])
    colour = next(x for x in index2["plots"] if x["file"] == "structure.png")["color"]
    check(colour == "displacement magnitude", f"--color displacement gave {colour}")
    # A killed run has frames but no tables (they are written at its end): the picture only, and a warning.
    killed = os.path.join(WORK, "killed")
    os.makedirs(killed)
    shutil.copy(os.path.join(run_dir, "results.h5"), killed)
    with h5py.File(os.path.join(killed, "results.h5"), "a") as h5:
        del h5["tables"]
    rc, so, se = run("plot", killed)
    check(rc == 0 and "no /tables/energy" in se and "summary.json not found" in se, f"killed run: exit {rc}, {se}")
    check([p["file"] for p in load_index(os.path.join(killed, "plots"))["plots"]] == ["structure.png"],
          "killed run: the picture only")
    rc, so, se = run("plot", run_dir, "--color", "pink")
    check(rc == 2 and "pink" in se, f"--color pink: exit {rc}, {se}")


def test_relaxation():
    run_dir = os.path.join(WORK, "run")
    structure_run(run_dir, "scene-dr.yaml")
    rc, so, se = run("plot", run_dir)
    check(rc == 0, f"fsi plot exit {rc}: {se}")
    plots = os.path.join(run_dir, "plots")
    index = load_index(plots)
    check_pngs(plots, index, ["relaxation.png", "structure.png"])
    with h5py.File(os.path.join(run_dir, "results.h5"), "r") as h5:
        rows = len(h5["tables/residual/iteration"])
    r = series(index, "relaxation.png")
    check(rows > 1 and r == {"residual_ratio": rows, "energy_ratio": rows}, f"relaxation series {r}, rows {rows}")


def test_coupled():
    run_dir = os.path.join(WORK, "run")
    structure_run(run_dir)
    case = os.path.join(WORK, "case")
    os.makedirs(os.path.join(case, "structure"))
    os.makedirs(os.path.join(case, "system"))
    shutil.copy(os.path.join(run_dir, "results.h5"), os.path.join(case, "structure", "results.h5"))
    shutil.copy(os.path.join(HERE, "scene.yaml"), os.path.join(case, "structure.yaml"))
    with open(os.path.join(case, "system", "controlDict"), "w") as f:
        f.write('functions { fsi { type fsiCoupling; scene "structure.yaml"; patches (bottom); } }\n')
    header = ("time,iterations,converged,residual,Fx_fluid,Fy_fluid,Fz_fluid,Fx_structure,Fy_structure,"
              "Fz_structure,center_z,rim_reaction_z")
    rows = []
    # First run: windows 1..10 (t = 0.1 .. 1.0); then a restart from t = 0.6 that recomputes 0.7 .. 1.5.
    for k in range(1, 11):
        rows.append(f"{0.1 * k:.12g},{3 + k % 2},1,{10.0 ** -(4 + k % 3)},{k},0,{-k},{k},0,{-k},{0.01 * k},{-k}")
    rows.append("# restart from t = 0.6 (0.6/uniform/fsiStructure.h5)")
    rows.append(header)  # a restarted run may repeat the header
    for k in range(7, 16):
        rows.append(f"{0.1 * k:.12g},{40 if k == 9 else 2},{0 if k == 9 else 1},1e-3,{k},1,{-k},{k},1,{-k},"
                    f"{0.02 * k},{-2 * k}")
    with open(os.path.join(case, "structure", "coupling.csv"), "w") as f:  # other comments are just skipped
        f.write("# coupling log\n" + header + "\n# forces in N\n" + "\n".join(rows) + "\n")
    with open(os.path.join(case, "structure", "timing.json"), "w") as f:
        json.dump({"wall_seconds": 12.5, "windows": 15, "mean_iterations": 3.2}, f)
    rc, so, se = run("plot", case)
    check(rc == 0, f"fsi plot exit {rc}: {se}")
    plots = os.path.join(case, "plots")
    index = load_index(plots)
    check(index["kind"] == "coupled", f"kind {index['kind']}")
    check_pngs(plots, index, ["interface_force.png", "iterations.png", "probes.png", "structure.png"])
    windows = 6 + 9  # t = 0.1 .. 0.6 of the first run, 0.7 .. 1.5 of the restarted one
    f = series(index, "interface_force.png")
    for c in "xyz":
        for side in ("fluid", "structure"):
            check(f.get(f"F{c}_{side}") == windows, f"F{c}_{side}: {f.get(f'F{c}_{side}')} points, expected {windows}")
    it = series(index, "iterations.png")
    check(it == {"iterations": windows, "residual": windows}, f"iteration series {it}")
    p = series(index, "probes.png")
    check(p == {"center_z": windows, "rim_reaction_z": windows}, f"probe series {p}")
    restarts = index.get("restarts", [])
    check(len(restarts) == 1 and abs(restarts[0]["time"] - 0.6) < 1e-12, f"restarts {restarts}")
    with h5py.File(os.path.join(case, "structure", "results.h5"), "r") as h5:
        triangles = h5["mesh/triangles"].shape[0]
    check(series(index, "structure.png").get("triangles") == triangles, "structure picture triangles")
    # A log cut short in the middle of a line (a killed run): that line is skipped with a warning.
    with open(os.path.join(case, "structure", "coupling.csv"), "a") as f:
        f.write("1.6,2,1,1e-3,16")
    rc, so, se = run("plot", case, "--out", os.path.join(WORK, "cut"))
    check(rc == 0 and "coupling.csv:25: incomplete last line" in se, f"cut log: exit {rc}, {se}")
    check(series(load_index(os.path.join(WORK, "cut")), "iterations.png").get("iterations") == windows,
          "cut log: the incomplete line is not plotted")
    # A coupled case without the structure results still gets its time series (and says what is missing).
    os.remove(os.path.join(case, "structure", "results.h5"))
    rc, so, se = run("plot", case, "--out", os.path.join(WORK, "no-h5"))
    check(rc == 0 and "results.h5 not found" in se, f"without results.h5: exit {rc}, {se}")
    check(len(load_index(os.path.join(WORK, "no-h5"))["plots"]) == 3, "three plots without results.h5")


def test_errors():
    empty = os.path.join(WORK, "empty")
    os.makedirs(empty)
    rc, so, se = run("plot", empty)
    check(rc == 2, f"empty folder: exit {rc}")
    for word in (empty, "neither", "results.h5", "coupling.csv"):
        check(word in se, f"empty folder: message lacks '{word}': {se}")
    rc, so, se = run("plot", os.path.join(WORK, "nowhere"))
    check(rc == 2 and "nowhere" in se and "no such folder" in se, f"missing folder: exit {rc}, {se}")
    # A case folder whose structure/ has results but no coupling log.
    case = os.path.join(WORK, "case")
    os.makedirs(os.path.join(case, "structure"))
    open(os.path.join(case, "structure", "results.h5"), "w").close()
    rc, so, se = run("plot", case)
    check(rc == 2 and os.path.join(case, "structure", "coupling.csv") in se, f"no coupling.csv: exit {rc}, {se}")
    # A malformed coupling log: the file, the line and the column are named.
    csv = os.path.join(case, "structure", "coupling.csv")
    with open(csv, "w") as f:
        f.write("time,iterations,converged,residual,Fx_fluid,Fy_fluid,Fz_fluid,Fx_structure,Fy_structure,"
                "Fz_structure\n0.1,2,1,1e-5,1,2,3,1,2,3\n0.2,2,1,oops,1,2,3,1,2,3\n0.3,2,1,1e-5,1,2,3\n")
    rc, so, se = run("plot", case)
    check(rc == 2 and f"{csv}:3" in se and "residual" in se and "oops" in se, f"bad number: exit {rc}, {se}")
    with open(csv, "w") as f:
        f.write("t,F\n0.1,2\n")
    rc, so, se = run("plot", case)
    check(rc == 2 and f"{csv}:1" in se and "header" in se, f"bad header: exit {rc}, {se}")
    # A results.h5 that is not HDF5.
    bad = os.path.join(WORK, "bad")
    os.makedirs(bad)
    with open(os.path.join(bad, "results.h5"), "w") as f:
        f.write("not hdf5")
    rc, so, se = run("plot", bad)
    check(rc == 2 and os.path.join(bad, "results.h5") in se and "HDF5" in se, f"not HDF5: exit {rc}, {se}")
    # An fsi without its share/fsi/fsi_plot.py (a partial installation) says where it looked.
    lonely = os.path.join(WORK, "lonely", "bin")
    os.makedirs(lonely)
    shutil.copy(FSI, lonely)
    p = subprocess.run([os.path.join(lonely, os.path.basename(FSI)), "plot", empty], capture_output=True, text=True)
    expected = os.path.join(WORK, "lonely", "share", "fsi", "fsi_plot.py")
    check(p.returncode == 1 and expected in p.stderr, f"without the script: exit {p.returncode}, {p.stderr}")


if __name__ == "__main__":
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    {"structure": test_structure, "relaxation": test_relaxation, "coupled": test_coupled,
     "errors": test_errors}[MODE]()
    print(f"{passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)
