#!/usr/bin/env python3
"""CI-size check of studies/ramair/cells16.py (the coupled main job with 16 cells, docs/AERODYNAMICS.md "Canopy
design"). Its runs take 10-50 min each, so the check is of what the study stands on and what it committed:

  settings   every run variant's settings (coupled.settings with the variant's changes, cells16.py RUNS) pass
             the ram-air settings validator (ramair_settings.read_settings), so the command in the docs runs as
             written on the case as it is now
  committed  docs/data/ramair_cells16.json has a row for every variant run so far, each with trim_reached,
             and each finished row with its coefficients; the main job's row it compares with is
             docs/data/ramair_convergence.json's s1 as committed
  docs       the numbers docs/AERODYNAMICS.md quotes for the runs (CL and CD on the design area, the centre
             section's angle) are the committed data's, rounded as printed
  brake      the symmetric brake's run (both toggles a quarter chord, layered wall) against the same run
             without brakes, both trimmed: CL and CD of the canopy higher, and the span-averaged section angle
             higher (what a parafoil's symmetric brake does; issue 34)
Usage: test_cells16.py SOURCE_DIR
"""
import json
import os
import sys
import tempfile


def main(src):
    sys.path.insert(0, os.path.join(src, "studies", "common"))
    sys.path.insert(0, os.path.join(src, "cases", "coupled"))
    sys.path.insert(0, os.path.join(src, "studies", "ramair"))
    from case_variants import settings_with
    import ramair_settings
    import cells16
    bad = []
    base = open(os.path.join(src, "cases", "coupled", "ramair-kt", "coupled.settings")).read()
    for name, changes in cells16.RUNS.items():
        path = os.path.join(tempfile.mkdtemp(prefix="cells16-"), f"{name}.settings")
        with open(path, "w") as f:
            f.write(settings_with(base, changes))
        try:
            s = ramair_settings.read_settings(path)
        except ramair_settings.InputError as e:
            bad.append(f"run {name}: its settings are refused: {e}")
            continue
        for k, v in changes.items():
            if s[k] != v:
                bad.append(f"run {name}: {k} reads {s[k]!r}, the study sets {v!r}")
    data = json.load(open(os.path.join(src, "docs", "data", "ramair_cells16.json")))
    conv = json.load(open(os.path.join(src, "docs", "data", "ramair_convergence.json")))
    s1 = next(r for r in conv["levels"] if r["run"] == "s1")
    if data["main_job_8_cells"]["CL"] != s1.get("CL"):
        bad.append(f"main_job_8_cells CL {data['main_job_8_cells']['CL']} is not ramair_convergence.json's s1 "
                   f"{s1.get('CL')}")
    doc = open(os.path.join(src, "docs", "AERODYNAMICS.md")).read()
    for name, key in cells16.KEYS.items():
        row = data.get(key)
        if row is None:
            print(f"{name}: not run yet (no row {key})")
            continue
        if "trim_reached" not in row.get("trim", row):
            bad.append(f"{key}: no trim_reached")
        if "CL_design_area" not in row:
            print(f"{name}: stopped ({row.get('stopped')})")
            continue
        quoted = {"CL": f"{row['CL_design_area']:.3f}", "CD": f"{row['CD_canopy_design_area']:.3f}",
                  "alpha": f"{row['section_alpha']['centre_deg']:.1f}°"}
        for what, text in quoted.items():
            if text not in doc:
                bad.append(f"{key}: docs/AERODYNAMICS.md does not quote its {what} {text}")
        print(f"{name}: CL {quoted['CL']}, CD {quoted['CD']}, centre alpha {quoted['alpha']}, "
              f"trim reached {row['trim']['trim_reached']}")
    off, on = data.get("cells16_layers"), data.get("cells16_layers_symmetric_brake")
    if off and on and "CL_design_area" in off and "CL_design_area" in on:
        for what, key in (("CL", "CL_design_area"), ("CD of the canopy", "CD_canopy_design_area")):
            if not on[key] > off[key]:
                bad.append(f"the symmetric brake does not raise {what}: {on[key]:.3f} against {off[key]:.3f}")
        a_off, a_on = off["section_alpha"]["span_average_deg"], on["section_alpha"]["span_average_deg"]
        if not a_on > a_off:
            bad.append(f"the symmetric brake does not raise the span-averaged angle: {a_on:.2f} against "
                       f"{a_off:.2f} deg")
        if not (on["trim"]["trim_reached"] and off["trim"]["trim_reached"]):
            bad.append("the brake comparison needs both runs trimmed")
        print(f"symmetric brake: CL {off['CL_design_area']:.3f} -> {on['CL_design_area']:.3f}, CD "
              f"{off['CD_canopy_design_area']:.3f} -> {on['CD_canopy_design_area']:.3f}, span-averaged angle "
              f"{a_off:.2f} -> {a_on:.2f} deg")
    for b in bad:
        print("FAILED:", b)
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(os.path.abspath(sys.argv[1])))
