#!/usr/bin/python3
"""Fuzz test of the fsi command (ctest label `fuzz`).

Feeds seeded, reproducible mutations of four kinds of input to build/bin/fsi and checks how it ends:
  scenes    cases/structure/*/scene.yaml (shrunk to a few elements and steps) and seeds/scenes/*.yaml,
            mutated as text, as YAML trees and through --set; run with `fsi run SCENE --out DIR`.
  gmsh      seeds/gmsh/*.msh (MSH 2.2 and 4.1, ASCII and binary, made by seeds/make_seeds.sh), mutated
            bytes, counts, tags, element lines and section headers; read by `fsi map-check MESH REF` or by
            `fsi run` of seeds/scenes/gmsh-sheet.yaml with the mutant as its mesh.
  openfoam  seeds/openfoam/constant/polyMesh (blockMesh of a 3x3x1 box), mutated counts, startFace/nFaces,
            labels, numbers, brackets; read by `fsi map-check CASE:top REF`.
  parafoil  seeds/parafoil/*.yaml (a small canopy, every generator key given): the generator's keys set to
            0, negative, huge, subnormal, nan, wrong types, quoted/tagged numbers, null, bad NACA names,
            deleted, or set to plausible values that interact, in the file or by --set; run with `fsi run`.
plus the unmodified seeds (each must run cleanly) and, when tests/corpus exists, every file in it (the
crashers other work collected: tests/corpus/gmsh/*, tests/corpus/openfoam/*).

What every run must satisfy (anything else is a failure, with a class and a signature):
  * it ends within --timeout seconds, or it is visibly busy in the solver with the simulated time
    advancing (class `slow`: a valid but expensive input, counted, not a failure);
  * no signal, exit code in {0, 2, 3, 4} (map-check: 1 too, when it reports unmapped points and no error),
    no "terminate called" / "std::" text (an exception that escaped);
  * exit 2: an `error:` line that names the input file, with the line number when the file is text;
  * exit 0 of `run`: summary.json parses (no NaN/Infinity), every number in it is finite (nlohmann::json
    writes NaN as null), and the energy-balance error of an explicit run is below the scene's
    energy_tolerance (0.05 unless the scene raised it); exit 0/1 of map-check: the same for its --json;
  * a scene that fsi accepts (exit 0, 3 or 4) has no key twice in one mapping (PyYAML's view of the same
    text), is UTF-8 (file and --set values), and has no mesh size (divisions, rings, across, ids) beyond
    int32 -- the reader must refuse these rather than pick one copy, replace bytes or wrap;
  * an unmodified seed exits 0 (4 for a capped until-static seed): they are all valid inputs.
Each process runs with a 2 GiB address-space limit (allocation failures must become messages rather than
swap), no core files and a 512 MiB file-size limit.

Usage (`ctest -L fuzz` runs the first line once per kind, --kinds KIND, seed 1, 150 inputs per kind):
  /usr/bin/python3 tests/fuzz/fuzz.py --fsi build/bin/fsi --work build/fuzz
  FSI_FUZZ_SEED=7 FSI_FUZZ_COUNT=2000 nice -n 10 /usr/bin/python3 tests/fuzz/fuzz.py --fsi build/bin/fsi \\
      --work build/fuzz-long --backtrace          # the long run of docs/ROBUSTNESS.md (about 30-40 min)
  /usr/bin/python3 tests/fuzz/fuzz.py --fsi build/bin/fsi --work /tmp/f --seed 1 --only scenes:17
                                                  # regenerate and rerun one input
A failure prints its seed, kind, index and mutations and keeps the input under WORK/failures/KIND-INDEX/
with `repro.sh` (the one command that reproduces it). WORK/results.jsonl has one line per input and
WORK/report.json the counts and the distinct failure signatures. Exit status 1 if anything failed.
Minimal reproducers of what the fuzzer found beyond the known reader/scene/run-loop bugs: found/*/repro.sh.
"""

import argparse
import collections
import concurrent.futures
import itertools
import json
import math
import os
import random
import re
import resource
import shlex
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import yaml

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(Path(__file__).resolve().parent))
import mutate  # noqa: E402

HERE = Path(__file__).resolve().parent
SOURCE = HERE.parent.parent
SEEDS = HERE / "seeds"
KINDS = ["seeds", "scenes", "gmsh", "openfoam", "parafoil"]
MEMORY_LIMIT = 2 << 30
FILE_SIZE_LIMIT = 512 << 20
STDBUF = shutil.which("stdbuf")


# ---------------------------------------------------------------------------------------------------------
# Seeds

