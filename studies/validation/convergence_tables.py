#!/usr/bin/env python3
"""Mesh-convergence tables for docs/VALIDATION.md. Usage: studies/validation/convergence_tables.py [build/bin/fsi]
Runs each case at several mesh sizes through `fsi run --set ...` (studies/common/fsi_runs.py) and prints markdown
tables; studies/cost/accuracy_cost.py measures the same refinements against wall time."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))  # fsi_runs
import fsi_runs  # noqa: E402

if len(sys.argv) > 1:
    fsi_runs.set_fsi(sys.argv[1])


def run(scene, sets):
    return fsi_runs.run(fsi_runs.ROOT / scene, sets)


print("### Hencky: centre deflection (GL/SVK reference 33.14 mm)\n")
print("| rings | triangles | deflection [mm] | vs 33.14 | steps | wall [s] |\n|---|---|---|---|---|---|")
for rings in (8, 16, 32, 64):
    s = run("cases/structure/hencky/scene.yaml", [f"meshes.disc.generator.rings={rings}"])
    w = s["probes"]["center_deflection"] * 1000
    st = s["stats"]
    print(f"| {rings} | {st['membrane_elements']} | {w:.3f} | {100 * (w / 33.14 - 1):+.2f}% | {st['steps']} | {st['wall_seconds']:.2f} |")

print("\n### Airbag: centre displacement (published 216.0-217.0 mm)\n")
print("| side [mm] | squares per face | triangles | displacement [mm] | steps |\n|---|---|---|---|---|")
for side in (0.84, 0.848528137):
    for n in (8, 16, 32):
        s = run("cases/structure/airbag/scene.yaml",
                [f"meshes.bag.generator.size=[{side},{side}]", f"meshes.bag.generator.divisions=[{n},{n}]"])
        print(f"| {side * 1000:.1f} | {n}x{n} | {s['stats']['membrane_elements']} | "
              f"{s['probes']['center_displacement'] * 1000:.2f} | {s['stats']['steps']} |")

print("\n### Sphere (E = 3000 MPa, p = 10 kPa): mean radial displacement\n")
print("| divisions | triangles | dr [mm] | vs analytic 0.3292 | vs GL/SVK closed form 0.32796 |\n|---|---|---|---|---|")
for d in (8, 16, 32, 64):
    s = run("cases/structure/sphere/scene.yaml", [f"meshes.sphere.generator.divisions={d}"])
    dr = s["probes"]["radial_displacement"] * 1000
    print(f"| {d} | {s['stats']['membrane_elements']} | {dr:.5f} | {100 * (dr / 0.3292 - 1):+.2f}% | "
          f"{100 * (dr / 0.3279568 - 1):+.2f}% |")
