#!/usr/bin/env python3
"""The coupled ram-air wing's results as a wing engineer reads them (the `wing` part of summary.json, the
headline rows of summary.md and the console, plots/wing_*.png). Called by `ramair_fluid.py summary` for a
coupled case; /usr/bin/python3 with numpy, h5py and matplotlib (Debian's python3-numpy, -h5py, -matplotlib).

What it reads (nothing from them is run):
  constant/structure/wing.msh   the structure's mesh with its sets (Allrun: `fsi generate structure-coupled.yaml`):
                                ribs, leading_edge, trailing_edge, skin, confluence, toggles, line rows
  structure/results.h5          the canopy's frames (coordinates, displacement, velocity, cable_force)
  structure/coupling.csv        one row per window (through summarize.py, via ramair_summary.coupled_summary)
  LATEST/p, LATEST/wallShearStress, LATEST/polyMesh/points (or constant/polyMesh/points), constant/polyMesh
                                the fluid's load on the `wing` patch at the latest written time (ASCII)

What it reports (docs/RAMAIR.md, "The summary"):
  section angle of attack of every rib (its deformed chord from the leading-edge to the trailing-edge node,
  measured in the section's own plane: the plane of the free stream and the section's local lift direction),
  at the end and at every frame; the centre, tip and span-averaged values;
  CL and CD on the design projected area and on the loaded canopy's projected area; CD of the canopy, of the
  lines and of the system (canopy + lines; no payload in the anchored case), the system's L/D and glide angle;
  the spanwise lift distribution (pressure + wall shear on the fluid's wing patch) against the elliptic one;
  Cp along the chord at three span stations and a planform map of Cp;
  line tensions at the confluence per line and per row (A, B, ...), their vector sum against the anchor's
  reaction, the attachment lines' tensions per row and rib, the brake lines at the toggles;
  the convergence of CL, CD and the centre section's angle to the trim (`trim_reached`, criterion stated);
  Helmbold's lifting-line estimate at the flown attitude.
"""
import hashlib
import json
import math
import os
import re

import numpy as np


class InputError(Exception):
    """A missing or malformed input file; the message names the file (ramair_fluid.py turns it into exit 2)."""


# Trim criterion (g): over the last TRIM_FRACTION of the windows, the mean of its second half against the mean
# of its first half, and the centre section's angle from the first frame in it to the last.
TRIM_FRACTION = 0.2
TRIM_CL_REL = 0.01
TRIM_CD_REL = 0.02
TRIM_ALPHA_DEG = 0.25
TRIM_BALANCE_REL = 0.01
A0_PER_RAD = 2 * math.pi  # section lift slope of the estimate (thin airfoil)


# ---------------------------------------------------------------------------------------------------------
# Readers


def read_msh(path):
    """A Gmsh MSH 2.2 ASCII file as `fsi generate` writes it: (points [N x 3], groups) with groups =
    {"node": {name: [i]}, "line": {name: [(i, j)]}, "tri": {name: [(i, j, k)]}}, node indices from 0."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise InputError(f"{path}: cannot read the structure's mesh ({e}); Allrun writes it with "
                         "`fsi generate structure-coupled.yaml --out constant/structure`")

    def section(name):
        m = re.search(r"\$" + name + r"\n(.*?)\$End" + name, text, re.S)
        if not m:
            raise InputError(f"{path}: no ${name} section (an MSH 2.2 ASCII file from fsi generate expected)")
        return m.group(1).split("\n")

    names = {}
    lines = section("PhysicalNames")
    for line in lines[1:int(lines[0]) + 1]:
        dim, tag, name = line.split(maxsplit=2)
        names[(int(dim), int(tag))] = name.strip('"')
    lines = section("Nodes")
    n = int(lines[0])
    pts = np.array([[float(v) for v in l.split()[1:4]] for l in lines[1:n + 1]])
    groups = {"node": {}, "line": {}, "tri": {}}
    lines = section("Elements")
    kinds = {15: ("node", 0), 1: ("line", 1), 2: ("tri", 2)}
    for line in lines[1:int(lines[0]) + 1]:
        w = [int(v) for v in line.split()]
        etype, ntags = w[1], w[2]
        if etype not in kinds or ntags < 1 or w[3] == 0:
            continue
        kind, dim = kinds[etype]
        name = names.get((dim, w[3]))
        if name is None:
            raise InputError(f"{path}: element {w[0]} names physical group ({dim}, {w[3]}), which is not in "
                             "$PhysicalNames")
        nodes = tuple(v - 1 for v in w[3 + ntags:])
        groups[kind].setdefault(name, []).append(nodes[0] if kind == "node" else nodes)
    return pts, groups


class Results:
    """structure/results.h5: the model's connectivity and its frames in time order."""

    def __init__(self, path):
        try:
            import h5py
        except ImportError as e:
            raise InputError(f"{path}: h5py is needed to read the canopy's frames ({e}; Debian: python3-h5py)")
        self.path = path
        try:
            self.f = h5py.File(path, "r")
        except OSError as e:
            raise InputError(f"{path}: cannot read the structure's results ({e})")
        for key in ("mesh/lines", "mesh/triangles", "steps"):
            if key not in self.f:
                raise InputError(f"{path}: no /{key}")
        self.lines = self.f["mesh/lines"][()]
        self.triangles = self.f["mesh/triangles"][()]
        steps = [(float(g.attrs["time"]), name) for name, g in self.f["steps"].items()]
        if not steps:
            raise InputError(f"{path}: no frames in /steps")
        self.steps = sorted(steps)
        self.times = [t for t, _ in self.steps]

    def field(self, i, name):
        g = self.f["steps"][self.steps[i][1]]
        if name not in g:
            raise InputError(f"{self.path}: frame at t = {self.steps[i][0]:g} s has no '{name}' (structure.yaml's "
                             f"output.fields must list it)")
        return g[name][()]

    def reference(self):
        return self.field(0, "coordinates") - self.field(0, "displacement")


def map_nodes(msh_pts, ref, where):
    """Index of every mesh node among the results' nodes (the model renumbers them), by reference position."""
    size = float(np.abs(ref).max()) or 1.0
    out = np.empty(len(msh_pts), dtype=int)
    for a in range(0, len(msh_pts), 256):
        chunk = msh_pts[a:a + 256]
        d2 = ((chunk[:, None, :] - ref[None, :, :]) ** 2).sum(-1)
        j = d2.argmin(1)
        worst = math.sqrt(float(d2[np.arange(len(chunk)), j].max()))
        if worst > 1e-7 * size:
            raise InputError(f"{where}: the mesh's nodes are not the results' nodes (a node {worst:.3g} m from the "
                             "nearest): constant/structure/wing.msh and structure/results.h5 are of different scenes")
        out[a:a + 256] = j
    if len(set(out.tolist())) != len(out):
        raise InputError(f"{where}: two mesh nodes map onto one results node")
    return out


def _foam_body(text, path):
    m = re.compile(r"^(\d+)\s*\n\(", re.M).search(text, text.find("}") + 1 if "FoamFile" in text else 0)
    if not m:
        raise InputError(f"{path}: not an ASCII OpenFOAM list (writeFormat ascii expected)")
    return int(m.group(1)), m.end()


def read_points(path):
    try:
        with open(path) as f:
            t = f.read()
    except OSError as e:
        raise InputError(f"{path}: {e}")
    n, pos = _foam_body(t, path)
    vals = np.array(re.findall(r"\(([^()]+)\)", t[pos:])[:n])
    pts = np.array([v.split() for v in vals], dtype=float)
    if pts.shape != (n, 3):
        raise InputError(f"{path}: {len(pts)} points read, {n} announced")
    return pts


def read_patch_faces(case, patch="wing"):
    """The faces of one patch of constant/polyMesh (node lists) and the index of the first."""
    mesh = os.path.join(case, "constant", "polyMesh")
    try:
        with open(os.path.join(mesh, "boundary")) as f:
            b = f.read()
    except OSError as e:
        raise InputError(f"{mesh}/boundary: {e}")
    m = re.search(r"\b" + re.escape(patch) + r"\s*\{([^}]*)\}", b)
    if not m:
        raise InputError(f"{mesh}/boundary: no patch '{patch}'")
    n_faces = int(re.search(r"nFaces\s+(\d+)", m.group(1)).group(1))
    start = int(re.search(r"startFace\s+(\d+)", m.group(1)).group(1))
    path = os.path.join(mesh, "faces")
    try:
        with open(path) as f:
            t = f.read()
    except OSError as e:
        raise InputError(f"{path}: {e}")
    n, pos = _foam_body(t, path)
    faces = re.findall(r"\d+\(([^()]*)\)", t[pos:])
    if len(faces) < start + n_faces:
        raise InputError(f"{path}: {len(faces)} faces, the patch '{patch}' needs {start + n_faces}")
    return [[int(i) for i in faces[k].split()] for k in range(start, start + n_faces)], start