def shrink_scene(tree):
    """A case scene made tiny: few elements, a short end time or cap, frequent energy checks. The case's
    structure (materials, effects, constraints, probes) stays as it is, which is what the mutations need."""
    for mesh in (tree.get("meshes") or {}).values():
        gen = mesh.get("generator") if isinstance(mesh, dict) else None
        if not isinstance(gen, dict):
            continue
        for key, small in (("divisions", 3), ("rings", 2), ("across", 1)):
            if isinstance(gen.get(key), list):
                gen[key] = [min(int(v), small) for v in gen[key]]
            elif isinstance(gen.get(key), int):
                gen[key] = min(gen[key], small)
        if gen.get("type") == "pillow" or gen.get("pattern") == "cross":
            # pillow/cross groups like top_center need even (or cross+odd) divisions: keep them valid.
            if isinstance(gen.get("divisions"), list):
                gen["divisions"] = [2 for _ in gen["divisions"]]
    solver = tree.get("solver")
    if isinstance(solver, dict) and solver.get("type") == "dynamic_relaxation":
        solver["max_iterations"] = min(int(solver.get("max_iterations", 200000)), 2000)
    time_ = tree.get("time")
    if isinstance(time_, dict):
        if "end" in time_:
            time_["end"] = min(float(time_["end"]), 0.005)
        if isinstance(time_.get("until_static"), dict):
            time_["until_static"]["max_time"] = min(float(time_["until_static"]["max_time"]), 0.005)
        time_["monitor_every"] = 10
    output = tree.get("output")
    if isinstance(output, dict) and output.get("interval"):
        output["interval"] = max(float(output["interval"]), 0.001)
    return tree


# The files a seed scene reads beside it (a case's Gmsh meshes), by seed name: written next to scene.yaml.
SEED_FILES = {}


def write_seed_files(name, case_dir):
    for file_name, data in SEED_FILES.get(name, {}).items():
        (case_dir / file_name).write_bytes(data)


def load_seeds():
    """{kind: [(name, payload)]}: scene texts, Gmsh file bytes, and the polyMesh files of the seed case."""
    scenes = []
    for path in sorted((SOURCE / "cases" / "structure").glob("*/scene.yaml")):
        tree = shrink_scene(yaml.safe_load(path.read_bytes()))
        text = yaml.safe_dump(tree, default_flow_style=None, sort_keys=False, width=100).encode()
        name = f"cases/structure/{path.parent.name}/scene.yaml (shrunk)"
        scenes.append((name, text))
        SEED_FILES[name] = {p.name: p.read_bytes() for p in sorted(path.parent.glob("*.msh"))}
    for path in sorted((SEEDS / "scenes").glob("*.yaml")):
        scenes.append((f"tests/fuzz/seeds/scenes/{path.name}", path.read_bytes()))
    gmsh = [(f"tests/fuzz/seeds/gmsh/{p.name}", p.read_bytes()) for p in sorted((SEEDS / "gmsh").glob("*.msh"))]
    poly = SEEDS / "openfoam" / "constant" / "polyMesh"
    foam = [("tests/fuzz/seeds/openfoam", {n: (poly / n).read_bytes() for n in mutate.POLYMESH_FILES})]
    parafoil = [(f"tests/fuzz/seeds/parafoil/{p.name}", p.read_bytes())
                for p in sorted((SEEDS / "parafoil").glob("*.yaml"))]
    return {"scenes": scenes, "gmsh": gmsh, "openfoam": foam, "parafoil": parafoil}


SHEET_SCENE = "gmsh-sheet.yaml"  # the seed scene that reads mesh.msh next to it
REFERENCE_MESH = "square-4.1-ascii.msh"  # the unit square both other meshes are checked against


# ---------------------------------------------------------------------------------------------------------
# Building one input

class Case:
    """One input: files written under `dir`, one fsi command, and how it was made."""

    def __init__(self, kind, index, seed, dir_):
        self.kind, self.index, self.seed, self.dir = kind, index, seed, dir_
        self.seed_name = ""
        self.mutations = []
        self.cmd = []
        self.mode = ""  # run | map-check
        self.text_inputs = []  # names of the input files that are text (line numbers expected)
        self.input_names = []  # names an error message may cite for the mutated input
        self.unmodified = False  # an unmodified seed: must exit 0
        self.sets = []


