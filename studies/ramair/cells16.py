#!/usr/bin/python3
"""The main job with the canopy design study's 16 cells (docs/AERODYNAMICS.md, "Canopy design"): a copy of
cases/coupled/ramair-kt run with ./Allrun.parallel and coupled.settings unchanged, structure.yaml with
`cells: 16` (the cut, lines, rig and everything else the main job's), beside the main job's own row of
docs/data/ramair_convergence.json (s1: the 8-cell canopy on the same fluid mesh and settings).

  /usr/bin/python3 studies/ramair/cells16.py [--out DIR] [--collect]

Writes docs/data/ramair_cells16.json. About 10 min on an idle 2-core machine (48 min loaded to 4-9)."""
import argparse
import datetime
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "studies/common"))
from case_variants import run_copy  # noqa: E402
from provenance import git_commit, machine  # noqa: E402
CASE = ROOT / "cases/coupled/ramair-kt"
ENV = ROOT / "build/share/fsi/fsi-env.sh"


def row(summary):
    s = json.loads(Path(summary).read_text())
    w = s["wing"]
    co = w["coefficients"]
    return {"CL_design_area": co["design_area"]["CL_canopy"], "CD_canopy_design_area": co["design_area"]["CD_canopy"],
            "CD_system_design_area": co["design_area"]["CD_system"], "CL_loaded_area": co["deformed_area"]["CL_canopy"],
            "loaded_area_m2": co["deformed_area"]["area_m2"], "design_area_m2": co["design_area"]["area_m2"],
            "L_over_D_canopy": co["L_over_D_canopy"], "L_over_D_system": co["L_over_D_system"],
            "section_alpha": w["section_alpha"], "trim": w["trim"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=str(ROOT / "studies-out/c16"))
    ap.add_argument("--collect", action="store_true", help="read the finished run in OUT/coarse")
    a = ap.parse_args()
    d = Path(a.out) / "coarse"
    if not a.collect:
        rc = run_copy(CASE, d, {}, {"cells": 16}, ENV)
        if rc != 0:
            sys.exit(f"cells16: the run failed (exit {rc}); see {d}/Allrun.out")
    r = row(d / "summary.json")
    r["wall_s"] = float((d / "wall_seconds").read_text()) if (d / "wall_seconds").exists() else None
    conv = json.loads((ROOT / "docs/data/ramair_convergence.json").read_text())
    main_job = next(x for x in conv["levels"] if x["run"] == "s1")
    out = {"what": "the main job (coupled.settings, coarse fluid mesh, wall functions) with 16 cells instead of 8",
           "command": "/usr/bin/python3 studies/ramair/cells16.py", "machine": machine(), "commit": git_commit(),
           "date": datetime.date.today().isoformat(), "cells16": r,
           "main_job_8_cells": {k: main_job.get(k) for k in ("CL", "CD", "alpha_centre_deg", "trim_reached", "wall_s")},
           "main_job_is": "docs/data/ramair_convergence.json row s1 (CL and CD of the canopy on the design area)"}
    (ROOT / "docs/data/ramair_cells16.json").write_text(json.dumps(out, indent=1) + "\n")
    print(json.dumps(r["trim"], indent=1))


if __name__ == "__main__":
    main()