def read_owner(case):
    path = os.path.join(case, "constant", "polyMesh", "owner")
    try:
        with open(path) as f:
            t = f.read()
    except OSError as e:
        raise InputError(f"{path}: {e}")
    n, pos = _foam_body(t, path)
    owner = np.array(t[pos:t.find(")", pos)].split(), dtype=int)
    if len(owner) != n:
        raise InputError(f"{path}: {len(owner)} owners read, {n} announced")
    return owner


def read_patch_field(path, patch, n, cells=None):
    """The boundary values of one patch of an ASCII vol scalar or vector field: n scalars or n x 3 vectors. A
    zeroGradient patch (no value written) takes the internal field at its faces' owner cells (`cells`)."""
    try:
        with open(path) as f:
            t = f.read()
    except OSError as e:
        raise InputError(f"{path}: {e}")
    b = t.find("boundaryField")
    m = re.compile(r"\b" + re.escape(patch) + r"\s*\{").search(t, b)
    if b < 0 or not m:
        raise InputError(f"{path}: no boundaryField entry for the patch '{patch}'")
    entry = t[m.end():t.find("}", m.end())]
    if re.search(r"\btype\s+zeroGradient\s*;", entry) and "value" not in entry and cells is not None:
        i = re.compile(r"internalField\s+(nonuniform\s+List<(scalar|vector)>\s*(\d+)\s*\(|uniform\s+([^;]+);)")
        i = i.search(t)
        if not i:
            raise InputError(f"{path}: no internalField")
        if i.group(4) is not None:
            u = [float(x) for x in i.group(4).replace("(", " ").replace(")", " ").split()]
            return np.full(n, u[0]) if len(u) == 1 else np.tile(np.array(u), (n, 1))
        body = t[i.end():t.find("\n)", i.end())]
        vals = (np.array(body.split(), dtype=float) if i.group(2) == "scalar" else
                np.array([s.split() for s in re.findall(r"\(([^()]+)\)", body)], dtype=float))
        if len(vals) != int(i.group(3)) or cells.max() >= len(vals):
            raise InputError(f"{path}: internalField of {len(vals)} values, announced {i.group(3)}")
        vals = vals[cells]
        if not np.all(np.isfinite(vals)):
            raise InputError(f"{path}: non-finite values next to the patch '{patch}'")
        return vals
    v = re.compile(r"\bvalue\s+(nonuniform\s+List<(scalar|vector)>\s*(\d+)\s*\(|uniform\s+([^;]+);)").search(t, m.end())
    if not v or v.start() > m.end() + len(entry):
        raise InputError(f"{path}: the patch '{patch}' has no value")
    if v.group(4) is not None:
        u = [float(x) for x in v.group(4).replace("(", " ").replace(")", " ").split()]
        return np.full(n, u[0]) if len(u) == 1 else np.tile(np.array(u), (n, 1))
    count = int(v.group(3))
    if count != n:
        raise InputError(f"{path}: {count} values on the patch '{patch}', which has {n} faces")
    end = t.find("\n)", v.end())
    body = t[v.end():end]
    if v.group(2) == "scalar":
        vals = np.array(body.split(), dtype=float)
    else:
        vals = np.array([s.split() for s in re.findall(r"\(([^()]+)\)", body)], dtype=float)
    if len(vals) != n or not np.all(np.isfinite(vals)):
        raise InputError(f"{path}: the patch '{patch}' has {len(vals)} values (expected {n}) or non-finite ones")
    return vals


def latest_time(case):
    """The latest time directory of the case with the fluid's fields (p)."""
    best = None
    for name in os.listdir(case):
        try:
            t = float(name)
        except ValueError:
            continue
        if t > 0 and os.path.exists(os.path.join(case, name, "p")) and (best is None or t > best[0]):
            best = (t, name)
    if best is None:
        raise InputError(f"{case}: no time directory with a field p (reconstructPar -latestTime after a parallel run)")
    return best


def face_geometry(pts, faces):
    """Face centres and area vectors (OpenFOAM's: triangles fanned from the points' average)."""
    centres = np.empty((len(faces), 3))
    areas = np.empty((len(faces), 3))
    for k, f in enumerate(faces):
        p = pts[f]
        c0 = p.mean(0)
        a = 0.5 * np.cross(p - c0, np.roll(p, -1, 0) - c0)
        mag = np.linalg.norm(a, axis=1)
        tri_c = (p + np.roll(p, -1, 0) + c0) / 3.0
        areas[k] = a.sum(0)
        centres[k] = (tri_c * mag[:, None]).sum(0) / max(mag.sum(), 1e-300)
    return centres, areas


# ---------------------------------------------------------------------------------------------------------
# Geometry of the canopy


def unit(v):
    return v / np.linalg.norm(v)


class Canopy:
    """The structure's sets in the results' numbering: ribs (ring of nodes, leading and trailing edge node),
    the stations' edges, the skin, the confluence point, toggles and the suspension and brake lines."""

    def __init__(self, msh_path, res):
        pts, g = read_msh(msh_path)
        for kind, name in (("tri", "ribs"), ("tri", "skin"), ("node", "leading_edge"), ("node", "trailing_edge"),
                           ("node", "confluence")):
            if not g[kind].get(name):
                raise InputError(f"{msh_path}: no set '{name}' (a parafoil generator's mesh expected)")
        ref = res.reference()
        m = map_nodes(pts, ref, f"{msh_path} vs {res.path}")
        self.ref = ref
        le, te = set(g["node"]["leading_edge"]), set(g["node"]["trailing_edge"])
        # ribs: connected sets of the rib triangles' nodes (ribs share no node)
        parent = {}

        def find(a):
            while parent.setdefault(a, a) != a:
                parent[a] = parent[parent[a]]
                a = parent[a]
            return a

        for t in g["tri"]["ribs"]:
            for a in t[1:]:
                parent[find(a)] = find(t[0])
        comps = {}
        for a in parent:
            comps.setdefault(find(a), []).append(a)
        ribs = []
        for nodes in comps.values():
            nodes = sorted(nodes)  # the generator's ring order: leading edge, upper surface, lower surface
            l, t = [a for a in nodes if a in le], [a for a in nodes if a in te]
            if len(l) != 1 or len(t) != 1:
                raise InputError(f"{msh_path}: a rib with {len(l)} leading-edge and {len(t)} trailing-edge nodes")
            ribs.append({"ring": m[nodes], "le": int(m[l[0]]), "te": int(m[t[0]]), "msh_nodes": set(nodes)})
        ribs.sort(key=lambda r: ref[r["le"], 1])
        self.ribs = ribs
        self.le_nodes = m[sorted(le, key=lambda a: pts[a, 1])]
        self.te_nodes = m[sorted(te, key=lambda a: pts[a, 1])]
        if len(self.le_nodes) != len(self.te_nodes):
            raise InputError(f"{msh_path}: {len(le)} leading-edge and {len(te)} trailing-edge nodes")
        self.skin = np.array([[m[a] for a in t] for t in g["tri"]["skin"]])
        self.confluence = int(m[g["node"]["confluence"][0]])
        self.toggles = {side: int(m[g["node"][f"toggle_{side}"][0]]) for side in ("left", "right")
                        if g["node"].get(f"toggle_{side}")}
        # lines: the results' index of every mesh line, with its sets
        key = {(min(a, b), max(a, b)): i for i, (a, b) in enumerate(res.lines.tolist())}
        self.line_sets = {}
        for name, segs in g["line"].items():
            for a, b in segs:
                A, B = int(m[a]), int(m[b])
                i = key.get((min(A, B), max(A, B)))
                if i is None:
                    raise InputError(f"{msh_path}: line {a + 1}-{b + 1} of set '{name}' is not in {res.path}")
                self.line_sets.setdefault(i, set()).add(name)
        self.adj = {}
        for i, (a, b) in enumerate(res.lines.tolist()):
            self.adj.setdefault(a, []).append((i, b))
            self.adj.setdefault(b, []).append((i, a))
        self.rib_of_node = {}
        for k, r in enumerate(ribs):
            for a in r["ring"]:
                self.rib_of_node[int(a)] = k
        self.attachments = {int(m[a]) for a in g["node"].get("attachments", [])}
        self.rows = sorted(n[len("lines_"):] for n in g["line"] if re.fullmatch(r"lines_[A-Z]", n))

    def _walk(self, node, line, sets):
        """From `node` along `line` while the lines stay in `sets` and the nodes are interior (two lines): the
        node where the chain ends and the last line."""
        while True:
            other = next(o for i, o in self.adj[node] if i == line)
            nxt = [(i, o) for i, o in self.adj[other] if i != line]
            if len(nxt) != 1 or not (self.line_sets.get(nxt[0][0], set()) & sets):
                return other, line
            node, line = other, nxt[0][0]

    def suspension(self):
        """Every line at the confluence point: its row, side and the ribs it serves (from the sets, walking
        the cascade), the results' index of its piece at the confluence; and every attachment line (row, rib,
        its piece at the canopy)."""
        mains, attach = [], []
        for i, _ in self.adj.get(self.confluence, []):
            sets = self.line_sets.get(i, set())
            if "lines" not in sets:
                continue
            junction, _ = self._walk(self.confluence, i, {"main_lines"} if "main_lines" in sets else sets)
            rows, ribs = set(), []
            for j, _ in self.adj[junction]:
                js = self.line_sets.get(j, set())
                rows |= {s[len("lines_"):] for s in js if re.fullmatch(r"lines_[A-Z]", s)}
                if "main_lines" in js:
                    continue
                end, last = self._walk(junction, j, js)
                if end in self.rib_of_node:
                    ribs.append(self.rib_of_node[end])
                    row = "".join(sorted(s[len("lines_"):] for s in js if re.fullmatch(r"lines_[A-Z]", s)))
                    attach.append({"row": row, "rib": self.rib_of_node[end], "piece": last})
            if junction in self.rib_of_node:  # cascade 1: the line runs from the canopy to the confluence
                ribs.append(self.rib_of_node[junction])
                attach.append({"row": "".join(sorted(rows)), "rib": self.rib_of_node[junction],
                               "piece": self._walk(self.confluence, i, sets)[1]})
            side = "left" if "lines_left" in sets else "right" if "lines_right" in sets else "centre"
            mains.append({"row": "".join(sorted(rows)) or "?", "side": side, "ribs": sorted(ribs), "piece": i})
        brakes = []
        for side, tog in self.toggles.items():
            for i, _ in self.adj.get(tog, []):
                end, _ = self._walk(tog, i, self.line_sets.get(i, set()))
                brakes.append({"side": side, "rib": self.rib_of_node.get(end), "piece": i})
        return mains, attach, brakes