def build_case(kind, index, seed, seeds, work, fsi):
    rng = random.Random(f"{seed}:{kind}:{index}")
    case = Case(kind, index, seed, work / "cases" / f"{kind}-{index:05d}")
    shutil.rmtree(case.dir, ignore_errors=True)
    case.dir.mkdir(parents=True)
    out = case.dir / "out"
    if kind == "scenes":
        name, text = mutate.pick(rng, seeds["scenes"])
        text, case.mutations, case.sets = mutate.mutate_scene(rng, text)
        case.seed_name = name
        (case.dir / "scene.yaml").write_bytes(text)
        shutil.copy(SEEDS / "gmsh" / mutate.pick(rng, [p.name for p in sorted((SEEDS / "gmsh").glob("*.msh"))]),
                    case.dir / "mesh.msh")
        write_seed_files(name, case.dir)
        case.cmd = [fsi, "run", "scene.yaml", "--out", "out"] + [f"--set={s}" for s in case.sets]
        case.mode = "run"
        case.text_inputs = ["scene.yaml"]
        case.input_names = ["scene.yaml", "mesh.msh"]
    elif kind == "parafoil":
        name, text = mutate.pick(rng, seeds["parafoil"])
        text, case.mutations, case.sets = mutate.mutate_parafoil(rng, text)
        case.seed_name = name
        (case.dir / "scene.yaml").write_bytes(text)
        case.cmd = [fsi, "run", "scene.yaml", "--out", "out"] + [f"--set={s}" for s in case.sets]
        case.mode = "run"
        case.text_inputs = ["scene.yaml"]
        case.input_names = ["scene.yaml"]
    elif kind == "gmsh":
        name, data = mutate.pick(rng, seeds["gmsh"])
        data, case.mutations = mutate.mutate_gmsh(rng, data)
        case.seed_name = name
        (case.dir / "mesh.msh").write_bytes(data)
        binary = bool(mutate._is_binary(data))
        case.text_inputs = [] if binary else ["mesh.msh"]
        if rng.random() < 0.5:
            shutil.copy(SEEDS / "gmsh" / REFERENCE_MESH, case.dir / "ref.msh")
            src = mutate.pick(rng, ["mesh.msh", "mesh.msh", "mesh.msh:sheet", "mesh.msh:rim"])
            args = [src, "ref.msh"] if rng.random() < 0.7 else ["ref.msh", src]
            case.cmd = [fsi, "map-check"] + args + ["--json", "map-check.json"]
            case.mode = "map-check"
            case.input_names = ["mesh.msh"]
        else:
            shutil.copy(SEEDS / "scenes" / SHEET_SCENE, case.dir / "scene.yaml")
            case.cmd = [fsi, "run", "scene.yaml", "--out", "out"]
            case.mode = "run"
            case.input_names = ["mesh.msh", "scene.yaml"]  # a renamed group is the scene's error
            case.text_inputs = case.text_inputs + ["scene.yaml"]
    else:
        name, files = seeds["openfoam"][0]
        files = dict(files)
        case.mutations = mutate.mutate_foam(rng, files)
        case.seed_name = name
        poly = case.dir / "foam" / "constant" / "polyMesh"
        poly.mkdir(parents=True)
        for n, data in files.items():
            (poly / n).write_bytes(data)
        shutil.copy(SEEDS / "gmsh" / REFERENCE_MESH, case.dir / "ref.msh")
        patch = mutate.pick(rng, ["top"] * 6 + ["bottom", "sides"])
        args = [f"foam:{patch}", "ref.msh"] if rng.random() < 0.7 else ["ref.msh", f"foam:{patch}"]
        case.cmd = [fsi, "map-check"] + args + ["--json", "map-check.json"]
        case.mode = "map-check"
        case.text_inputs = [f"polyMesh/{n}" for n in mutate.POLYMESH_FILES]
        case.input_names = ["polyMesh/", "foam"]
    del out
    return case


def unmodified_cases(seeds, work, fsi):
    """Every seed as it is: valid inputs that must run to a clean end (exit 0)."""
    cases = []
    for i, (name, text) in enumerate(seeds["scenes"] + seeds["parafoil"]):
        case = Case("seed", i, 0, work / "cases" / f"seed-scene-{i:02d}")
        shutil.rmtree(case.dir, ignore_errors=True)
        case.dir.mkdir(parents=True)
        (case.dir / "scene.yaml").write_bytes(text)
        shutil.copy(SEEDS / "gmsh" / REFERENCE_MESH, case.dir / "mesh.msh")
        write_seed_files(name, case.dir)
        case.seed_name, case.unmodified, case.mode = name, True, "run"
        case.cmd = [fsi, "run", "scene.yaml", "--out", "out"]
        case.text_inputs, case.input_names = ["scene.yaml"], ["scene.yaml"]
        cases.append(case)
    for j, (name, data) in enumerate(seeds["gmsh"]):
        case = Case("seed", len(cases), 0, work / "cases" / f"seed-gmsh-{j:02d}")
        shutil.rmtree(case.dir, ignore_errors=True)
        case.dir.mkdir(parents=True)
        (case.dir / "mesh.msh").write_bytes(data)
        shutil.copy(SEEDS / "gmsh" / REFERENCE_MESH, case.dir / "ref.msh")
        case.seed_name, case.unmodified, case.mode = name, True, "map-check"
        case.cmd = [fsi, "map-check", "mesh.msh", "ref.msh", "--json", "map-check.json"]
        case.input_names = ["mesh.msh"]
        cases.append(case)
    case = Case("seed", len(cases), 0, work / "cases" / "seed-openfoam")
    shutil.rmtree(case.dir, ignore_errors=True)
    shutil.copytree(SEEDS / "openfoam", case.dir / "foam")
    shutil.copy(SEEDS / "gmsh" / REFERENCE_MESH, case.dir / "ref.msh")
    case.seed_name, case.unmodified, case.mode = "tests/fuzz/seeds/openfoam", True, "map-check"
    case.cmd = [fsi, "map-check", "foam:top", "ref.msh", "--json", "map-check.json"]
    case.input_names = ["polyMesh/", "foam"]
    cases.append(case)
    return cases


