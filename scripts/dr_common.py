"""Helpers shared by the dynamic-relaxation study scripts: run `fsi`, read summary.json, update a marked
block of docs/DYNAMIC_RELAXATION.md."""
import json
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FSI = ROOT / "build/bin/fsi"
DOC = ROOT / "docs/DYNAMIC_RELAXATION.md"

# label -> solver settings (the thesis' names; KDR is this project's default)
METHODS = {
    "KDR": ["solver.damping=kinetic", "solver.mass=gerschgorin"],
    "KDR1": ["solver.damping=kinetic", "solver.mass=stress"],
    "oDR": ["solver.damping=viscous", "solver.mass=gerschgorin", "solver.coefficient=underwood"],
    "mdDR": ["solver.damping=viscous", "solver.mass=rezaiee_pajand", "solver.coefficient=rezaiee_pajand"],
}


def run(case, sets):
    """Runs cases/structure/<case>/scene.yaml with --set assignments; returns summary.json as a dict."""
    with tempfile.TemporaryDirectory() as out:
        cmd = [str(FSI), "run", str(ROOT / "cases/structure" / case / "scene.yaml"), "--out", out, "--quiet",
               "--set", "output.fields=[displacement]"]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return json.loads((Path(out) / "summary.json").read_text())


def replace_block(name, text):
    """Replaces the text between <!-- name:begin --> and <!-- name:end --> in docs/DYNAMIC_RELAXATION.md."""
    doc = DOC.read_text()
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    head, rest = doc.split(begin, 1)
    _, tail = rest.split(end, 1)
    DOC.write_text(f"{head}{begin}\n{text.rstrip()}\n{end}{tail}")