def section_frames(X, canopy, e_d, e_lift=(0.0, 0.0, 1.0)):
    """Per rib: the section's angle of attack [deg] (its chord, leading-edge minus trailing-edge node, in the
    plane of the free stream e_d and the section's local lift direction e_l = e_d x e_s, e_s the rib plane's
    normal made normal to e_d: the angle between the stream and the plane through the chord and e_s), e_l,
    the quarter-chord point; and the chord's angle projected on the plane of e_d and the wing's lift direction
    e_lift (alpha_xz: what the section angle is not at a tilted, toed-in tip)."""
    e_lift = np.asarray(e_lift, float)
    out = []
    for r in canopy.ribs:
        P = X[r["ring"]]
        c0 = P.mean(0)
        n = np.linalg.svd(P - c0)[2][-1]
        if n[1] < 0:
            n = -n
        e_s = unit(n - np.dot(n, e_d) * e_d)
        e_l = np.cross(e_d, e_s)
        chord = X[r["le"]] - X[r["te"]]
        alpha = math.degrees(math.atan2(np.dot(chord, e_l), -np.dot(chord, e_d)))
        out.append({"alpha": alpha, "e_l": e_l, "e_s": e_s, "qc": X[r["le"]] - 0.25 * chord,
                    "chord": float(np.linalg.norm(chord)),
                    "alpha_xz": math.degrees(math.atan2(np.dot(chord, e_lift), -np.dot(chord, e_d)))})
    return out


def strip_weights(s):
    """Trapezoid weights of stations at the (sorted) positions s: each stands for half the way to its
    neighbours."""
    w = np.zeros(len(s))
    d = np.diff(s)
    w[:-1] += 0.5 * d
    w[1:] += 0.5 * d
    return w


def line_drag_model(case, canopy):
    """The line_drag effect of the coupled scene: (1/2 rho C_D d, wind, the results' indices of its lines)."""
    import yaml
    path = os.path.join(case, "structure-coupled.yaml")
    try:
        with open(path) as f:
            scene = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        raise InputError(f"{path}: cannot read the coupled scene ({e})")
    ld = (scene.get("effects") or {}).get("line_drag") if isinstance(scene, dict) else None
    if not isinstance(ld, dict):
        return None
    try:
        sets = ld["lines"] if isinstance(ld["lines"], list) else [ld["lines"]]
        k = 0.5 * float(ld.get("density", 1.225)) * float(ld["cd"]) * float(ld["diameter"])
        wind = np.array(ld["wind"], float)
    except (KeyError, TypeError, ValueError) as e:
        raise InputError(f"{path}: effects.line_drag: {e}")
    if "function" in ld:
        raise InputError(f"{path}: effects.line_drag has a time function: the summary's line drag assumes the "
                         "steady wind")
    names = set()
    for s in sets:
        if not (isinstance(s, str) and s.startswith("wing/")):
            raise InputError(f"{path}: effects.line_drag.lines: '{s}' is not a set of the mesh 'wing'")
        names.add(s[len("wing/"):])
    idx = sorted(i for i, sets_i in canopy.line_sets.items() if sets_i & names)
    if not idx:
        raise InputError(f"{path}: effects.line_drag.lines {sets}: no line of constant/structure/wing.msh in them")
    return k, wind, np.array(idx)


def line_drag(model, res, i):
    """The line_drag effect's total force at frame i (structure/effects/AerodynamicDrag.cpp: the relative wind
    at each cable's mid-point, the force on its current length)."""
    if model is None:
        return np.zeros(3)
    k, wind, idx = model
    x, v = res.field(i, "coordinates"), res.field(i, "velocity")
    a, b = res.lines[idx, 0], res.lines[idx, 1]
    d = x[b] - x[a]
    rel = wind - 0.5 * (v[a] + v[b])
    wn = rel - ((rel * d).sum(1) / (d * d).sum(1))[:, None] * d
    return k * ((np.linalg.norm(wn, axis=1) * np.linalg.norm(d, axis=1))[:, None] * wn).sum(0)


def projected_area(X, tris, e_l):
    a = np.cross(X[tris[:, 1]] - X[tris[:, 0]], X[tris[:, 2]] - X[tris[:, 0]])
    return 0.25 * float(np.abs(a @ e_l).sum())  # a closed skin is seen twice: half of the |n.e| dA


def helmbold_slope(ar):
    k = A0_PER_RAD / (math.pi * ar)
    return A0_PER_RAD / (math.sqrt(1 + k * k) + k)


def elliptic_mean(total, b, s0, lo, hi):
    """Mean over [lo, hi] of the elliptic lift per unit span of total `total` on the span b centred at s0."""
    def prim(s):
        u = min(1.0, max(-1.0, 2 * (s - s0) / b))
        return 0.5 * (u * math.sqrt(1 - u * u) + math.asin(u))
    return 4 * total / (math.pi * b) * (b / 2) * (prim(hi) - prim(lo)) / (hi - lo)


# ---------------------------------------------------------------------------------------------------------
# The analysis


def _finite(name, *values):
    for v in values:
        if not np.all(np.isfinite(v)):
            raise InputError(f"the wing summary's '{name}' is not finite: an input is broken")