def corpus_cases(corpus, work, fsi, kinds):
    """Regression corpus (tests/corpus, collected by the reader fixes): every Gmsh file is read by
    map-check against the reference square; an OpenFOAM entry is a case folder (constant/polyMesh), a
    polyMesh folder, or one polyMesh file named after the file it replaces (e.g. `faces`, `x.faces`,
    `faces.x`) that is dropped into the seed case. Each patch named in its boundary file is checked."""
    cases = []
    if not corpus.is_dir():
        return cases
    gmsh_files = sorted(p for p in (corpus / "gmsh").glob("**/*") if p.is_file()) if "gmsh" in kinds else []
    for i, path in enumerate(gmsh_files):
        case = Case("corpus", i, 0, work / "cases" / f"corpus-gmsh-{i:03d}")
        shutil.rmtree(case.dir, ignore_errors=True)
        case.dir.mkdir(parents=True)
        shutil.copy(path, case.dir / "mesh.msh")
        shutil.copy(SEEDS / "gmsh" / REFERENCE_MESH, case.dir / "ref.msh")
        case.seed_name, case.mode = str(path.relative_to(corpus.parent.parent)), "map-check"
        case.cmd = [fsi, "map-check", "mesh.msh", "ref.msh", "--json", "map-check.json"]
        case.text_inputs = [] if mutate._is_binary(path.read_bytes()) else ["mesh.msh"]
        case.input_names = ["mesh.msh"]
        cases.append(case)
    entries = sorted((corpus / "openfoam").glob("*")) if "openfoam" in kinds else []
    for i, path in enumerate(entries):
        case = Case("corpus", i, 0, work / "cases" / f"corpus-openfoam-{i:03d}")
        shutil.rmtree(case.dir, ignore_errors=True)
        poly = case.dir / "foam" / "constant" / "polyMesh"
        shutil.copytree(SEEDS / "openfoam" / "constant" / "polyMesh", poly)
        if path.is_dir():
            src = path / "constant" / "polyMesh" if (path / "constant" / "polyMesh").is_dir() else path
            for f in src.iterdir():
                if f.is_file():
                    shutil.copy(f, poly / f.name)
        else:
            parts = re.split(r"[.\-_]", path.name)
            target = next((n for n in mutate.POLYMESH_FILES if n in parts), None)
            if target is None:
                shutil.rmtree(case.dir)
                print(f"corpus: {path}: not a polyMesh file name (points, faces, owner, neighbour, "
                      f"boundary), skipped")
                continue
            shutil.copy(path, poly / target)
        patches = re.findall(rb"^\s*(\w+)\s*\n\s*\{", (poly / "boundary").read_bytes(), re.M) or [b"top"]
        for p in patches[:3]:
            c = Case("corpus", len(cases), 0, case.dir)
            patch = p.decode(errors="replace")
            c.seed_name, c.mode = f"{path.relative_to(corpus.parent.parent)} (patch {patch})", "map-check"
            c.cmd = [fsi, "map-check", "foam:" + patch, "ref.msh", "--json", "map-check.json"]
            shutil.copy(SEEDS / "gmsh" / REFERENCE_MESH, case.dir / "ref.msh")
            c.text_inputs = [f"polyMesh/{n}" for n in mutate.POLYMESH_FILES]
            c.input_names = ["polyMesh/", "foam"]
            cases.append(c)
    return cases


# ---------------------------------------------------------------------------------------------------------
# Running and judging one input

def _limits():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_SIZE_LIMIT, FILE_SIZE_LIMIT))


def _head_and_tail(path, n=100000):
    """The start (where the error line is) and the end (the last progress) of an output file."""
    with open(path, "rb") as f:
        data = f.read(n)
        size = os.fstat(f.fileno()).st_size
        if size > n:
            f.seek(max(n, size - n))
            data += b"\n[...]\n" + f.read()
    return data.decode("utf-8", "replace")


def run_case(case, timeout):
    env = dict(os.environ, OMP_NUM_THREADS="1", LC_ALL="C")
    t0 = time.monotonic()
    with open(case.dir / "stdout.txt", "wb") as so, open(case.dir / "stderr.txt", "wb") as se:
        # Line-buffered stdout (stdbuf), so that what a killed run printed (its progress) reaches the file.
        cmd = (["stdbuf", "-oL"] if STDBUF else []) + case.cmd
        proc = subprocess.Popen(cmd, cwd=case.dir, stdout=so, stderr=se, stdin=subprocess.DEVNULL,
                                env=env, preexec_fn=_limits, start_new_session=True)
        try:
            rc = proc.wait(timeout=timeout)
            timed_out = False
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            rc = proc.wait()
            timed_out = True
    seconds = time.monotonic() - t0
    stdout = _head_and_tail(case.dir / "stdout.txt")
    stderr = _head_and_tail(case.dir / "stderr.txt")
    return rc, timed_out, seconds, stdout, stderr


def _strict_json(text):
    def reject(name):
        raise ValueError(f"non-finite constant {name}")
    return json.loads(text, parse_constant=reject)


def _non_finite(node, path="", out=None):
    out = [] if out is None else out
    if isinstance(node, dict):
        for k, v in node.items():
            _non_finite(v, f"{path}.{k}" if path else k, out)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            _non_finite(v, f"{path}[{i}]", out)
    elif node is None:
        out.append(f"{path}=null")
    elif isinstance(node, float) and not math.isfinite(node):
        out.append(f"{path}={node}")
    return out


class _DuplicateKeyLoader(yaml.CSafeLoader):
    """PyYAML's safe loader that records keys repeated in one mapping (YAML forbids them)."""

    def construct_mapping(self, node, deep=False):
        seen = set()
        for key_node, _ in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                continue
            key = self.construct_object(key_node, deep=True)
            try:
                if key in seen:
                    self.duplicates.append(f"{key!r} (line {key_node.start_mark.line + 1})")
                seen.add(key)
            except TypeError:  # an unhashable key (a list or map): PyYAML itself rejects it below
                pass
        return super().construct_mapping(node, deep)


def _apply_sets(tree, sets):
    """The documented --set semantics (dot path, list index, YAML value), best effort."""
    for arg in sets:
        path, _, value = arg.partition("=")
        node, keys = tree, path.split(".")
        for k in keys[:-1]:
            node = node[int(k)] if isinstance(node, list) else node.setdefault(k, {})
        if isinstance(node, list):
            node[int(keys[-1])] = yaml.safe_load(value)
        else:
            node[keys[-1]] = yaml.safe_load(value)
    return tree


