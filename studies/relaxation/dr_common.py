"""Helpers shared by the dynamic-relaxation study scripts: the methods, a run of a cushion case (through
fsi_runs.run), and updating a marked block of docs/DYNAMIC_RELAXATION.md."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))  # fsi_runs
import fsi_runs  # noqa: E402
from fsi_runs import ROOT  # noqa: E402

DOC = ROOT / "docs/DYNAMIC_RELAXATION.md"

# label -> solver settings (the thesis' names; KDR is this project's default)
METHODS = {
    "KDR": ["solver.damping=kinetic", "solver.mass=gerschgorin"],
    "KDR1": ["solver.damping=kinetic", "solver.mass=stress"],
    "oDR": ["solver.damping=viscous", "solver.mass=gerschgorin", "solver.coefficient=underwood"],
    "mdDR": ["solver.damping=viscous", "solver.mass=rezaiee_pajand", "solver.coefficient=rezaiee_pajand"],
}


def run(case, sets, repeats=1):
    """Runs cases/structure/<case>/scene.yaml with --set assignments; returns summary.json as a dict (also for
    a run that did not converge or diverged: exit codes 3 and 4 are results here). With repeats > 1 the
    summary's "wall" is the median wall time of that many runs."""
    return fsi_runs.run_timed(case, ["output.fields=[displacement]"] + list(sets), repeats=repeats,
                              ok_codes=(0, 3, 4))


def replace_block(name, text):
    """Replaces the text between <!-- name:begin --> and <!-- name:end --> in docs/DYNAMIC_RELAXATION.md."""
    doc = DOC.read_text()
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    head, rest = doc.split(begin, 1)
    _, tail = rest.split(end, 1)
    DOC.write_text(f"{head}{begin}\n{text.rstrip()}\n{end}{tail}")
