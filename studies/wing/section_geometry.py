"""Sections of a wing skin (an ASCII STL such as `fsi generate` writes): the skin cut by planes y = const, each
section's chord line (leading edge = the point of least x, trailing edge = the point of largest x), its angle
to the x axis (nose up positive), chord length and greatest thickness normal to the chord over chord.
Used by wing_polar.py to state a shape's angles of attack and thickness, for the design and for a deformed
canopy alike."""
import math

import numpy as np


def read_stl(path):
    """The triangles of an ASCII STL as an array (n, 3 vertices, xyz)."""
    v = []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "vertex":
                v.append([float(x) for x in w[1:4]])
    if not v or len(v) % 3:
        raise ValueError(f"{path}: not an ASCII STL with whole triangles")
    return np.array(v).reshape(-1, 3, 3)


def cut(tris, y):
    """The points where the triangles' edges cross the plane y (each crossing edge once per triangle)."""
    d = tris[:, :, 1] - y
    pts = []
    for i in range(3):
        a, b = tris[:, i], tris[:, (i + 1) % 3]
        da, db = d[:, i], d[:, (i + 1) % 3]
        m = da * db < 0
        s = (da[m] / (da[m] - db[m]))[:, None]
        pts.append(a[m] + s * (b[m] - a[m]))
    return np.concatenate(pts) if pts else np.zeros((0, 3))


def section(points, bins=40):
    """Chord angle [deg], chord [m] and thickness/chord of a section's points (x-z plane)."""
    le, te = points[np.argmin(points[:, 0])], points[np.argmax(points[:, 0])]
    chord = math.hypot(te[0] - le[0], te[2] - le[2])
    u = np.array([te[0] - le[0], te[2] - le[2]]) / chord
    n = np.array([-u[1], u[0]])
    q = points[:, [0, 2]] - le[[0, 2]]
    s, h = q @ u, q @ n
    edges = np.linspace(0.0, chord, bins + 1)
    thick = 0.0
    for k in range(bins):
        m = (s >= edges[k]) & (s < edges[k + 1])
        if m.sum() >= 2:
            thick = max(thick, float(h[m].max() - h[m].min()))
    return {"chord_angle_deg": math.degrees(math.atan2(le[2] - te[2], te[0] - le[0])), "chord_m": chord,
            "thickness_over_chord": thick / chord}


def shape_report(stl, stations):
    """{name: section} at the named y stations, plus the skin's span (y extent) and projected planform area
    (on the x-y plane)."""
    tris = read_stl(stl)
    out = {"span_y_m": float(tris[:, :, 1].max() - tris[:, :, 1].min())}
    # planform: the upper half of the skin's triangles projected on z = 0 (half the total projected area)
    a, b, c = tris[:, 0, :2], tris[:, 1, :2], tris[:, 2, :2]
    area = 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1]))
    out["planform_area_xy_m2"] = float(area.sum() / 2)
    for name, y in stations.items():
        pts = cut(tris, y + 1e-9)
        out[name] = section(pts) if len(pts) >= 4 else None
    return out