def scene_facts(case):
    """What the scene as fsi sees it (file + --set) says, for the oracles that need its content:
    (tree or None, duplicate keys, is the text UTF-8, out-of-int32 mesh sizes)."""
    data = (case.dir / "scene.yaml").read_bytes()

    def is_utf8(b):
        try:
            b.decode("utf-8")
            return True
        except UnicodeDecodeError:
            return False
    utf8 = is_utf8(data) and all(is_utf8(os.fsencode(s)) for s in case.sets)
    tree, dups = None, []
    try:
        # libyaml's composer recurses in C: a flow nesting thousands deep overflows the stack of this
        # process (found by this test's own deep-nesting mutation). Such a scene gets no content oracle.
        depth = max(itertools.accumulate((c in b"[{") - (c in b"]}") for c in data), default=0)
        if depth > 200:
            raise ValueError("nesting too deep for the oracle")
        loader = _DuplicateKeyLoader(data)
        loader.duplicates = dups
        try:
            tree = loader.get_single_data()
        finally:
            loader.dispose()
        tree = _apply_sets(tree, case.sets)
    except Exception:  # noqa: BLE001 - any parse failure: the oracles below then do not apply
        tree = None
    wide = []
    seen = set()

    def walk(node, path):
        if isinstance(node, (dict, list)):
            if id(node) in seen:  # reached again through an alias: do not expand (billion laughs)
                return
            seen.add(id(node))
        if isinstance(node, dict):
            for k, v in node.items():
                if k in ("divisions", "rings", "across", "ids"):
                    for x in (v if isinstance(v, list) else [v]):
                        if isinstance(x, int) and not isinstance(x, bool) and not -2**31 <= x < 2**31:
                            wide.append(f"{path}.{k}={x}")
                walk(v, f"{path}.{k}")
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, f"{path}[{i}]")
    try:
        walk(tree, "")
    except RecursionError:
        pass
    return tree, dups, utf8, wide


def _energy_bound(tree):
    """The energy tolerance the scene asked for (an explicit run may stop as unstable only above it)."""
    try:
        tol = tree["time"].get("energy_tolerance", 0.05)
    except (KeyError, TypeError, AttributeError):
        return 0.05
    if isinstance(tol, (int, float)) and not isinstance(tol, bool):
        return max(0.05, float(tol)) if math.isfinite(tol) else None
    return 0.05


# Errors about the file as a whole or about a command-line argument: no line to cite.
# Whole-file properties: no single line is at fault (an empty file, a missing group, a mesh whose extent is
# too large for the projection's arithmetic); and the model builder's geometric checks, which name the
# element and node by their tags in the file (the builder works on merged meshes, not on file lines).
LINE_EXEMPT = re.compile(r"no physical \w+ group|contains no line, triangle or quadrangle|no such file|cannot open"
                         r"|not readable|is empty|no patch|squared areas overflow; rescale the meshes"
                         r"|is degenerate \(zero|has zero length \(nodes|belongs to no element and has no mass")


def _cites_line(err, name):
    """True if the message names the file and then a line: `name:12`, `name...:12` or `'name', line 12`."""
    i = err.find(name)
    return i >= 0 and re.match(r"(\S*:\d+|.*\bline \d+)", err[i + len(name):]) is not None


PROGRESS_RE = re.compile(r"^step\s+(\d+)\s+t\s+(\S+?)/", re.M)


# The parafoil generator's rules (docs/PARAFOIL.md, issue 35) as an oracle on what an accepted scene gave it.
PARAFOIL_NUMBERS = {"span", "root_chord", "tip_chord", "arc_radius", "incidence", "twist", "thickness_scale",
                    "bulge", "cascade_fraction", "line_length", "rigging_angle", "toggle_fraction",
                    "brake_slack", "riser_length"}
PARAFOIL_INTEGERS = {"cells", "chordwise_points", "span_divisions", "cascade", "line_elements", "brake_points"}
PARAFOIL_POSITIVE = {"span", "root_chord", "tip_chord", "thickness_scale", "line_length", "riser_length"}
PLAIN_NUMBER_RE = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
NACA_RE = re.compile(r"(?:naca *)?\d{4,5}", re.I)


