"""Reading a ram-air case's mesh (part of ramair_fluid.py, the case generator): the ASCII polyMesh (a
patch's points and faces, its area; the mirror plane before and after mirrorMesh) and checkMesh's log (cells,
failed checks, the only failure accepted: skewness at the sharp trailing edge; the gate a new mesh passes
before a run goes on). Standard library only.
"""
import math
import os
import re

from ramair_geometry import _cross, _sub
from ramair_settings import InputError


def _foam_list(text, start):
    """The list after the header of an ASCII polyMesh file: (count, text of the body)."""
    m = re.compile(r"^(\d+)\s*\n\(", re.M).search(text, start)
    if not m:
        raise InputError("not an ASCII OpenFOAM list (writeFormat ascii expected)")
    return int(m.group(1)), m.end()


def _patch_range(mesh, patch):
    """(startFace, nFaces, the boundary file's text, the entry's match) of a patch of constant/polyMesh."""
    with open(os.path.join(mesh, "boundary")) as f:
        b = f.read()
    m = re.search(r"\b" + re.escape(patch) + r"\s*\{([^}]*)\}", b)
    if not m:
        raise InputError(f"{mesh}/boundary: no patch '{patch}'")
    n_faces = int(re.search(r"nFaces\s+(\d+)", m.group(1)).group(1))
    start = int(re.search(r"startFace\s+(\d+)", m.group(1)).group(1))
    return start, n_faces, b, m


def read_patch(case, patch):
    """The points and faces of constant/polyMesh (ASCII) and the face range of one patch."""
    mesh = os.path.join(case, "constant", "polyMesh")
    start, n_faces, _, _ = _patch_range(mesh, patch)
    with open(os.path.join(mesh, "points")) as f:
        t = f.read()
    n, pos = _foam_list(t, t.index("}") if "FoamFile" in t else 0)
    pts = re.findall(r"\(([^()]+)\)", t[pos:])[:n]
    pts = [tuple(map(float, p.split())) for p in pts]
    with open(os.path.join(mesh, "faces")) as f:
        t = f.read()
    n, pos = _foam_list(t, t.index("}") if "FoamFile" in t else 0)
    faces = re.findall(r"\d+\(([^()]*)\)", t[pos:])
    return pts, faces, start, n_faces


def mirror_check(case):
    """Before mirrorMesh: snappyHexMesh must have left every point of the half mesh's `mirror` patch on the
    plane y = 0, or mirrorMesh would leave those faces unmerged (a slit in the fluid)."""
    pts, faces, start, n_faces = read_patch(case, "mirror")
    if n_faces == 0:
        raise InputError(f"{case}/constant/polyMesh/boundary: the patch 'mirror' has no faces")
    size = max(abs(x) for p in pts for x in p)
    for fi in range(start, start + n_faces):
        for i in faces[fi].split():
            y = pts[int(i)][1]
            if abs(y) > 1e-9 * size:
                raise InputError(f"{case}/constant/polyMesh: point {i} of the patch 'mirror' (face {fi}) lies at "
                                 f"y = {y:.3g}, off the mirror plane y = 0 (snappyHexMesh moved it)")
    print(f"mirror plane: {n_faces} faces, every point at y = 0")


def mirror_finish(case):
    """After mirrorMesh: the faces of `mirror` have all become internal faces; the empty patch is removed
    (the fields need no entry for it)."""
    mesh = os.path.join(case, "constant", "polyMesh")
    start, n_faces, b, m = _patch_range(mesh, "mirror")
    if n_faces != 0:
        raise InputError(f"{mesh}: mirrorMesh left {n_faces} faces of the patch 'mirror' unmerged")
    b = b[:m.start()] + b[m.end():]
    count = re.compile(r"^(\d+)\s*\n\(", re.M)
    c = count.search(b)
    if not c:
        raise InputError(f"{mesh}/boundary: not an ASCII patch list")
    b = b[:c.start(1)] + str(int(c.group(1)) - 1) + b[c.end(1):]
    with open(os.path.join(mesh, "boundary"), "w") as f:
        f.write(b)
    print("mirror plane: merged, the patch 'mirror' removed")


def patch_area(case, patch):
    pts, faces, start, n_faces = read_patch(case, patch)
    area = 0.0
    for fi in range(start, start + n_faces):
        ids = [int(i) for i in faces[fi].split()]
        sx = sy = sz = 0.0
        p0 = pts[ids[0]]
        for i in range(1, len(ids) - 1):
            cr = _cross(_sub(pts[ids[i]], p0), _sub(pts[ids[i + 1]], p0))
            sx, sy, sz = sx + cr[0], sy + cr[1], sz + cr[2]
        area += 0.5 * math.sqrt(sx * sx + sy * sy + sz * sz)
    return area, n_faces


def check_mesh(case, log="log.checkMesh"):
    path = os.path.join(case, log)
    with open(path) as f:
        text = f.read()
    cells = re.search(r"^\s*cells:\s+(\d+)", text, re.M)
    if not cells:
        raise InputError(f"{path}: no cell count: checkMesh did not finish")
    out = {"cells": int(cells.group(1)),
           "ok": "Mesh OK." in text,
           "failed": [l.strip() for l in text.splitlines() if l.strip().startswith("***")]}
    m = re.search(r"Failed (\d+) mesh checks", text)
    out["failed_checks"] = int(m.group(1)) if m else 0
    m = re.search(r"Mesh non-orthogonality Max:\s*([\d.eE+-]+)", text)
    out["max_non_orthogonality"] = float(m.group(1)) if m else None
    m = re.search(r"Max skewness = ([\d.eE+-]+)", text)
    out["max_skewness"] = float(m.group(1)) if m else None
    # the only failure accepted: high skewness (the faces at the sharp trailing edge)
    out["only_skewness"] = out["failed_checks"] == 1 and all("skew" in l for l in out["failed"])
    return out


def mesh_gate(case, log):
    """A new mesh made during a run (remeshing) must pass checkMesh, the sharp trailing edge's skewness
    excepted, before the run goes on: a mesh with wrong-oriented faces stops the moving-mesh run in its first
    window. The message for the console, or None."""
    m = check_mesh(case, log)
    if m["ok"] or m["only_skewness"]:
        return None
    return (f"{os.path.join(case, log)}: the new mesh fails {m['failed_checks']} checkMesh check(s): "
            + "; ".join(x.lstrip("*") for x in m["failed"]))
