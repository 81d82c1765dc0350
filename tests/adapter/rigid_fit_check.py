#!/usr/bin/env python3
"""Checks of the fsiRigidFitDisplacementLaplacian mesh motion on the square-body case (tests/adapter/rigid-fit).

  rigid_fit_check.py boundary-data CASE   writes constant/boundaryData/body: the body's points and, at t = 0 and
                                          t = 1, the displacement of the `deform` motion below
  rigid_fit_check.py rigid CASE LOG       the body turned 60 deg about (0.2, 0.1) (angularOscillatingDisplacement)
  rigid_fit_check.py deform CASE LOG      the body turned 60 deg about its centre, grown 10 % in x and y, moved by
                                          (0.3, -0.2, 0): a rigid motion plus a deformation the fit must ignore

The references are the prescribed motions (closed form), not the solver's output:
  * the body's points reach the prescribed displacement (1e-9 m);
  * rigid: every point within 0.2 of the body (inside innerDistance 0.3 for the nearest body point, whose spacing
    is below 0.06) moves by the same rotation (1e-9 m): those cells move rigidly;
  * rigid: every point 3 or more from the body (outerDistance 3) stays where it was (1e-12 m; with a deformation the
    Laplacian carries its residual out to the far field);
  * the written pointDisplacement is the total displacement, points - points0 (1e-9 m);
  * deform: the logged fit is the prescribed rotation (60 deg about z, 1e-6 deg) and translation (1e-9 m): growing the
    body about its centre does not bias the fit.
"""
import math
import os
import re
import sys

THETA = math.pi / 3
INNER_SURE, OUTER = 0.2, 3.0
GROW, SHIFT = 1.1, (0.3, -0.2, 0.0)


def body(text):
    """The text between the outermost parentheses of an OpenFOAM list file (after the header)."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    text = text[text.index("}", text.index("FoamFile")) + 1:]
    return text[text.index("("):text.rindex(")") + 1]


def vectors(path, internal=False):
    text = open(path).read()
    if internal:
        text = "FoamFile {}\n" + text[text.index("internalField"):text.index("boundaryField")]
        text = text[:text.rindex(";")]
    return [tuple(map(float, m.split())) for m in re.findall(r"\(([-+0-9.eE\s]+)\)", body(text)[1:-1])]


def faces(path):
    return [list(map(int, m.split())) for m in re.findall(r"\d+\s*\(([\d\s]+)\)", body(open(path).read())[1:-1])]


def patch_points(mesh, name):
    b = open(os.path.join(mesh, "boundary")).read()
    m = re.search(name + r"\s*\{[^}]*?nFaces\s+(\d+);[^}]*?startFace\s+(\d+);", b, re.S)
    n, start = int(m.group(1)), int(m.group(2))
    fs = faces(os.path.join(mesh, "faces"))[start:start + n]
    return sorted({v for f in fs for v in f})


def square_distance(p):
    dx, dy = max(abs(p[0]) - 0.5, 0.0), max(abs(p[1]) - 0.5, 0.0)
    return math.hypot(dx, dy)


def rotate(p, theta, origin):
    c, s = math.cos(theta), math.sin(theta)
    x, y = p[0] - origin[0], p[1] - origin[1]
    return (origin[0] + c * x - s * y, origin[1] + s * x + c * y, p[2])


def deformed(p):
    q = rotate((GROW * p[0], GROW * p[1], p[2]), THETA, (0.0, 0.0))
    return tuple(q[k] + SHIFT[k] for k in range(3))


def dist(a, b):
    return math.sqrt(sum((a[k] - b[k]) ** 2 for k in range(3)))


def write_boundary_data(case):
    x0 = vectors(os.path.join(case, "constant/polyMesh/points"))
    ids = patch_points(os.path.join(case, "constant/polyMesh"), "body")
    root = os.path.join(case, "constant/boundaryData/body")

    def write(path, values):  # a bare list, no header: what timeVaryingMappedFixedValue reads
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(f"{len(values)}\n(\n")
            f.writelines("(%.17g %.17g %.17g)\n" % v for v in values)
            f.write(")\n")

    write(os.path.join(root, "points"), [x0[i] for i in ids])
    write(os.path.join(root, "0/pointDisplacement"), [(0.0, 0.0, 0.0)] * len(ids))
    write(os.path.join(root, "1/pointDisplacement"),
          [tuple(deformed(x0[i])[k] - x0[i][k] for k in range(3)) for i in ids])


def check(mode, case, log):
    bad = []
    x0 = vectors(os.path.join(case, "constant/polyMesh/points"))
    x1 = vectors(os.path.join(case, "1/polyMesh/points"))
    d1 = vectors(os.path.join(case, "1/pointDisplacement"), internal=True)
    ids = patch_points(os.path.join(case, "constant/polyMesh"), "body")
    if len(x1) != len(x0) or len(d1) != len(x0):
        return [f"{len(x0)} points, {len(x1)} moved points, {len(d1)} displacements"]
    target = (lambda p: rotate(p, THETA, (0.2, 0.1))) if mode == "rigid" else deformed
    err = max(dist(x1[i], target(x0[i])) for i in ids)
    print(f"body: {len(ids)} points, largest distance from the prescribed position {err:.3g} m")
    if not err < 1e-9:
        bad.append(f"the body's points are {err:.3g} m from the prescribed motion")
    if mode == "rigid":
        near = [i for i in range(len(x0)) if square_distance(x0[i]) <= INNER_SURE]
        err = max(dist(x1[i], target(x0[i])) for i in near)
        print(f"{len(near)} points within {INNER_SURE} of the body: largest distance from the rigid motion {err:.3g} m")
        if len(near) < 2 * len(ids) or not err < 1e-9:
            bad.append(f"the points near the body are not moved rigidly ({len(near)} points, {err:.3g} m)")
        far = [i for i in range(len(x0)) if square_distance(x0[i]) >= OUTER]
        err = max(dist(x1[i], x0[i]) for i in far)
        print(f"{len(far)} points {OUTER} or more from the body: largest motion {err:.3g} m")
        if not far or not err < 1e-12:
            bad.append(f"the far points moved ({len(far)} points, {err:.3g} m)")
    err = max(dist(d1[i], tuple(x1[i][k] - x0[i][k] for k in range(3))) for i in range(len(x0)))
    print(f"pointDisplacement against points - points0: {err:.3g} m")
    if not err < 1e-9:
        bad.append(f"pointDisplacement is not the total displacement ({err:.3g} m off)")
    fits = re.findall(r"rigid part: rotation (\S+) deg about \((\S+) (\S+) (\S+)\), translation \((\S+) (\S+) (\S+)\)",
                      open(log).read())
    if len(fits) != 10:
        bad.append(f"{len(fits)} logged fits for 10 mesh updates")
    elif mode == "deform":
        angle, axis, t = float(fits[-1][0]), tuple(map(float, fits[-1][1:4])), tuple(map(float, fits[-1][4:]))
        print(f"last fit: rotation {angle:.12g} deg about {axis}, translation {t}")
        if abs(angle - 60) > 1e-6 or dist(axis, (0, 0, 1)) > 1e-9 or dist(t, SHIFT) > 1e-9:
            bad.append(f"the fit is rotation {angle} deg about {axis}, translation {t}; prescribed 60 deg about z, "
                       f"{SHIFT}")
    return bad


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "boundary-data":
        write_boundary_data(sys.argv[2])
        return 0
    if len(sys.argv) != 4 or sys.argv[1] not in ("rigid", "deform"):
        print(__doc__)
        return 2
    bad = check(*sys.argv[1:])
    for b in bad:
        print("FAIL:", b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