def analyse(case, rec, c):
    """The `wing` part of summary.json from a finished coupled case; c = ramair_summary.coupled_summary(...)."""
    s, d = rec["settings"], rec["derived"]
    e_d, e_l = np.array(d["flow_dir"], float), np.array(d["lift_dir"], float)
    e_s = np.cross(e_l, e_d)  # the span direction (+y: right)
    q = d["q"]
    a_design = d["Aref"]
    res = Results(os.path.join(case, "structure", "results.h5"))
    canopy = Canopy(os.path.join(case, "constant", "structure", "wing.msh"), res)
    last = len(res.steps) - 1
    X = res.field(last, "coordinates")
    X0 = canopy.ref
    t_end = res.times[last]
    dt = d["deltaT"]
    if abs(t_end - c["time"]) > 0.5 * dt:
        raise InputError(f"{res.path}: the last frame is at t = {t_end:g} s, the last window at {c['time']:g} s")
    w = {"source": {"structure_mesh": "constant/structure/wing.msh", "structure_frames": "structure/results.h5",
                    "frame_time_s": t_end}}

    # (a) section angles of attack
    design, end = section_frames(X0, canopy, e_d, e_l), section_frames(X, canopy, e_d, e_l)
    s_end = np.array([np.dot(f["qc"], e_s) for f in end])
    order = np.argsort(s_end)
    wts = np.zeros(len(end))
    wts[order] = strip_weights(s_end[order])
    alpha = np.array([f["alpha"] for f in end])
    cosphi = np.array([float(np.dot(f["e_l"], e_l)) for f in end])
    centre = int(np.argmin(np.abs(s_end)))
    mean_alpha = float((wts * alpha).sum() / wts.sum())
    s_des = np.array([np.dot(f["qc"], e_s) for f in design])
    o = np.argsort(s_des)
    w_des = np.zeros(len(design))
    w_des[o] = strip_weights(s_des[o])
    design_mean = float((w_des * np.array([f["alpha"] for f in design])).sum() / w_des.sum())
    hist = {"time_s": [], "window": [], "centre_deg": [], "tip_deg": [], "span_average_deg": []}
    for i in range(len(res.steps)):
        fr = section_frames(res.field(i, "coordinates"), canopy, e_d)
        a = np.array([f["alpha"] for f in fr])
        sp = np.array([np.dot(f["qc"], e_s) for f in fr])
        o = np.argsort(sp)
        ww = np.zeros(len(fr))
        ww[o] = strip_weights(sp[o])
        hist["time_s"].append(res.times[i])
        hist["window"].append(int(round(res.times[i] / dt)))
        hist["centre_deg"].append(float(a[int(np.argmin(np.abs(sp)))]))
        hist["tip_deg"].append(float(0.5 * (a[0] + a[-1])))
        hist["span_average_deg"].append(float((ww * a).sum() / ww.sum()))
    _finite("section angles", alpha, hist["span_average_deg"])
    w["section_alpha"] = {
        "definition": "angle of each rib's chord (leading-edge node minus trailing-edge node of the deformed rib) "
                      "to the free stream, in the plane of the free stream and the section's local lift direction "
                      "(normal to the free stream and to the local span direction, the rib plane's normal made "
                      "normal to the stream): the angle between the stream and the plane through the chord and the "
                      "local span direction, the angle the section meets the air at; positive nose up. alpha_xz: "
                      "the chord projected on the plane of the stream and the wing's lift direction instead (equal "
                      "at the centre; smaller at the tilted tips, and different where a rib is toed in)",
        "centre_deg": float(alpha[centre]), "tip_deg": float(0.5 * (alpha[0] + alpha[-1])),
        "tip_left_deg": float(alpha[0]), "tip_right_deg": float(alpha[-1]),
        "span_average_deg": mean_alpha,
        "tips_te_inboard_of_le_m": float(0.5 * (np.dot(X[canopy.ribs[-1]["le"]] - X[canopy.ribs[-1]["te"]], e_s)
                                                - np.dot(X[canopy.ribs[0]["le"]] - X[canopy.ribs[0]["te"]], e_s))),
        "tips_te_inboard_is": "how far the tip ribs' trailing-edge nodes lie inboard of their leading-edge nodes along "
                              "the projected span (0 in the design: each rib in a plane along the stream)",
        "weighting": "trapezoid rule over the ribs' positions along the projected span (each rib stands for half "
                     "the way to its neighbours)",
        "ribs": [{"rib": k, "span_position_m": float(s_end[k]), "alpha_deg": float(alpha[k]),
                  "alpha_design_deg": float(design[k]["alpha"]), "cos_dihedral": float(cosphi[k]),
                  "alpha_xz_deg": end[k]["alpha_xz"], "alpha_xz_design_deg": design[k]["alpha_xz"],
                  "chord_m": end[k]["chord"], "chord_design_m": design[k]["chord"], "weight_m": float(wts[k]),
                  "te_inboard_of_le_m": float(np.sign(s_end[k])
                                              * np.dot(X[canopy.ribs[k]["le"]] - X[canopy.ribs[k]["te"]], e_s))}
                 for k in range(len(end))],
        "history": hist,
    }

    # (e) areas, span, forces and coefficients
    skin = canopy.skin
    a_def = projected_area(X, skin, e_l)
    a_des_struct = projected_area(X0, skin, e_l)
    span_def = float((X[np.unique(skin)] @ e_s).ptp())
    span_des = float((X0[np.unique(skin)] @ e_s).ptp())
    fluid = np.array(c["fluid_force_N"], float)
    drag_model = line_drag_model(case, canopy)
    lines = line_drag(drag_model, res, last)
    hist["line_drag_N"] = [line_drag(drag_model, res, i).tolist() for i in range(len(res.steps))]
    system = fluid + lines
    L, D = float(fluid @ e_l), float(fluid @ e_d)
    Ll, Dl = float(lines @ e_l), float(lines @ e_d)
    Ls, Ds = L + Ll, D + Dl
    _finite("forces", fluid, lines)

    def coeffs(area):
        k = 1.0 / (q * area)
        return {"area_m2": area, "CL_canopy": L * k, "CD_canopy": D * k, "CD_lines": Dl * k, "CL_lines": Ll * k,
                "CL_system": Ls * k, "CD_system": Ds * k}

    w["reference"] = {
        "design_projected_area_m2": a_design,
        "design_projected_area_is": "the fluid's design skin (STL) projected on the plane normal to the lift "
                                    "direction: forceCoeffs' Aref",
        "design_projected_area_structure_m2": a_des_struct,
        "deformed_projected_area_m2": a_def,
        "deformed_projected_area_is": "the loaded canopy's skin (structure, last frame) projected on the plane "
                                      "normal to the lift direction",
        "planform_change": a_def / a_des_struct - 1,
        "design_span_m": span_des, "deformed_span_m": span_def, "span_change": span_def / span_des - 1,
        "design_aspect_ratio": span_des ** 2 / a_des_struct, "deformed_aspect_ratio": span_def ** 2 / a_def,
        "q_Pa": q,
    }
    w["forces"] = {
        "canopy_N": fluid.tolist(), "lift_canopy_N": L, "drag_canopy_N": D,
        "line_drag_N": lines.tolist(), "lift_lines_N": Ll, "drag_lines_N": Dl,
        "line_drag_source": "recomputed with the structure's line_drag model (1/2 rho C_D d |U_n| U_n per unit length, "
                            "U_n the relative wind normal to the cable; rho, C_D, d, wind and the line sets of "
                            "structure-coupled.yaml's effects.line_drag) on the lines of the last frame",
        "system_N": system.tolist(), "lift_system_N": Ls, "drag_system_N": Ds,
        "system_is": "canopy + lines: the anchored case has no payload (and no riser)",
    }
    w["coefficients"] = {"design_area": coeffs(a_design), "deformed_area": coeffs(a_def),
                         "L_over_D_canopy": L / D, "L_over_D_system": Ls / Ds,
                         "glide_angle_deg": math.degrees(math.atan2(Ds, Ls)),
                         "glide_angle_is": "tan(gamma) = CD_system / CL_system (canopy + lines)"}

    # (h) the estimate at the flown attitude
    ar = w["reference"]["deformed_aspect_ratio"]
    slope = helmbold_slope(ar)
    a_eff = mean_alpha - s["zero_lift_angle"]
    cl_est = slope * math.radians(a_eff)
    cl_def = L / (q * a_def)
    w["estimate"] = {
        "formula": "Helmbold: CL = a0 (alpha - alpha0) / (sqrt(1 + (a0/(pi AR))^2) + a0/(pi AR)), a0 = 2 pi",
        "alpha_deg": mean_alpha, "alpha_is": "the span-averaged section angle at the end",
        "zero_lift_angle_deg": s["zero_lift_angle"], "aspect_ratio": ar,
        "aspect_ratio_is": "deformed projected span^2 / deformed projected area",
        "arc_factor": 1.0,
        "arc_factor_is": "1: the section angles are measured in each section's own plane and averaged over the "
                         "projected span, and the coefficient is on the projected area, so each section's lift "
                         "counts with its vertical share cos(dihedral) already; the arch's effect on the induced "
                         "angle is not modelled",
        "mean_cos_dihedral": float((wts * cosphi).sum() / wts.sum()),
        "CL_estimate": cl_est, "CL_canopy_deformed_area": cl_def, "CL_over_estimate": cl_def / cl_est,
        "CL_estimate_design": helmbold_slope(w["reference"]["design_aspect_ratio"])
                              * math.radians(design_mean - s["zero_lift_angle"]),
        "CL_estimate_design_is": "the same estimate for the design canopy (its ribs' angles and aspect ratio)",
        "ratio_is": "CL of the canopy on the deformed projected area / Helmbold's CL at the span-averaged section "
                    "angle and the deformed aspect ratio",
    }

    # (f) lines
    w["lines"] = line_tensions(res, canopy, X, last, c, w["forces"])

    # (b), (c) the fluid's load on the wing patch
    w["fluid_surface"] = fluid_surface(case, rec, c, canopy, X, end, s_end, w)

    # (g) convergence to the trim
    w["trim"] = trim(c, hist, a_design, q)

    # the error against the converged answer (studies/ramair/trim_study.py), where this case is the main job
    w["converged_reference"] = converged_reference(case, rec, w)

    faces = w["fluid_surface"].pop("_faces")  # arrays for the pictures, not for summary.json
    w["plots"] = plots(case, rec, c, canopy, X, X0, design, end, s_end, w, faces)
    return w