def parafoil_violations(given):
    """What an accepted parafoil entry must not have: a non-number where a number belongs, a value out of
    its physical range, unset confused with 0, a value that cannot take effect, a malformed NACA name."""
    bad, num = [], {}
    for key, raw in given.items():
        if key in PARAFOIL_NUMBERS | PARAFOIL_INTEGERS:
            tag, _, rest = raw.partition(" ")
            if tag in ("!!float", "!!int"):  # the core tags of numbers are honoured
                raw = rest.strip()
                if tag == "!!int" and PLAIN_NUMBER_RE.fullmatch(raw) and not float(raw).is_integer():
                    bad.append(f"{key}: !!int {raw} is not an integer")
                    continue
            if not PLAIN_NUMBER_RE.fullmatch(raw):
                bad.append(f"{key}: {raw} is not a plain number")
                continue
            num[key] = float(raw)
            if not math.isfinite(num[key]) or (key in PARAFOIL_POSITIVE and not num[key] >= 2.2250738585072014e-308):
                bad.append(f"{key}: {raw} out of range")
    span = num.get("span", 3.0)
    for key, limit in (("span", 1000.0), ("root_chord", span), ("tip_chord", span), ("line_length", 10.0),
                       ("riser_length", 10.0 * span)):
        if key in num and num[key] > limit:
            bad.append(f"{key}: {given[key]} above {limit:g}")
    if num.get("bulge", 0) > 0 and num.get("span_divisions", 2) < 2:
        bad.append("bulge > 0 with span_divisions 1 (no effect)")
    if "cascade_fraction" in given and num.get("cascade", 2) == 1:
        bad.append("cascade_fraction with cascade 1 (no effect)")
    if num.get("brake_points", 3) == 0 and ("toggle_fraction" in given or num.get("brake_slack", 0) > 0):
        bad.append("toggle_fraction or brake_slack with brake_points 0 (no effect)")
    if "section" in given and not given["section"].startswith("{") and \
            not NACA_RE.fullmatch(given["section"].strip("'\"")):
        bad.append(f"section: {given['section']} is not NACA and 4 or 5 digits")
    if "row_trim" in given and "rows" not in given and given["row_trim"].count(",") != 3:
        bad.append(f"row_trim: {given['row_trim']} does not have one entry per row")
    return bad


def judge(case, rc, timed_out, stdout, stderr):
    """Returns (outcome, failure classes). outcome: 'exit N', 'signal NAME', 'timeout'."""
    fails = []
    if timed_out:
        times = [float(t) for _, t in PROGRESS_RE.findall(stdout)]
        if len(times) >= 2 and times[-1] > times[0]:
            return "slow", []  # busy in the step loop and the simulated time advances
        if "model " in stdout and not times:
            return "slow", []  # a dynamic-relaxation loop (prints nothing per iteration) or a first step
        return "timeout", ["timeout: no progress" if "model " in stdout else "timeout: before the model was built"]
    if rc < 0:
        name = signal.Signals(-rc).name
        if name == "SIGXFSZ":
            return "file-size limit", []  # writes > 512 MiB: a huge but valid output request
        return f"signal {name}", [f"signal {name}"]
    outcome = f"exit {rc}"
    text = stdout + stderr
    if "terminate called" in text:
        fails.append("uncaught exception (terminate called)")
    elif "std::" in stderr:
        fails.append("exception text (std::) in the message")
    allowed = {0, 2, 3, 4} if case.mode == "run" else {0, 1, 2}
    if rc not in allowed:
        fails.append(f"exit code {rc}")
    elif case.mode == "map-check" and rc == 1 and "error:" in stderr:
        fails.append("exit code 1 (error)")
    if rc == 2:
        err = next((l for l in stderr.splitlines() if l.startswith("error:")), "")
        names = case.input_names + (["--set"] if case.sets else [])
        if not err:
            fails.append("exit 2 without an 'error:' line")
        elif not any(n in err for n in names):
            fails.append("exit 2: message does not name the input file")
        elif not case.sets and not LINE_EXEMPT.search(err):
            # The error must be located: a line in one of the text inputs it names (it may name another file
            # as context, e.g. "boundary:20: patch 'top' has 9 faces from face N, but faces has 42 faces");
            # an OpenFOAM error that names no polyMesh file at all (only CASE:patch) has lost its location.
            named = [n for n in case.text_inputs if n in err]
            if (named and not any(_cites_line(err, n) for n in named)) or (not named and case.kind == "openfoam"):
                fails.append("exit 2: message has no line number")
    tree = None
    if case.mode == "run" and case.kind in ("scenes", "seed", "parafoil"):
        tree, dups, utf8, wide = scene_facts(case)
        if rc in (0, 3, 4):  # the scene was accepted
            if dups:
                fails.append("scene with a duplicate key accepted")
                case.detail = "duplicate " + ", ".join(dups[:3])
            if not utf8:
                fails.append("scene that is not UTF-8 accepted")
            if wide:
                fails.append("mesh size beyond int32 accepted")
                case.detail = ", ".join(wide[:3])
    if case.kind == "parafoil" and rc in (0, 3, 4):
        bad = parafoil_violations(mutate.parafoil_given((case.dir / "scene.yaml").read_bytes(), case.sets))
        if bad:
            fails.append("parafoil: invalid value accepted")
            case.detail = "; ".join(bad[:3])
    if rc == 0 and case.mode == "run":
        try:
            summary = _strict_json((case.dir / "out" / "summary.json").read_text())
            bad = _non_finite(summary)
            if bad:
                fails.append("exit 0: non-finite number in summary.json")
                case.detail = ", ".join(bad[:5])
            stats = summary.get("stats", {})
            err = stats.get("energy_balance_error")
            bound = _energy_bound(tree) if tree is not None else 0.05
            if isinstance(err, (int, float)) and bound is not None and not err < bound:
                fails.append("exit 0: energy-balance error above the tolerance")
                case.detail = f"energy_balance_error {err:.3g} (bound {bound:.3g}), steps {stats.get('steps')}"
        except (OSError, ValueError) as e:
            fails.append("exit 0: summary.json missing or not valid JSON")
            case.detail = str(e)[:200]
    if rc in (0, 1) and case.mode == "map-check" and not fails:
        try:
            bad = _non_finite(_strict_json((case.dir / "map-check.json").read_text()))
            if bad:
                fails.append(f"map-check exit {rc}: non-finite number in its JSON")
                case.detail = ", ".join(bad[:5])
        except (OSError, ValueError) as e:
            fails.append(f"map-check exit {rc}: JSON missing or not valid")
            case.detail = str(e)[:200]
    # A seed is a valid input: it must end cleanly (4 is the normal end of a capped until-static run).
    if case.unmodified and rc not in (0, 4):
        fails.append(f"unmodified seed exits {rc}")
    return outcome, fails


