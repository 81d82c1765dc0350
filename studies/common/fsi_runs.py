"""Running the fsi command from the study scripts (convergence_tables.py, dr_*.py, accuracy_cost.py): one
`fsi run` with --set overrides -> summary.json, one `fsi map-check` -> its JSON report, medians of repeats,
and the mesh-refinement studies those scripts share (which case, which knob, which probe, which reference)."""
import json
import statistics
import subprocess
import tempfile
from pathlib import Path

import hencky_reference

ROOT = Path(__file__).resolve().parents[2]
FSI = ROOT / "build/bin/fsi"  # the scripts' --fsi option replaces it (set_fsi)


def set_fsi(path):
    global FSI
    FSI = Path(path).resolve()


def scene_path(case):
    """cases/structure/<case>/scene.yaml, or the path itself when it names a file."""
    p = Path(case)
    return p if p.suffix in (".yaml", ".yml") else ROOT / "cases/structure" / case / "scene.yaml"


class RunFailed(RuntimeError):
    pass


def run(case, sets=(), ok_codes=(0,), quiet_output=True):
    """`fsi run` of a case (name under cases/structure or a scene path) with --set assignments; returns
    summary.json as a dict, with the exit code as "exit_code". Output frames are kept to the first and last
    (output.interval=0) unless a --set says otherwise. An exit code outside ok_codes raises RunFailed with
    the command's last lines of output."""
    with tempfile.TemporaryDirectory() as out:
        cmd = [str(FSI), "run", str(scene_path(case)), "--out", out, "--quiet"]
        if quiet_output:
            cmd += ["--set", "output.interval=0"]
        for s in sets:
            cmd += ["--set", s]
        p = subprocess.run(cmd, capture_output=True, text=True)
        summary = Path(out) / "summary.json"
        if p.returncode not in ok_codes or not summary.exists():
            tail = "\n".join((p.stdout + p.stderr).strip().splitlines()[-5:])
            raise RunFailed(f"{' '.join(cmd)}: exit code {p.returncode}\n{tail}")
        s = json.loads(summary.read_text())
        s["exit_code"] = p.returncode
        return s


def map_check(a, b, args=()):
    """`fsi map-check A B [args]` -> its --json report (exit code 0 or 1: 1 means some points unmapped,
    which the report shows)."""
    with tempfile.TemporaryDirectory() as out:
        js = Path(out) / "map-check.json"
        cmd = [str(FSI), "map-check", str(a), str(b), "--json", str(js), *args]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode not in (0, 1) or not js.exists():
            raise RunFailed(f"{' '.join(cmd)}: exit code {p.returncode}\n{p.stderr.strip()}")
        return json.loads(js.read_text())


def run_timed(case, sets=(), repeats=1, cheap_seconds=2.0, ok_codes=(0,)):
    """run() repeated up to `repeats` times while one run takes less than cheap_seconds of wall time;
    returns the first summary with "wall" = the median of stats.wall_seconds over the runs made and
    "wall_runs" = how many (the answer is deterministic, only the time varies)."""
    first = run(case, sets, ok_codes)
    walls = [first["stats"]["wall_seconds"]]
    while len(walls) < repeats and walls[0] < cheap_seconds:
        walls.append(run(case, sets, ok_codes)["stats"]["wall_seconds"])
    first["wall"] = statistics.median(walls)
    first["wall_runs"] = len(walls)
    return first


# Mesh-refinement studies of the validation cases: the knob's --set per level, the probe, and the
# independent reference (a function: computed when needed; docs/VALIDATION.md explains each).
def sphere_closed_form(p=10.0e3, r=0.3, young=3000.0e6, nu=0.41, t=0.27e-3):
    """Radius increase of a pressurised Green-Lagrange / St Venant-Kirchhoff sphere (constant reference
    thickness, follower pressure): t S = p r lambda / 2 with S = E/(1-nu) (lambda^2-1)/2 gives
    lambda = a + sqrt(1 + a^2), a = p r (1 - nu) / (2 E t)."""
    a = p * r * (1 - nu) / (2 * young * t)
    return r * (a + (1 + a * a) ** 0.5 - 1)


MESH_STUDIES = {
    "hencky": dict(
        case="hencky", probe="center_deflection", unit=1e-3, unit_name="mm", level_name="rings",
        sets=lambda n: [f"meshes.disc.generator.rings={n}"], h=lambda n: 0.1425 / n,
        reference=lambda: hencky_reference.centre_deflection(),
        reference_text="GL/SVK axisymmetric solution {:.6f} mm (studies/common/hencky_reference.py: the membrane's "
                       "ODEs by shooting; published to 4 digits: 33.14 mm)",
        reference_resolution=0.0, expected_order=2),
    "sphere": dict(
        case="sphere", probe="radial_displacement", unit=1e-3, unit_name="mm", level_name="divisions",
        sets=lambda n: [f"meshes.sphere.generator.divisions={n}"], h=lambda n: 0.3 * 1.5708 / n,
        reference=sphere_closed_form, reference_text="GL/SVK closed form {:.6f} mm (E = 3000 MPa, 10 kPa)",
        reference_resolution=0.0, expected_order=2),
    "airbag": dict(
        case="airbag", probe="center_displacement", unit=1e-3, unit_name="mm", level_name="squares per face",
        sets=lambda n: [f"meshes.bag.generator.divisions=[{n},{n}]"], h=lambda n: 0.848528137 / n,
        reference=lambda: 0.2165, reference_text="published 216.0-217.0 mm (mid-point 216.5; span ±0.5 mm)",
        reference_resolution=0.5e-3, expected_order=None),
}
