"""The wing's skin as the ram-air case sees it (part of ramair_fluid.py, the case generator): the ASCII STL
that `fsi generate` writes, its bounds, areas and centre chord, the numbers derived from it and the settings
(time step, reference area and length, free-stream turbulence, Helmbold's lift estimate), and the small vector
helpers the other parts share. Standard library only.
"""
import math

from ramair_settings import RESOLUTIONS, InputError


def read_stl(path):
    tris = []
    try:
        with open(path, encoding="ascii") as f:
            verts = []
            for n, line in enumerate(f, 1):
                w = line.split()
                if w and w[0] == "vertex":
                    try:
                        verts.append(tuple(float(v) for v in w[1:4]))
                    except ValueError:
                        raise InputError(f"{path}:{n}: bad vertex")
                    if len(verts) == 3:
                        tris.append(verts)
                        verts = []
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: cannot read the STL (ASCII expected): {e}")
    if not tris:
        raise InputError(f"{path}: no triangles")
    return tris


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def wing_geometry(tris, lift_dir):
    """Bounds, area, the area projected on the plane normal to the lift direction (a closed surface is seen
    twice: half the sum of |n . e_lift| dA) and the centre section's chord line (incidence)."""
    lo = [min(p[i] for t in tris for p in t) for i in range(3)]
    hi = [max(p[i] for t in tris for p in t) for i in range(3)]
    area = projected = 0.0
    for a, b, c in tris:
        n = _cross(_sub(b, a), _sub(c, a))
        area += 0.5 * _norm(n)
        projected += 0.25 * abs(n[0] * lift_dir[0] + n[1] * lift_dir[1] + n[2] * lift_dir[2])
    # centre section: points within 1 % of the span of y = 0; trailing edge = largest x, leading edge = the
    # point farthest from it
    band = 0.01 * (hi[1] - lo[1])
    centre = [p for t in tris for p in t if abs(p[1]) <= band]
    if len(centre) < 3:
        raise InputError("the STL has no points near the symmetry plane y = 0: is it a parafoil's skin?")
    te = max(centre, key=lambda p: p[0])
    le = max(centre, key=lambda p: _norm(_sub(p, te)))
    chord = _norm(_sub(te, le))
    incidence = math.degrees(math.atan2(le[2] - te[2], te[0] - le[0]))
    return {"min": lo, "max": hi, "area": area, "projected_area": projected, "chord": chord,
            "leading_edge": le, "trailing_edge": te, "incidence_deg": incidence}


def derived(s, geo):
    a = math.radians(s["angle"])
    flow = (math.cos(a), 0.0, math.sin(a))
    lift = (-math.sin(a), 0.0, math.cos(a))
    if s.get("sideslip", 0.0) != 0:
        # sideslip b: the stream turned about z by -b (the air from the right for b > 0); the lift normal to the
        # stream and to the span (y), as the flight model's wind axes have it (flight/FlightSystem.cpp); at b = 0
        # the lines above (kept apart so that the dictionaries stay byte for byte those without sideslip)
        b = math.radians(s["sideslip"])
        flow = (math.cos(a) * math.cos(b), -math.cos(a) * math.sin(b), math.sin(a))
        n = math.hypot(flow[2], flow[0])
        lift = (0.0 - flow[2] / n, 0.0, flow[0] / n)  # 0.0 - : no "-0" at angle 0
    res = RESOLUTIONS[s["resolution"]]
    c = geo["chord"]
    h0 = c  # background cell: one chord
    h_wing = h0 / 2 ** res["surface"][1]
    dt = s["courant"] * h_wing / s["speed"]
    span = geo["max"][1] - geo["min"][1]
    aref = geo["projected_area"]
    ar = span * span / aref
    # Helmbold's low-aspect-ratio lifting-line slope with a 2 pi section slope
    a0 = 2 * math.pi
    k = a0 / (math.pi * ar)
    slope = a0 / (math.sqrt(1 + k * k) + k)
    alpha_eff = geo["incidence_deg"] + s["angle"] - s["zero_lift_angle"]
    le, te = geo["leading_edge"], geo["trailing_edge"]
    d = {
        "flow_dir": flow, "lift_dir": lift, "u_inf": [s["speed"] * v for v in flow],
        "h0": h0, "h_wing": h_wing, "deltaT": dt, "endTime": dt * s["steps"],
        "Aref": aref, "lRef": c, "span_projected": span, "aspect_ratio": ar,
        "Re": s["speed"] * c / s["nu"], "q": 0.5 * s["rho"] * s["speed"] ** 2,
        "CofR": [le[0] + 0.25 * (te[0] - le[0]), 0.0, le[2] + 0.25 * (te[2] - le[2])],
        "helmbold_slope_per_rad": slope, "alpha_effective_deg": alpha_eff,
        "CL_helmbold": slope * math.radians(alpha_eff),
    }
    if s["model"] == "kOmegaSST":
        kin = 1.5 * (s["turbulence_intensity"] * s["speed"]) ** 2
        d["k_inf"], d["omega_inf"] = kin, kin / (s["viscosity_ratio"] * s["nu"])
    return d


def v3(v):
    return "(" + " ".join(f"{x:.9g}" for x in v) + ")"