def line_tensions(res, canopy, X, last, c, w_forces):
    T = res.field(last, "cable_force")
    mains, attach, brakes = canopy.suspension()
    if not mains:
        raise InputError(f"{res.path}: no suspension line at the confluence point")
    conf = canopy.confluence
    total = np.zeros(3)
    out = []
    for m in sorted(mains, key=lambda m: (m["row"], {"left": 0, "centre": 1, "right": 2}[m["side"]], m["ribs"])):
        a, b = res.lines[m["piece"]]
        other = b if a == conf else a
        e = unit(X[other] - X[conf])
        t = float(T[m["piece"]])
        total += t * e
        ribs = "-".join(str(r) for r in m["ribs"])
        out.append({"name": f"{m['row']} {m['side']} (rib{'s' if len(m['ribs']) > 1 else ''} {ribs})", "row": m["row"],
                    "side": m["side"], "ribs": m["ribs"], "tension_N": t, "direction": e.tolist()})
    rows = {}
    for m in out:
        r = rows.setdefault(m["row"], {"lines": 0, "sum_N": 0.0, "max_N": 0.0})
        r["lines"] += 1
        r["sum_N"] += m["tension_N"]
        r["max_N"] = max(r["max_N"], m["tension_N"])
    tsum = sum(r["sum_N"] for r in rows.values())
    for r in rows.values():
        r["share"] = r["sum_N"] / tsum if tsum else None
    att = {}
    for a in attach:
        att.setdefault(a["row"], {})[str(a["rib"])] = float(T[a["piece"]])
    brk = {}
    for b in brakes:
        brk.setdefault(b["side"], []).append({"rib": b["rib"], "tension_N": float(T[b["piece"]])})
    reaction = np.array(c["anchor_force_N"], float)
    aero_lines = np.array(c["fluid_force_N"], float) + np.array(w_forces["line_drag_N"], float)
    pull = total.copy()
    for b in brakes:
        tog = canopy.toggles[b["side"]]
        a, o = res.lines[b["piece"]]
        pull += float(T[b["piece"]]) * unit(X[o if a == tog else a] - X[tog])
    _finite("line tensions", T, total)
    return {
        "at_confluence": out,
        "at_confluence_is": "the tension in each suspension line's piece attached to the confluence point "
                            "(cable_force of the last frame); rows and ribs from the generator's sets (lines_A ..., "
                            "main_lines) along the cascade",
        "rows": rows,
        "attachments": att,
        "attachments_is": "the tension in each row's line piece attached to the canopy, by rib (0 = left tip)",
        "brakes": brk, "brakes_is": "the tension in each brake line's piece attached to its toggle",
        "vector_sum_at_confluence_N": total.tolist(),
        "anchor_reaction_N": reaction.tolist(),
        "vector_sum_vs_anchor": float(np.linalg.norm(total + reaction) / max(np.linalg.norm(reaction), 1e-30)),
        "vector_sum_vs_anchor_is": "|sum + anchor reaction| / |anchor reaction|: the confluence node's balance; the "
                                   "rest is the line drag the node carries itself",
        "lines_pull_on_supports_N": pull.tolist(),
        "lines_pull_on_supports_is": "the vector sum of the tensions at the confluence point and at the toggles",
        "aero_plus_line_drag_N": aero_lines.tolist(),
        "pull_vs_aero_plus_line_drag": float(np.linalg.norm(pull - aero_lines)
                                             / max(np.linalg.norm(aero_lines), 1e-30)),
        "line_tension_max_N": float(T[[i for i, s in canopy.line_sets.items() if "lines" in s]].max()),
    }