def signature(case, outcome, fails, stderr, backtrace=""):
    """What distinguishes one bug from another: the failure class plus the normalised error line (paths,
    numbers and quoted values replaced) or, for a signal, the innermost frames of the backtrace."""
    line = next((l for l in stderr.splitlines() if l.startswith("error:")), "")
    if not line:
        lines = [l for l in stderr.splitlines() if l.strip()]
        line = lines[-1] if lines else ""
    line = line.replace(str(case.dir), "DIR")
    line = re.sub(r"'[^']*'", "'…'", line)
    line = re.sub(r"\"[^\"]*\"", '"…"', line)
    line = re.sub(r"\d+(\.\d+)?([eE][-+]?\d+)?", "N", line)[:180]
    parts = [fails[0]]
    if "accepted" in fails[0]:
        pass  # the input should have been refused: whatever the run then did is not the signature
    elif backtrace:
        parts.append(backtrace)
    elif line:
        parts.append(line)
    return " | ".join(parts)


def backtrace_of(case, timeout):
    """Reruns a crashing input under gdb and returns its innermost function names (a crash signature)."""
    cmd = ["gdb", "-batch", "-nx", "-ex", "run", "-ex", "bt 12", "--args"] + case.cmd
    try:
        p = subprocess.run(cmd, cwd=case.dir, capture_output=True, timeout=timeout * 3, preexec_fn=_limits,
                           stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return ""
    text = p.stdout.decode("utf-8", "replace").replace("(anonymous namespace)::", "")
    frames = re.findall(r"^#\d+\s+(?:0x[0-9a-f]+ in )?([^\s(]+)", text, re.M)
    skip = ("raise", "abort", "__pthread_kill", "__GI_", "std::__", "__libc", "??", "_start")
    names = [f for f in frames if not f.startswith(skip)]
    (case.dir / "backtrace.txt").write_bytes(p.stdout)
    ours = next((f for f in names if f.startswith("fsi::")), "")
    return " < ".join(names[:3] + ([ours] if ours and ours not in names[:3] else []))


def save_failure(case, work, outcome, fails, seconds):
    dest = work / "failures" / case.dir.name
    shutil.rmtree(dest, ignore_errors=True)
    shutil.copytree(case.dir, dest, ignore=shutil.ignore_patterns("out"))
    cmd = " ".join(shlex.quote(c) for c in case.cmd)
    # Arguments may hold bytes that are not UTF-8 (surrogate-escaped): written back as those bytes.
    (dest / "repro.sh").write_bytes((
        "#!/bin/sh\n"
        f"# {case.kind} {case.index}, fuzz seed {case.seed}, from {case.seed_name}\n"
        + "".join(f"# mutation: {m}\n" for m in case.mutations)
        + f"# outcome: {outcome} ({'; '.join(fails)}), {seconds:.2f} s\n"
        + f"# the fuzz test's limits: {MEMORY_LIMIT >> 20} MiB of address space, no core file\n"
        + f'ulimit -v {MEMORY_LIMIT >> 10}; ulimit -c 0\n'
        + 'cd "$(dirname "$0")" && rm -rf out && exec ' + cmd + "\n").encode("utf-8", "surrogateescape"))
    (dest / "repro.sh").chmod(0o755)
    return dest


# ---------------------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fsi", required=True, help="the fsi binary")
    ap.add_argument("--work", required=True, type=Path, help="work folder (inputs, failures, report)")
    ap.add_argument("--seed", type=int, default=int(os.environ.get("FSI_FUZZ_SEED", 1)))
    ap.add_argument("--count", type=int, default=int(os.environ.get("FSI_FUZZ_COUNT", 150)),
                    help="inputs per kind (default 150, or FSI_FUZZ_COUNT)")
    ap.add_argument("--kinds", default=",".join(KINDS),
                    help="comma-separated: seeds (the unmodified seeds), scenes, gmsh, openfoam, parafoil (each with its "
                         "part of the corpus)")
    ap.add_argument("--timeout", type=float, default=10.0, help="seconds per run")
    ap.add_argument("--jobs", type=int, default=int(os.environ.get("FSI_FUZZ_JOBS", 2)))
    ap.add_argument("--corpus", type=Path, default=SOURCE / "tests" / "corpus")
    ap.add_argument("--only", help="KIND:INDEX: build and run this one input only")
    ap.add_argument("--backtrace", action="store_true", help="rerun crashes under gdb for their signature")
    ap.add_argument("--keep", action="store_true", help="keep the folders of inputs that passed")
    args = ap.parse_args()

    sys.stdout.reconfigure(errors="backslashreplace")  # messages may quote bytes that are not UTF-8
    fsi = str(Path(args.fsi).resolve())
    work = args.work.resolve()
    work.mkdir(parents=True, exist_ok=True)
    shutil.rmtree(work / "failures", ignore_errors=True)
    seeds = load_seeds()
    t0 = time.monotonic()

    if args.only:
        kind, index = args.only.split(":")
        jobs = [(kind, int(index))]
        fixed = []
    else:
        kinds = [k for k in args.kinds.split(",") if k]
        unknown = set(kinds) - set(KINDS)
        if unknown:
            ap.error(f"--kinds: unknown {', '.join(sorted(unknown))}; known: {', '.join(KINDS)}")
        jobs = [(k, i) for i in range(args.count) for k in kinds if k != "seeds"]
        fixed = (unmodified_cases(seeds, work, fsi) if "seeds" in kinds else []) + \
            corpus_cases(args.corpus, work, fsi, kinds)
        if not args.corpus.is_dir() and ("gmsh" in kinds or "openfoam" in kinds):
            print(f"fuzz: no regression corpus at {args.corpus}", flush=True)
    print(f"fuzz: seed {args.seed}, {len(jobs)} mutated inputs ({args.count} per kind), {len(fixed)} seeds "
          f"and corpus inputs, timeout {args.timeout:g} s, {args.jobs} jobs; work {work}", flush=True)

    lock = threading.Lock()
    results = []
    log = open(work / "results.jsonl", "w")

    def one(item):
        try:
            return one_checked(item)
        except Exception:  # noqa: BLE001 - a bug of this driver must not end a long run: report it, go on
            import traceback
            text = traceback.format_exc()
            rec = {"kind": str(item[0]) if isinstance(item, tuple) else item.kind,
                   "index": item[1] if isinstance(item, tuple) else item.index, "seed": args.seed,
                   "outcome": "driver error", "failures": ["fuzz driver error"],
                   "signature": "fuzz driver error | " + text.strip().splitlines()[-1][:160], "stderr": text}
            with lock:
                print(f"DRIVER ERROR on {item if isinstance(item, tuple) else item.dir}:\n{text}", flush=True)
                results.append(rec)
                log.write(json.dumps(rec) + "\n")
            return rec

    def one_checked(item):
        case = build_case(*item, args.seed, seeds, work, fsi) if isinstance(item, tuple) else item
        case.detail = ""
        rc, timed_out, seconds, stdout, stderr = run_case(case, args.timeout)
        outcome, fails = judge(case, rc, timed_out, stdout, stderr)
        bt = backtrace_of(case, args.timeout) if args.backtrace and outcome.startswith("signal") else ""
        sig = signature(case, outcome, fails, stderr, bt) if fails else ""
        rec = {"kind": case.kind, "index": case.index, "seed": case.seed, "from": case.seed_name,
               "mode": case.mode, "mutations": case.mutations, "sets": case.sets, "outcome": outcome,
               "failures": fails, "signature": sig, "detail": case.detail, "seconds": round(seconds, 3),
               "stderr": stderr.strip()[-400:]}
        with lock:
            if fails:
                dest = save_failure(case, work, outcome, fails, seconds)
                rec["saved"] = str(dest)
                print(f"FAIL {case.kind} {case.index} (seed {case.seed}, from {case.seed_name}): {outcome}: "
                      f"{'; '.join(fails)}{' - ' + case.detail if case.detail else ''}\n"
                      + "".join(f"     mutation: {m}\n" for m in case.mutations)
                      + f"     error: {stderr.strip().splitlines()[-1][:300] if stderr.strip() else '(none)'}\n"
                      f"     reproduce: sh {dest}/repro.sh", flush=True)
            results.append(rec)
            log.write(json.dumps(rec) + "\n")
            log.flush()
            if len(results) % 100 == 0:
                print(f"fuzz: {len(results)} done, {time.monotonic() - t0:.0f} s", flush=True)
        if not fails and not args.keep and case.kind not in ("corpus",):
            shutil.rmtree(case.dir, ignore_errors=True)
        return rec

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        list(pool.map(one, fixed + jobs))
    log.close()
    shutil.rmtree(work / "cases", ignore_errors=True) if not args.keep else None

    # Report: inputs and outcomes per kind, failure classes, distinct signatures with an example each.
    wall = time.monotonic() - t0
    by_kind = collections.defaultdict(collections.Counter)
    classes = collections.Counter()
    sigs = collections.OrderedDict()
    for r in results:
        by_kind[r["kind"]][r["outcome"]] += 1
        for f in r["failures"]:
            classes[f] += 1
        if r["signature"]:
            s = sigs.setdefault(r["signature"], {"count": 0, "example": r.get("saved"), "kind": r["kind"]})
            s["count"] += 1
    failed = sum(1 for r in results if r["failures"])
    print(f"\nfuzz: seed {args.seed}: {len(results)} inputs in {wall:.0f} s, {failed} failed")
    for kind, counts in by_kind.items():
        print(f"  {kind:<9} {sum(counts.values()):>6}: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    if classes:
        print("failure classes:")
        for k, v in classes.most_common():
            print(f"  {v:>6}  {k}")
        print(f"distinct signatures ({len(sigs)}):")
        for s, info in sorted(sigs.items(), key=lambda kv: -kv[1]["count"]):
            print(f"  {info['count']:>6}  [{info['kind']}] {s}\n          e.g. {info['example']}")
    report = {"seed": args.seed, "count_per_kind": args.count, "inputs": len(results), "failed": failed,
              "wall_seconds": round(wall, 1), "outcomes": {k: dict(v) for k, v in by_kind.items()},
              "classes": dict(classes), "signatures": sigs}
    (work / "report.json").write_text(json.dumps(report, indent=2) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