def fluid_surface(case, rec, c, canopy, X, end, s_end, w):
    """Spanwise lift (pressure + wall shear on the wing patch, the latest time), Cp at three stations."""
    s, d = rec["settings"], rec["derived"]
    e_d, e_l = np.array(d["flow_dir"], float), np.array(d["lift_dir"], float)
    e_s = np.cross(e_l, e_d)
    t, name = latest_time(case)
    pts_path = os.path.join(case, name, "polyMesh", "points")
    if not os.path.exists(pts_path):
        pts_path = os.path.join(case, "constant", "polyMesh", "points")
    faces, start = read_patch_faces(case)
    pts = read_points(pts_path)
    centres, sf = face_geometry(pts, faces)
    cells = read_owner(case)[start:start + len(faces)]
    p = read_patch_field(os.path.join(case, name, "p"), "wing", len(faces), cells)
    wss_path = os.path.join(case, name, "wallShearStress")
    viscous = os.path.exists(wss_path)
    wss = read_patch_field(wss_path, "wing", len(faces)) if viscous else np.zeros((len(faces), 3))
    mag = np.linalg.norm(sf, axis=1)
    # the face's load on the wing: rho (p Sf + Sf . devReff) = rho (p Sf - |Sf| wallShearStress), Sf out of the
    # fluid (into the wing), p and wallShearStress kinematic (OpenFOAM's forces function object)
    f = s["rho"] * (p[:, None] * sf - mag[:, None] * wss)
    total = f.sum(0)
    lift_faces = f @ e_l
    L = float(lift_faces.sum())
    sc = centres @ e_s
    sp = pts[np.unique(np.concatenate([np.array(x) for x in faces]))] @ e_s
    s_lo, s_hi = float(sp.min()), float(sp.max())
    b = s_hi - s_lo
    s0 = 0.5 * (s_lo + s_hi)
    # strips: the cells between the deformed ribs (the outer edges at the skin's ends), and 31 equal strips
    rib_s = np.sort(s_end)
    edges = np.concatenate([[s_lo], rib_s[1:-1], [s_hi]])
    cells = []
    for k in range(len(edges) - 1):
        lo, hi = edges[k], edges[k + 1]
        sel = (sc >= lo) & (sc < hi) if k < len(edges) - 2 else (sc >= lo) & (sc <= hi)
        l = float(lift_faces[sel].sum()) / (hi - lo)
        le = elliptic_mean(L, b, s0, lo, hi)
        cells.append({"cell": k + 1, "from_m": float(lo), "to_m": float(hi), "lift_per_span_N_m": l,
                      "elliptic_N_m": le, "ratio_to_elliptic": l / le})
    fine_edges = np.concatenate([np.linspace(edges[k], edges[k + 1], 5)[:-1] for k in range(len(edges) - 1)]
                                + [edges[-1:]])
    nb = len(fine_edges) - 1
    fine = []
    for k in range(nb):
        lo, hi = fine_edges[k], fine_edges[k + 1]
        sel = (sc >= lo) & (sc < hi) if k < nb - 1 else (sc >= lo)
        fine.append(float(lift_faces[sel].sum()) / (hi - lo))
    fc = 0.5 * (fine_edges[1:] + fine_edges[:-1])
    ncell = len(cells)
    centre_cells = [cells[(ncell - 1) // 2], cells[ncell // 2]]
    tip_cells = [cells[0], cells[-1]]
    fl = np.array(c["fluid_force_N"], float)
    out = {
        "time_s": t, "time_directory": name, "points": os.path.relpath(pts_path, case),
        "load_is": "pressure + wall shear (wallShearStress)" if viscous else
                   "pressure only (no wallShearStress field: the shear's share of the lift is the difference to "
                   "the interface force)",
        "force_sum_N": total.tolist(), "lift_sum_N": L,
        "lift_sum_vs_interface": L / float(fl @ e_l) - 1,
        "lift_sum_vs_interface_is": "the patch's lift summed here over the coupling's interface lift (the "
                                    "adapter's, same window), minus 1",
        "span_m": b,
        "cells": cells,
        "centre_ratio_to_elliptic": float(np.mean([x["ratio_to_elliptic"] for x in centre_cells])),
        "tip_ratio_to_elliptic": float(np.mean([x["ratio_to_elliptic"] for x in tip_cells])),
        "strips": {"centre_m": fc.tolist(), "lift_per_span_N_m": fine},
        "lift_per_span_is": "the lift (component along the lift direction) of the wing patch's faces whose centres "
                            "lie in the strip, over the strip's width along the projected span; cells: between "
                            "the deformed ribs (the outer ones to the skin's ends); strips: each cell in four",
        "elliptic_is": "4 L / (pi b) sqrt(1 - (2 y / b)^2), L the patch's lift, b its projected span",
    }
    _finite("lift distribution", fine, total)
    # the pitching moment of the patch's load about the deformed centre section's quarter-chord point, on the
    # design area and the centre rib's design chord; nose up positive (about +span: x downstream, z up)
    kc = int(np.argmin(np.abs(s_end)))
    ref = np.asarray(end[kc]["qc"], float)
    m_s = float(np.cross(centres - ref, f).sum(0) @ e_s)
    c_ref = float(w["section_alpha"]["ribs"][kc]["chord_design_m"])
    out["Cm_quarter_chord"] = m_s / (d["q"] * d["Aref"] * c_ref)
    out["Cm_is"] = ("pitching moment of pressure + wall shear on the wing patch about the deformed centre "
                    "section's quarter-chord point, along the span axis (nose up positive), over q x design "
                    "projected area x the centre rib's design chord")
    out["Cm_reference_point_m"] = ref.tolist()
    out["Cm_reference_chord_m"] = c_ref
    _finite("pitching moment", m_s)
    # (c) Cp along three ribs of the right half: the faces near each deformed rib's plane
    cp = p / (0.5 * s["speed"] ** 2)
    n_out = -sf / mag[:, None]
    right = [k for k in range(len(s_end)) if s_end[k] > 0.05 * b]
    centre_rib = int(np.argmin(np.abs(s_end)))
    picks = [("centre", centre_rib)]
    if len(right) >= 2:
        picks.append(("mid", min(right, key=lambda k: abs(s_end[k] - s0 - 0.25 * b))))
        picks.append(("near tip", sorted(right, key=lambda k: s_end[k])[-2]))
    band = 0.03
    stations = []
    for label, k in picks:
        r = canopy.ribs[k]
        ring = X[r["ring"]]
        c0 = ring.mean(0)
        normal = np.linalg.svd(ring - c0)[2][-1]
        LE, TE = X[r["le"]], X[r["te"]]
        chord = TE - LE
        xc_all = (centres - LE) @ chord / np.dot(chord, chord)
        near = np.abs((centres - c0) @ normal) <= band
        sel = near & (xc_all > -0.1) & (xc_all < 1.1)
        xc = xc_all[sel]
        up = end[k]["e_l"]
        upper = n_out[sel] @ up > 0
        cps = cp[sel]
        st = {"station": label, "rib": k, "span_position_m": float(s_end[k]), "band_m": band, "faces": int(sel.sum()),
              "alpha_deg": end[k]["alpha"],
              "upper": {"x_over_c": xc[upper].tolist(), "cp": cps[upper].tolist()},
              "lower": {"x_over_c": xc[~upper].tolist(), "cp": cps[~upper].tolist()}}
        if upper.any():
            j = int(np.argmin(cps[upper]))
            st["cp_min_upper"] = float(cps[upper][j])
            st["cp_min_upper_x_over_c"] = float(xc[upper][j])
        if (~upper).any():
            st["cp_max_lower"] = float(cps[~upper].max())
        stations.append(st)
    out["cp"] = {"is": "Cp = p / (U^2 / 2) (p kinematic, the free stream's p = 0) on the wing patch's faces within "
                       f"{band} m of the plane of a deformed rib (the centre rib, the right rib nearest half the "
                       "semi-span, the right rib next to the tip); x/c along the rib's chord (leading- to "
                       "trailing-edge node); upper: faces whose outward normal points up the section's local lift "
                       "direction",
                 "stations": stations}
    out["_faces"] = {"pts": pts, "faces": faces, "cp": cp, "n_out": n_out, "centres": centres}
    return out


def trim(c, hist, area, q):
    h = c["history"]
    n = len(h["time"])
    start = n - max(2, int(round(TRIM_FRACTION * n)))
    mid = (start + n) // 2
    lift = [float(x) for x in h["lift_N"]]
    drag = [float(x) for x in h["drag_N"]]

    def change(x):
        a, b = np.mean(x[start:mid]), np.mean(x[mid:])
        return float(abs(b - a) / max(abs(b), 1e-30))

    # the frames from the last one at or before the start of that part of the run to the end
    t0 = h["time"][start - 1] if start > 0 else 0.0
    before = [k for k, tk in enumerate(hist["time_s"]) if tk <= t0 + 1e-9]
    first = before[-1] if before else 0
    frames = list(range(first, len(hist["time_s"])))
    a_change = (abs(hist["centre_deg"][-1] - hist["centre_deg"][frames[0]]) if len(frames) >= 2 else None)
    cl_c, cd_c = change(lift), change(drag)
    bal = c["equilibrium_relative"]
    reached = (cl_c < TRIM_CL_REL and cd_c < TRIM_CD_REL and a_change is not None and a_change < TRIM_ALPHA_DEG
               and bal < TRIM_BALANCE_REL)
    return {
        "trim_reached": bool(reached),
        "criterion": f"over the last {100 * TRIM_FRACTION:.0f} % of the windows (from window {start + 1}): the mean "
                     f"CL and CD of its second half differ from those of its first half by less than "
                     f"{100 * TRIM_CL_REL:g} % and {100 * TRIM_CD_REL:g} %, the centre section's angle of attack "
                     f"changes by less than {TRIM_ALPHA_DEG:g} deg (first frame in it to the last), and the "
                     f"supports balance the applied load within {100 * TRIM_BALANCE_REL:g} % at the end",
        "CL_change": cl_c, "CD_change": cd_c, "centre_alpha_change_deg": a_change,
        "balance": bal, "from_window": start + 1, "alpha_frames": [hist["window"][k] for k in frames],
    }


CONVERGED = "ramair_convergence.json"  # beside this file (share/fsi), from docs/data


def converged_reference(case, rec, w, path=None):
    """This run's CL, CD and trim angles against the values the convergence study (docs/data/ramair_convergence
    .json) extrapolated to a fine structure, when this case has the inputs that study ran as the main job (the
    same structure.yaml, byte for byte, and the same settings); otherwise why there is no reference."""
    if path is None:
        # share/fsi (FSI_SHARE_DIR, set by fsi-env.sh; or beside this file in an install), else the source tree's
        # docs/data: a script run through build/share/fsi's symbolic links imports this module from the sources
        # (python puts the script's resolved folder on sys.path)
        here = os.path.dirname(os.path.abspath(__file__))
        places = [os.environ.get("FSI_SHARE_DIR", ""), here,
                  os.path.join(os.path.dirname(os.path.dirname(here)), "docs", "data")]
        path = next((os.path.join(d, CONVERGED) for d in places if d and os.path.exists(os.path.join(d, CONVERGED))),
                    os.path.join(here, CONVERGED))
    if not os.path.exists(path):
        return {"available": False, "why": f"no {CONVERGED} in share/fsi ($FSI_SHARE_DIR) or beside ramair_wing.py"}
    try:
        with open(path) as f:
            ref = json.load(f)
        inputs, best = ref["main_job_inputs"], ref["converged"]
    except (OSError, ValueError, KeyError) as e:
        raise InputError(f"{path}: not a convergence study's result ({e})")
    yaml_path = os.path.join(case, "structure.yaml")
    try:
        with open(yaml_path, "rb") as f:
            sha = hashlib.sha256(f.read()).hexdigest()
    except OSError as e:
        raise InputError(f"{yaml_path}: {e}")
    if sha != inputs["structure_yaml_sha256"] or not same_settings(rec["settings"], inputs["settings"]):
        which = "structure.yaml" if sha != inputs["structure_yaml_sha256"] else "the settings"
        return {"available": False,
                "why": f"{which} differ from the main job's the convergence study ran ({ref.get('commit', '?')}): "
                       "its converged answer is of that wing (docs/AERODYNAMICS.md, rung 3)"}
    des, a = w["coefficients"]["design_area"], w["section_alpha"]
    now = {"CL": des["CL_canopy"], "CD": des["CD_canopy"], "CD_system": des["CD_system"],
           "alpha_centre_deg": a["centre_deg"], "alpha_span_average_deg": a["span_average_deg"]}
    out = {"available": True, "source": CONVERGED, "commit": ref.get("commit"), "converged_is": ref.get("converged_is")}
    for k, v in now.items():
        if k in best:
            c, bar = best[k]["extrapolated"], best[k]["error_bar"]
            out[k] = {"this_run": v, "converged": c, "error_bar": bar, "error": v - c,
                      "relative": (v / c - 1) if not k.startswith("alpha") else None}
    return out


def same_settings(a, b):
    """Two settings records alike, a key missing from one standing for its default (a setting added after the
    study ran, at its default, changes nothing)."""
    import ramair_settings  # same folder; the settings' defaults
    default = {k: v[1] for k, v in ramair_settings.SETTINGS.items()}
    return all(a.get(k, default.get(k)) == b.get(k, default.get(k)) for k in set(a) | set(b))


def _num(x, spec):
    return "n/a" if x is None else format(x, spec)


def headline(w):
    """Lines for the console."""
    a, co, r, li, fs, e, t = (w["section_alpha"], w["coefficients"], w["reference"], w["lines"],
                              w["fluid_surface"], w["estimate"], w["trim"])
    des, dfm = co["design_area"], co["deformed_area"]
    rows = li["rows"]
    vs = li["vector_sum_at_confluence_N"]
    return [
        f"  section angle of attack: centre {a['centre_deg']:.2f} deg, tips {a['tip_deg']:.2f} deg, span average "
        f"{a['span_average_deg']:.2f} deg (design: centre {a['ribs'][len(a['ribs']) // 2]['alpha_design_deg']:.2f})",
        f"  projected area {r['deformed_projected_area_m2']:.3f} m^2 loaded vs {r['design_projected_area_m2']:.3f} "
        f"design ({100 * r['planform_change']:+.1f} %), span {r['deformed_span_m']:.3f} m "
        f"({100 * r['span_change']:+.1f} %), "
        f"AR {r['deformed_aspect_ratio']:.2f}; the tips' trailing edges {100 * a['tips_te_inboard_of_le_m']:.1f} cm "
        "inboard of their leading edges",
        f"  on the design area: CL {des['CL_canopy']:.4f}, CD canopy {des['CD_canopy']:.4f} + lines "
        f"{des['CD_lines']:.4f} = system {des['CD_system']:.4f}; on the loaded area: CL {dfm['CL_canopy']:.4f}, "
        f"CD system {dfm['CD_system']:.4f}",
        f"  L/D canopy {co['L_over_D_canopy']:.2f}, system {co['L_over_D_system']:.2f}; glide angle "
        f"{co['glide_angle_deg']:.2f} deg (no payload)",
        "  lines at the confluence: rows " + ", ".join(f"{k} {v['sum_N']:.1f} N ({100 * v['share']:.0f} %)"
                                                        for k, v in sorted(rows.items()))
        + f"; vector sum ({vs[0]:.2f}, {vs[1]:.2f}, {vs[2]:.2f}) N vs anchor reaction "
          f"({', '.join(f'{-x:.2f}' for x in li['anchor_reaction_N'])}) N",
        f"  lift distribution: centre {fs['centre_ratio_to_elliptic']:.2f}, tips {fs['tip_ratio_to_elliptic']:.2f} "
        f"x elliptic; patch lift vs interface {100 * fs['lift_sum_vs_interface']:+.2f} %",
        f"  Helmbold at the flown attitude (alpha {e['alpha_deg']:.2f} deg, AR {e['aspect_ratio']:.2f}): CL "
        f"{e['CL_estimate']:.3f}; CL / estimate {e['CL_over_estimate']:.2f}",
        f"  trim reached: {'yes' if t['trim_reached'] else 'NO'} (CL {100 * t['CL_change']:.2f} %, CD "
        f"{100 * t['CD_change']:.2f} %, centre alpha {_num(t['centre_alpha_change_deg'], '.3f')} deg over the last "
        f"{100 * TRIM_FRACTION:.0f} %, balance {100 * t['balance']:.3f} %)",
    ] + converged_lines(w.get("converged_reference", {}))


def converged_lines(r):
    if not r:
        return []
    if not r.get("available"):
        return [f"  error against the converged answer: {converged_text(r)}"]
    return ["  error against the converged answer (" + r["source"] + ", " + (r.get("converged_is") or "") + "): "
            + converged_text(r)]


def converged_text(r):
    """The figures of converged_reference's result (or why there are none), for the console and summary.md."""
    if not r.get("available"):
        return f"not known here ({r.get('why', 'no reference')})"
    parts = []
    for k, name in (("CL", "CL"), ("CD", "CD canopy"), ("CD_system", "CD system")):
        if k in r:
            x = r[k]
            parts.append(f"{name} {x['this_run']:.4f} vs {x['converged']:.4f} +- {x['error_bar']:.4f} "
                         f"({100 * x['relative']:+.1f} %)")
    for k, name in (("alpha_centre_deg", "centre section"), ("alpha_span_average_deg", "span-averaged section")):
        if k in r:
            x = r[k]
            parts.append(f"{name} {x['this_run']:.2f} vs {x['converged']:.2f} +- {x['error_bar']:.2f} deg "
                         f"({x['error']:+.2f} deg)")
    return "; ".join(parts)


def table_rows(w):
    """Rows of summary.md: (quantity, this run, reference/definition)."""
    a, co, r, li, fs, e, t, fo = (w["section_alpha"], w["coefficients"], w["reference"], w["lines"],
                                  w["fluid_surface"], w["estimate"], w["trim"], w["forces"])
    des, dfm = co["design_area"], co["deformed_area"]
    v = lambda x: "(" + ", ".join(f"{y:.2f}" for y in x) + ")"
    rows = [
        ("section angle of attack: centre, tips, span average [deg]",
         f"{a['centre_deg']:.2f}, {a['tip_deg']:.2f}, {a['span_average_deg']:.2f}",
         f"design {a['ribs'][len(a['ribs']) // 2]['alpha_design_deg']:.2f}; each rib's chord against the stream, in the "
         "plane of the stream and the section's local lift direction; average: trapezoid over the projected span; "
         "plots/wing_alpha.png"),
        ("projected area: design, loaded [m^2]",
         f"{r['design_projected_area_m2']:.3f}, {r['deformed_projected_area_m2']:.3f}",
         f"loaded {100 * r['planform_change']:+.1f} % of the structure's design skin "
         f"({r['design_projected_area_structure_m2']:.3f})"),
        ("projected span: design, loaded [m]; loaded aspect ratio",
         f"{r['design_span_m']:.3f}, {r['deformed_span_m']:.3f}; {r['deformed_aspect_ratio']:.2f}",
         f"the tips' trailing edges {100 * a['tips_te_inboard_of_le_m']:.1f} cm inboard of their leading edges "
         "(design 0)"),
        ("lift, drag of the canopy [N]", f"{fo['lift_canopy_N']:.2f}, {fo['drag_canopy_N']:.2f}",
         "the flow's force on the skin"),
        ("line drag [N] (lift, drag components)", f"{fo['lift_lines_N']:.2f}, {fo['drag_lines_N']:.2f}",
         "the line_drag effect's model on the last frame's lines"),
        ("CL, CD canopy / CD lines / CD system, on the design area",
         f"{des['CL_canopy']:.4f}, {des['CD_canopy']:.4f} / {des['CD_lines']:.4f} / {des['CD_system']:.4f}",
         f"A = {des['area_m2']:.3f} m^2 (design, projected)"),
        ("CL, CD canopy / CD lines / CD system, on the loaded area",
         f"{dfm['CL_canopy']:.4f}, {dfm['CD_canopy']:.4f} / {dfm['CD_lines']:.4f} / {dfm['CD_system']:.4f}",
         f"A = {dfm['area_m2']:.3f} m^2 (loaded canopy, projected)"),
        ("L/D canopy, system; glide angle [deg]", f"{co['L_over_D_canopy']:.2f}, {co['L_over_D_system']:.2f}; "
         f"{co['glide_angle_deg']:.2f}", "system = canopy + lines (no payload: anchored); tan(glide) = CD/CL system"),
        ("Helmbold at the flown attitude: CL estimate; CL / estimate",
         f"{e['CL_estimate']:.3f}; {e['CL_over_estimate']:.2f}",
         f"alpha {e['alpha_deg']:.2f} deg (span average), alpha0 {e['zero_lift_angle_deg']:g}, "
         f"AR {e['aspect_ratio']:.2f} "
         "(loaded), arc factor 1; CL on the loaded area"),
        ("lift per span / elliptic: centre, tips",
         f"{fs['centre_ratio_to_elliptic']:.2f}, {fs['tip_ratio_to_elliptic']:.2f}",
         f"pressure + shear on the wing patch (sum {100 * fs['lift_sum_vs_interface']:+.2f} % of the interface lift); "
         "plots/wing_lift.png"),
        ("Cp min on the upper surface: centre, mid, near tip", ", ".join(
            f"{_num(st.get('cp_min_upper'), '.2f')} at x/c {_num(st.get('cp_min_upper_x_over_c'), '.2f')}"
            for st in fs["cp"]["stations"]), "plots/wing_cp.png, plots/wing_cp_map.png"),
        ("lines at the confluence by row: sum [N] (share)", ", ".join(
            f"{k} {x['sum_N']:.1f} ({100 * x['share']:.0f} %)" for k, x in sorted(li["rows"].items())),
         f"{len(li['at_confluence'])} lines; largest piece anywhere {li['line_tension_max_N']:.2f} N"),
        ("vector sum of the confluence tensions vs anchor reaction [N]",
         f"{v(li['vector_sum_at_confluence_N'])} vs {v([-x for x in li['anchor_reaction_N']])}",
         f"difference {100 * li['vector_sum_vs_anchor']:.2f} % (the node's own line drag)"),
        ("lines' pull on the supports (confluence + toggles) vs canopy force + line drag [N]",
         f"{v(li['lines_pull_on_supports_N'])} vs {v(li['aero_plus_line_drag_N'])}",
         f"difference {100 * li['pull_vs_aero_plus_line_drag']:.2f} % (the supports' own line drag; the load "
         "relaxation's lag)"),
        ("brake lines at the toggles [N]", "; ".join(
            f"{side} " + ", ".join(f"{b['tension_N']:.2f}" for b in bl)
            for side, bl in sorted(li["brakes"].items())), ""),
        ("trim reached", "yes" if t["trim_reached"] else "no",
         f"CL {100 * t['CL_change']:.2f} %, CD {100 * t['CD_change']:.2f} %, centre alpha "
         f"{_num(t['centre_alpha_change_deg'], '.3f')} deg over the last {100 * TRIM_FRACTION:.0f} % of the windows; "
         f"balance {100 * t['balance']:.3f} %; plots/wing_convergence.png"),
    ]
    r = w.get("converged_reference")
    if r:
        rows.append(("error against the converged answer", converged_text(r),
                     (r.get("converged_is") or "") + "; docs/AERODYNAMICS.md, rung 3"))
    return rows


# ---------------------------------------------------------------------------------------------------------
# Plots


def plots(case, rec, c, canopy, X, X0, design, end, s_end, w, g):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PolyCollection
    except ImportError:
        return []
    d = rec["derived"]
    e_d, e_l = np.array(d["flow_dir"], float), np.array(d["lift_dir"], float)
    e_s = np.cross(e_l, e_d)
    outdir = os.path.join(case, "plots")
    os.makedirs(outdir, exist_ok=True)
    done = []

    def save(fig, name):
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, name), dpi=110)
        plt.close(fig)
        done.append("plots/" + name)

    a = w["section_alpha"]
    # (a) section angles
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4))
    ribs = a["ribs"]
    ax.plot([r["span_position_m"] for r in ribs], [r["alpha_deg"] for r in ribs], "o-", label="loaded (end)")
    ax.plot([np.dot(f["qc"], e_s) for f in design], [r["alpha_design_deg"] for r in ribs], "s--", color="0.5",
            label="design")
    ax.axhline(a["span_average_deg"], color="tab:red", lw=0.8, label=f"span average {a['span_average_deg']:.2f}")
    ax.set_xlabel("rib position along the projected span [m]")
    ax.set_ylabel("section angle of attack [deg]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    h = a["history"]
    for key, lab in (("centre_deg", "centre rib"), ("tip_deg", "tip ribs"), ("span_average_deg", "span average")):
        bx.plot(h["window"], h[key], "o-", ms=3, label=lab)
    bx.set_xlabel("window")
    bx.set_ylabel("section angle of attack [deg]")
    bx.grid(alpha=0.3)
    bx.legend(fontsize=8)
    save(fig, "wing_alpha.png")

    # (b) lift distribution
    fs = w["fluid_surface"]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    st = fs["strips"]
    ax.step(st["centre_m"], st["lift_per_span_N_m"], where="mid", label="wing patch, strips of a quarter cell")
    for k, cell in enumerate(fs["cells"]):
        ax.plot([cell["from_m"], cell["to_m"]], [cell["lift_per_span_N_m"]] * 2, color="tab:green", lw=2.5,
                label="between ribs" if k == 0 else None)
    b, L = fs["span_m"], fs["lift_sum_N"]
    y = np.linspace(-b / 2, b / 2, 201)
    s0 = 0.5 * (fs["cells"][0]["from_m"] + fs["cells"][-1]["to_m"])
    ax.plot(y + s0, 4 * L / (math.pi * b) * np.sqrt(np.clip(1 - (2 * y / b) ** 2, 0, None)), "k--",
            label=f"elliptic, same lift ({L:.1f} N)")
    ax.set_xlabel("projected span position [m]")
    ax.set_ylabel("lift per unit span [N/m]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, "wing_lift.png")

    # (c) Cp along the chord
    stations = fs["cp"]["stations"]
    fig, axes = plt.subplots(1, len(stations), figsize=(4.2 * len(stations), 4), sharey=True)
    for ax, stn in zip(axes, stations):
        ax.plot(stn["upper"]["x_over_c"], stn["upper"]["cp"], "o", ms=3, label="upper")
        ax.plot(stn["lower"]["x_over_c"], stn["lower"]["cp"], "s", ms=3, mfc="none", label="lower")
        ax.set_title(f"{stn['station']}: rib {stn['rib']}, y = {stn['span_position_m']:.2f} m, alpha "
                     f"{stn['alpha_deg']:.1f} deg", fontsize=9)
        ax.set_xlabel("x/c")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("Cp")
    axes[0].invert_yaxis()
    axes[0].legend(fontsize=8)
    save(fig, "wing_cp.png")

    # (c) planform map of Cp, upper and lower
    pts, faces, cp, n_out = g["pts"], g["faces"], g["cp"], g["n_out"]
    polys = [np.stack([pts[f] @ e_s, -(pts[f] @ e_d)], 1) for f in faces]
    up = n_out @ e_l > 0
    lo, hi = np.percentile(cp, [1, 99])
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    for ax, sel, lab in ((axes[0], up, "upper surface (seen from above)"),
                         (axes[1], ~up, "lower surface (seen from above)")):
        pc = PolyCollection([polys[i] for i in np.nonzero(sel)[0]], array=cp[sel], cmap="RdBu_r", edgecolors="none")
        pc.set_clim(lo, hi)
        ax.add_collection(pc)
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_title(lab, fontsize=9)
        ax.set_xlabel("span [m]")
        ax.set_ylabel("- chordwise [m] (leading edge up)")
        fig.colorbar(pc, ax=ax, label="Cp", shrink=0.8)
    save(fig, "wing_cp_map.png")

    # (d) deformed sections beside the design
    n = len(canopy.ribs)
    pick = sorted({n // 2, n // 2 + max(1, (n // 2) // 2), n - 1})
    fig, axes = plt.subplots(len(pick), 1, figsize=(8, 2.4 * len(pick)), sharex=True)
    for ax, k in zip(axes, pick):
        r = canopy.ribs[k]
        for Y, fr, style, lab in ((X0, design[k], "--", "design"), (X, end[k], "-", "loaded")):
            P = Y[r["ring"]] - Y[r["le"]]
            xi, eta = P @ e_d, P @ fr["e_l"]
            ax.plot(np.append(xi, xi[0]), np.append(eta, eta[0]), style, label=f"{lab}, alpha {fr['alpha']:.2f} deg")
        ax.set_aspect("equal")
        ax.set_title(f"rib {k} (y = {w['section_alpha']['ribs'][k]['span_position_m']:.2f} m)", fontsize=9)
        ax.set_ylabel("local lift dir. [m]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("along the free stream from the leading edge [m]")
    save(fig, "wing_sections.png")

    # (g) convergence to the trim
    hc = c["history"]
    nwin = len(hc["time"])
    win = np.arange(1, nwin + 1)
    q, area = d["q"], d["Aref"]
    fig, axes = plt.subplots(3, 1, figsize=(8, 7.5), sharex=True)
    axes[0].plot(win, np.array(hc["lift_N"]) / (q * area))
    axes[0].set_ylabel("CL (design area)")
    axes[1].plot(win, np.array(hc["drag_N"]) / (q * area), label="canopy")
    fw = [k for k in a["history"]["window"] if 1 <= k <= nwin]
    dl = [np.dot(x, e_d) for k, x in zip(a["history"]["window"], a["history"]["line_drag_N"]) if 1 <= k <= nwin]
    axes[1].plot(fw, (np.array([hc["drag_N"][k - 1] for k in fw]) + np.array(dl)) / (q * area), "o-", ms=3,
                 label="system (canopy + lines), at the frames")
    axes[1].set_ylabel("CD (design area)")
    axes[1].legend(fontsize=8)
    axes[2].plot(a["history"]["window"], a["history"]["centre_deg"], "o-", ms=3)
    axes[2].set_ylabel("centre section alpha [deg]")
    axes[2].set_xlabel("window")
    t0 = w["trim"]["from_window"]
    for ax in axes:
        ax.axvspan(t0, nwin, color="0.9")
        ax.grid(alpha=0.3)
    fig.suptitle(f"trim reached: {'yes' if w['trim']['trim_reached'] else 'no'} (shaded: the last "
                 f"{100 * TRIM_FRACTION:.0f} % of the windows, the criterion's)", fontsize=9)
    save(fig, "wing_convergence.png")

    # (f) line tensions by row and rib
    att = w["lines"]["attachments"]
    fig, ax = plt.subplots(figsize=(8, 4))
    for row in sorted(att):
        ribs = sorted(att[row], key=int)
        ax.plot([int(k) for k in ribs], [att[row][k] for k in ribs], "o-", label=f"row {row}")
    ax.set_xlabel("rib (0 = left tip)")
    ax.set_ylabel("attachment line tension [N]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, "wing_lines.png")
    return done
