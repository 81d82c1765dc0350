"""The ram-air case's settings file (part of ramair_fluid.py, the case generator): `key value` per line, `#`
starts a comment, every key known and every value checked (SETTINGS: kind, default, range, meaning; the keys
that depend on each other in read_settings), the Markdown table of docs/RAMAIR.md "Settings", the brake inputs
the settings describe, and constant/fluidSettings.json (the settings and the numbers derived from them, which
`ramair_fluid.py write` stores and every later step reads: load_record). Standard library only.
"""
import json
import math
import os
import re


RESOLUTIONS = {
    # wing surface (min max) level, feature-edge level, near-wing box level, wake box level; the background
    # cell is one chord. Levels as in the feasibility trial (shared notes: 52 k / 235 k cells).
    "coarse": {"surface": (4, 5), "features": 5, "near": 3, "wake": 2},
    "medium": {"surface": (5, 6), "features": 6, "near": 4, "wake": 3},
    # The medium mesh away from the skin and the coarse one at it: the flow around the wing and its wake
    # resolved one level finer while the cells the canopy moves stay those of the coarse mesh (the medium
    # mesh's thinner cells there fold as the canopy moves; docs/RAMAIR.md). The same step as coarse.
    "wake": {"surface": (4, 5), "features": 5, "near": 4, "wake": 3},
    # One level finer than medium at the skin and its edges (cells of 1/128 chord), the boxes as medium's: the
    # rigid wing's third mesh of the validation ladder (docs/AERODYNAMICS.md); not for the moving canopy.
    "fine": {"surface": (6, 7), "features": 7, "near": 4, "wake": 3},
}


# motion_diffusivity: the displacementLaplacian's diffusivity (OpenFOAM's names)
DIFFUSIVITY = {"quadratic": "quadratic inverseDistance (wing)", "inverse": "inverseDistance (wing)",
               "uniform": "uniform"}


# key: (kind, default, lower, upper, help); kind "float" (finite, lower <= v <= upper), "int", or a word list
SETTINGS = {
    "speed": ("float", None, 1e-3, 1e3, "free-stream speed [m/s]"),
    "angle": ("float", 0.0, -30.0, 30.0, "inflow angle in the x-z plane [deg], added to the wing's incidence"),
    "sideslip": ("float", 0.0, -30.0, 30.0,
                 "rigid wing, whole domain: the free stream (at `angle`) turned by this angle about the vertical z "
                 "axis [deg]; positive: the air comes from the right (+y), U = speed (cos a cos b, -cos a sin b, sin a), "
                 "the flight model's sideslip asin(cos a sin b) (docs/RAMAIR.md \"Sideslip\")"),
    "nu": ("float", 1.5e-5, 1e-7, 10.0, "kinematic viscosity [m^2/s]"),
    "rho": ("float", 1.225, 1e-3, 1e4, "density for forces [kg/m^3] (p is kinematic)"),
    "model": (["laminar", "kOmegaSST"], "laminar", None, None,
              "flow model; kOmegaSST with wall functions on the wing (kqRWallFunction, omegaWallFunction, "
              "nutUSpaldingWallFunction) and inletOutlet on the far field"),
    "resolution": (list(RESOLUTIONS), "coarse", None, None,
                   "mesh levels of the skin, its sharp edges and the near-wing and wake boxes (docs/RAMAIR.md \"The "
                   "mesh\"): coarse (the main job), medium, wake (medium's boxes, coarse's skin), fine (medium's "
                   "boxes, the skin a level finer: rigid wing)"),
    "steps": ("int", 60, 1, 1000000, "time steps of the run"),
    "write_interval": ("int", 0, 0, 1000000,
                       "write the fields (and the coupled canopy's frames) every this many steps; 0: at the end only"),
    "rigid_steps": ("int", 0, 0, 1000000,
                    "coupled yes: steps of the rigid wing before the coupling starts; their flow is the coupled "
                    "run's initial field (the impulsive start's pressure transient never reaches the canopy)"),
    "courant": ("float", 4.0, 0.05, 50.0, "speed * deltaT / (finest cell at the wing)"),
    "outer_correctors": ("int", 3, 1, 50, "PIMPLE outer correctors per step"),
    "turbulence_intensity": ("float", 0.005, 1e-5, 0.5, "free-stream k = 1.5 (I U)^2 (kOmegaSST)"),
    "viscosity_ratio": ("float", 10.0, 1e-3, 1e5, "free-stream nut/nu, sets omega = k/(ratio nu) (kOmegaSST)"),
    "mesh_motion": (["auto", "none", "laplacian", "rigidfit"], "auto", None, None,
                    "none: static mesh (rigid wing); laplacian: displacementLaplacian, inverse-distance "
                    "diffusivity; rigidfit: the wing's best-fit rigid motion carried by the cells around it "
                    "(libfsiFoam's fsiRigidFitDisplacementLaplacian), the Laplacian for the rest; auto: "
                    "laplacian when coupled, else none"),
    "correct_phi": (["no", "yes"], "no", None, None,
                    "moving mesh: PIMPLE's correctPhi (make the fluxes divergence-free again after each mesh "
                    "motion, one more pressure-like solve per step)"),
    "rigid_inner": ("float", 0.3, 0.0, 50.0, "rigidfit: cells this many chords from the wing move rigidly"),
    "rigid_outer": ("float", 4.0, 0.01, 100.0,
                    "rigidfit: the rigid part fades out over the cells up to this many chords from the wing"),
    "motion_diffusivity": (list(DIFFUSIVITY), "quadratic", None, None,
                           "laplacian: quadratic (1/r^2 from the wing: the cells next to it move with it), "
                           "inverse (1/r) or uniform"),
    "coupled": (["no", "yes"], "no", None, None,
                "yes: the wing is structure.yaml's canopy, coupled to the flow through libfsiFoam (its scene "
                "for the run: structure-coupled.yaml, written from structure.yaml and these settings)"),
    "scheme": (["staggered", "implicit"], "implicit", None, None,
               "coupling scheme: staggered (one pass per step) or implicit (iterated to the tolerance)"),
    "structure_mode": (["equilibrium", "timeAccurate"], "equilibrium", None, None,
                       "equilibrium: each fluid step relaxes the canopy towards its static state under the "
                       "step's load (Kalro-Tezduyar; steady states); timeAccurate: its real motion"),
    "equilibrium_steps": ("int", 100, 1, 1000000, "equilibrium: damped structural steps per fluid step"),
    "equilibrium_start": (["rest", "carry"], "rest", None, None,
                          "equilibrium: each step's relaxation from rest, or carrying the previous step's "
                          "pseudo-motion (the slow swing on the lines converges in fewer steps)"),
    "carry_after": ("int", 0, 0, 1000000,
                    "equilibrium_start carry: the first this many coupled steps still relax from rest (the "
                    "start-up transient dies out before the motion is carried; the adapter's "
                    "equilibriumCarryFrom)"),
    "load_relaxation": ("float", 1.0, 1e-3, 1.0,
                        "the canopy gets w f + (1 - w) f_previous of the flow's load f (1: off)"),
    "brake_right": ("float", 0.0, 0.0, 2.0,
                    "coupled yes: the right toggle pulled down by this much [m] (0: held)"),
    "brake_left": ("float", 0.0, 0.0, 2.0,
                   "coupled yes: the left toggle pulled down by this much [m] (0: held); both: a symmetric or "
                   "differential brake"),
    "brake_start": ("float", 0.0, 0.0, 1e6, "coupled yes: when the pull starts [s]"),
    "brake_duration": ("float", 0.1, 1e-6, 1e6, "coupled yes: the pull's smooth ramp [s]"),
    "brake_table": ("file", "", None, None,
                    "coupled yes: the toggles' travel in time instead of brake_left/right/start/duration: a CSV "
                    "file (relative to the settings file) with the header time,left,right and rows of t [s], "
                    "left and right travel down [m, 0-2], times increasing; linear between rows, held after the "
                    "last"),
    "trailing_edge_tape": (["no", "yes"], "no", None, None,
                           "coupled yes: a tape (cables) along the canopy's trailing edge, so that a brake line "
                           "draws the edge down over the span instead of denting the skin (docs/PARAFOIL.md)"),
    "keep_side": (["no", "yes"], "no", None, None,
                  "coupled yes: map each fluid point onto the structure's skin facing its own way (the "
                  "projection's keepSide; at the thin trailing edge the closest skin can be the other one)"),
    "gap_correction": (["no", "yes"], "no", None, None,
                       "coupled yes: the projection's gapCorrection (carry the displacement across the gap "
                       "between the fluid's and the structure's skins; docs/PROJECTION.md)"),
    "conserve_moment": (["yes", "no"], "yes", None, None,
                        "coupled yes: the adapter's conserveMoment (the structure's loads carry the fluid's moment "
                        "too, not only its force; docs/COUPLING.md)"),
    "smoothing_length": ("float", 0.0, 0.0, 1.0,
                         "coupled yes: the fluid's skin moves with the displacement smoothed over this length [m] "
                         "(the adapter's smoothingLength): the flow sees a crumpled trailing edge's mean surface"),
    "remesh_below": ("float", 0.0, 0.0, 0.95,
                     "coupled yes: when the moved mesh has crushed a cell below this fraction of its volume, the "
                     "run stops cleanly, a new mesh is snapped to the canopy as it is and the run continues on it "
                     "(the adapter's remeshBelow; Allrun does the rest; 0: off)"),
    "remesh_max": ("int", 50, 1, 10000,
                   "coupled yes, remesh_below > 0: new meshes at most; when the run asks for one more, Allrun stops "
                   "with the case as it is (a mesh that keeps folding every few windows would otherwise snap for "
                   "hours)"),
    "tolerance": ("float", 1e-3, 1e-12, 0.5, "implicit: relative interface-displacement residual of a step"),
    "max_iterations": ("int", 20, 1, 1000, "implicit: iterations per step at most"),
    "subcycles": ("int", 1, 1, 100000, "structural steps per fluid step at least"),
    "stl_bulge": ("float", -1.0, -1.0, 0.5,
                  "the fluid's skin: the generator's cell bulge (-1: the scene's; a rigid run may differ, a "
                  "coupled one may not)"),
    "stl_deformed": ("path", "", None, None,
                     "rigid wing: the fluid's skin at a structure run's last frame (`fsi generate --deformed`): "
                     "its folder, results.h5 or a state file (relative to the settings file), e.g. the inflated "
                     "canopy of `fsi run structure.yaml` or a coupled run's structure/; sampled as stl_chordwise_"
                     "points and stl_span_divisions give, the displacement interpolated (docs/AERODYNAMICS.md)"),
    "ranks": ("int", 2, 2, 64, "MPI ranks of Allrun.parallel (hierarchical (N 1 1))"),
    "zero_lift_angle": ("float", -4.15, -20.0, 20.0,
                        "the section's zero-lift angle [deg] for the lifting-line estimate (NACA 4415: -4.15, thin airfoil theory)"),
    "stl_chordwise_points": ("int", 60, 0, 1000,
                             "the fluid's skin: chordwise points of the wing generator (0: the scene's own)"),
    "stl_span_divisions": ("int", 6, 0, 100, "the fluid's skin: span divisions per cell (0: the scene's own)"),
    "mirror_mesh": (["no", "yes"], "no", None, None,
                    "yes: snappyHexMesh meshes the half y >= 0 and mirrorMesh adds its mirror image, so the left and "
                    "right cells are exact mirror images (a whole snapped mesh is not mirror-symmetric: its cells "
                    "at the right trailing edge were the ones that folded; docs/RAMAIR.md)"),
    "solver": (["pimple", "simple"], "pimple", None, None,
               "pimple: pimpleFoam, pseudo-transient at `courant`; simple: simpleFoam, steady, `steps` iterations "
               "(rigid wing only: a steady answer for steady flow, docs/AERODYNAMICS.md)"),
    "prism_layers": (["no", "yes"], "no", None, None,
                     "yes: snappyHexMesh adds prism layers on the wing whose first cell centre sits at y+ of about "
                     "50 (first layer 0.0022 chord, growing by 1.2 up to half the wall cell): the log-layer band the "
                     "wall functions are valid in (docs/AERODYNAMICS.md rung 1); rigid wing only so far"),
    "wall_split": ("int", 0, 0, 2,
                   "after snapping, the cells next to the wing are split at half their height this many "
                   "times (OpenFOAM's refineWallLayer, edge fraction 0.5): a wall cell of h/2^N, on every face of "
                   "the skin but those within 8 % of the half-span of the tips (split there, the tip's sharp edge "
                   "gives inverted cells), nor around spots where a split made wrong-oriented faces (Allrun splits again "
                   "without them, checkMesh.split*); 2: y+ about 100 on the coarse mesh (docs/AERODYNAMICS.md rung 2b). "
                   "3 splits invert cells at the leading edge; coupled yes needs courant <= 4 / 2^N, or wall_after"),
    "wall_layers": ("int", 0, 0, 5,
                    "snappyHexMesh adds this many prism layers on the wing, sized on the wall cell (the outermost "
                    "0.4 of it, each inner one 1.3 times thinner; where the skin allows: 1.8 on average, 58 % of "
                    "the thickness, on the coarse mesh around the trimmed canopy); the first layer is about 1/F of "
                    "the wall cell, F = round(1.3^(N-1) / 0.4) (4 for 3 layers); coupled yes needs courant <= 4 / F, "
                    "or wall_after"),
    "wall_after": ("int", 0, 0, 1000000,
                   "coupled yes with wall_split or wall_layers: the first this many steps run on the plain mesh at "
                   "`courant`; then the run stops (the adapter's remeshAt), a new mesh with the thin wall cells is "
                   "snapped to the canopy as it is, and the run goes on to the same end time with the step and "
                   "equilibrium_steps divided by F (2^N for wall_split, wall_layers' F) and write_interval "
                   "multiplied by it (the same flow time and pseudo-steps per second, on wall cells F times "
                   "thinner); 0: the thin wall cells from the start"),
    "half_domain": (["no", "yes"], "no", None, None,
                    "yes: the half y >= 0 with a symmetry plane at y = 0 (rigid wing in symmetric flow only: half "
                    "the cells for the same answer; the coefficients are the whole wing's)"),
    "upstream": ("float", 8.0, 2.0, 100.0, "domain: chords upstream of the wing"),
    "downstream": ("float", 16.0, 3.0, 200.0, "domain: chords downstream of the wing"),
    "lateral": ("float", 8.0, 2.0, 100.0, "domain: chords beyond the tips, above and below the wing"),
}


NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


class InputError(Exception):
    pass


def read_brake_table(loc, key, text, base):
    """brake_table FILE: the file's path (checked: a plain relative or absolute path, the file exists) and its
    rows [[t, left, right], ...], validated with the file's own line numbers."""
    if not re.fullmatch(r"[A-Za-z0-9._/+-]+", text):
        raise InputError(f"{loc}: {key} '{text}': a file name of letters, digits and . _ / + - only")
    path = text if os.path.isabs(text) else os.path.join(base, text)
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{loc}: {key} {text}: cannot read it: {e}")
    rows = []
    body = [(n, l.split("#", 1)[0].strip()) for n, l in enumerate(lines, 1)]
    body = [(n, l) for n, l in body if l]
    if not body or [c.strip() for c in body[0][1].split(",")] != ["time", "left", "right"]:
        raise InputError(f"{path}:{body[0][0] if body else 1}: the first line must be the header time,left,right")
    for n, l in body[1:]:
        cells = [c.strip() for c in l.split(",")]
        if len(cells) != 3 or not all(NUMBER.match(c) for c in cells):
            raise InputError(f"{path}:{n}: expected three numbers t,left,right, got '{l}'")
        t, left, right = (float(c) for c in cells)
        if rows and not t > rows[-1][0]:
            raise InputError(f"{path}:{n}: time {t:g} does not follow {rows[-1][0]:g} (times must increase)")
        for name, v in (("left", left), ("right", right)):
            if not 0.0 <= v <= 2.0:
                raise InputError(f"{path}:{n}: {name} travel {v:g} m is outside [0, 2]")
        rows.append([t, left, right])
    if not rows:
        raise InputError(f"{path}: no rows after the header")
    return {"file": os.path.abspath(path), "rows": rows}


def read_run_path(loc, key, text, base):
    """A structure run's folder, results.h5 or state file (checked: a plain path that exists), absolute."""
    if not re.fullmatch(r"[A-Za-z0-9._/+-]+", text):
        raise InputError(f"{loc}: {key} '{text}': a path of letters, digits and . _ / + - only")
    path = os.path.abspath(text if os.path.isabs(text) else os.path.join(base, text))
    h5 = os.path.join(path, "results.h5") if os.path.isdir(path) else path
    if not os.path.isfile(h5):
        raise InputError(f"{loc}: {key} {text}: no such run ({h5} does not exist; run `fsi run structure.yaml "
                         "--out DIR` first)")
    return path


def read_settings(path):
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: cannot read the settings file: {e}")
    values, where = {}, {}
    for n, raw in enumerate(lines, 1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        parts = line.split()
        loc = f"{path}:{n}"
        if len(parts) != 2:
            raise InputError(f"{loc}: expected 'key value', got '{line}'")
        key, text = parts
        if key not in SETTINGS:
            near = sorted(SETTINGS, key=lambda k: _distance(k, key))[0]
            raise InputError(f"{loc}: unknown key '{key}' (did you mean '{near}'? valid: {', '.join(SETTINGS)})")
        if key in values:
            raise InputError(f"{loc}: key '{key}' given twice (first at line {where[key]})")
        kind, _, lo, hi, what = SETTINGS[key]
        if kind == "file":
            value = read_brake_table(loc, key, text, os.path.dirname(os.path.abspath(path)))
        elif kind == "path":
            value = read_run_path(loc, key, text, os.path.dirname(os.path.abspath(path)))
        elif isinstance(kind, list):
            if text not in kind:
                raise InputError(f"{loc}: {key} must be one of {', '.join(kind)}, not '{text}'")
            value = text
        else:
            if not NUMBER.match(text):
                raise InputError(f"{loc}: {key} ({what}) must be a number, not '{text}'")
            value = float(text)
            if kind == "int":
                if value != int(value):
                    raise InputError(f"{loc}: {key} ({what}) must be a whole number, not {text}")
                value = int(value)
            if not (math.isfinite(value) and lo <= value <= hi):
                raise InputError(f"{loc}: {key} = {text} is outside [{lo:g}, {hi:g}] ({what})")
        values[key], where[key] = value, n
    for key, (kind, default, _, _, what) in SETTINGS.items():
        if key not in values:
            if default is None:
                raise InputError(f"{path}: key '{key}' ({what}) is required")
            values[key] = default
    # Keys that depend on each other
    if values["mesh_motion"] == "auto":
        values["mesh_motion"] = "laplacian" if values["coupled"] == "yes" else "none"
    for key in ("rigid_inner", "rigid_outer"):
        if key in where and values["mesh_motion"] != "rigidfit":
            raise InputError(f"{path}:{where[key]}: {key} needs mesh_motion rigidfit")
    if "carry_after" in where and values["equilibrium_start"] != "carry":
        raise InputError(f"{path}:{where['carry_after']}: carry_after needs equilibrium_start carry")
    if values["rigid_inner"] >= values["rigid_outer"]:
        line = where.get("rigid_outer", where.get("rigid_inner"))
        raise InputError(f"{path}:{line}: rigid_inner ({values['rigid_inner']:g} chords) must be below rigid_outer "
                         f"({values['rigid_outer']:g}): the rigid part fades out between the two")
    thin = "wall_split" if values["wall_split"] > 0 else "wall_layers" if values["wall_layers"] > 0 else None
    if values["wall_after"] > 0:
        line = where["wall_after"]
        if values["coupled"] != "yes" or thin is None:
            raise InputError(f"{path}:{line}: wall_after needs coupled yes and wall_split or wall_layers (it makes the "
                             "wall cells of a coupled run thin part way through)")
        if values["wall_after"] >= values["steps"]:
            raise InputError(f"{path}:{line}: wall_after {values['wall_after']} must be below steps "
                             f"{values['steps']} (the mesh with thin wall cells would never run)")
    elif thin and values["coupled"] == "yes" and values["courant"] * wall_factor(values) > 4.0 + 1e-9:
        n = values[thin]
        raise InputError(f"{path}:{where[thin]}: {thin} {n} with coupled yes needs courant "
                         f"<= {4.0 / wall_factor(values):g} (4 / {wall_factor(values)}, now {values['courant']:g}), or "
                         "wall_after: the wall cells are that many times thinner than the cell the step is set on, and at "
                         "the main job's step the rigid start diverged (docs/AERODYNAMICS.md rung 3)")
    if values["brake_table"] and (values["brake_left"] > 0 or values["brake_right"] > 0):
        key = "brake_left" if values["brake_left"] > 0 else "brake_right"
        raise InputError(f"{path}:{where[key]}: {key} with brake_table: the table gives both toggles' travel")
    if values["wall_split"] > 0 and values["wall_layers"] > 0:
        raise InputError(f"{path}:{where['wall_layers']}: wall_split and wall_layers exclude each other (two ways of "
                         "making thin cells at the wall)")
    if values["wall_layers"] > 0 and values["prism_layers"] == "yes":
        raise InputError(f"{path}:{where['wall_layers']}: wall_layers and prism_layers exclude each other (two layer "
                         "specifications)")
    if values["wall_split"] > 0 and values["prism_layers"] == "yes":
        raise InputError(f"{path}:{where['wall_split']}: wall_split and prism_layers exclude each other (two ways "
                         "of making thin cells at the wall)")
    if values["half_domain"] == "yes" and values["mirror_mesh"] == "yes":
        raise InputError(f"{path}:{where['half_domain']}: half_domain and mirror_mesh exclude each other (mirror_mesh "
                         "meshes the half and mirrors it; half_domain keeps the half with a symmetry plane)")
    if values["sideslip"] != 0:
        # A sideslipping wing's flow is not mirror-symmetric, and the coupled canopy's attitude is its own.
        for key, why in (("coupled", "sideslip is for the rigid wing (the coupled canopy's rig and its lines' wind take the "
                                     "stream in the x-z plane)"),
                         ("half_domain", "the half domain's symmetry plane assumes a symmetric flow"),
                         ("mirror_mesh", "the flow about a sideslipping wing is not mirror-symmetric: mesh the "
                                         "whole box")):
            if values[key] == "yes":
                raise InputError(f"{path}:{where['sideslip']}: sideslip {values['sideslip']:g} with {key} yes "
                                 f"(line {where[key]}): {why}")
    if values["coupled"] == "yes":
        for key in ("solver", "half_domain", "prism_layers"):
            if key in where and values[key] != SETTINGS[key][1]:
                raise InputError(f"{path}:{where[key]}: {key} {values[key]} is for the rigid wing (coupled no): the "
                                 "coupled canopy moves in time and need not stay symmetric")
        if values["mesh_motion"] not in ("laplacian", "rigidfit"):
            raise InputError(f"{path}:{where['mesh_motion']}: mesh_motion none with coupled yes: the coupled wing "
                             "moves the mesh (mesh_motion laplacian or auto)")
        if values["stl_deformed"]:
            raise InputError(f"{path}:{where['stl_deformed']}: stl_deformed with coupled yes: the coupled canopy "
                             "starts from the structure's own state (remove stl_deformed)")
        if values["stl_bulge"] >= 0:
            raise InputError(f"{path}:{where['stl_bulge']}: stl_bulge with coupled yes: the fluid's skin must be "
                             "the structure's own surface (remove stl_bulge)")
    else:
        # The structure's keys mean nothing to a rigid wing: say so rather than run without them.
        for key in ("brake_right", "brake_left", "brake_table", "trailing_edge_tape", "equilibrium_start", "keep_side", "gap_correction",
                    "smoothing_length", "conserve_moment", "remesh_below"):
            if key in where and values[key] != SETTINGS[key][1]:
                raise InputError(f"{path}:{where[key]}: {key} needs coupled yes (the rigid wing has no structure)")
    return values


def wall_factor(s):
    """How many times thinner than the wall cell the thin wall cells are: 2^N for wall_split N, the first layer's
    ratio for wall_layers N (the outermost 0.4 of the cell, each inner one 1.3 times thinner), 1 for neither."""
    if s["wall_split"] > 0:
        return 2 ** s["wall_split"]
    if s["wall_layers"] > 0:
        return round(1.3 ** (s["wall_layers"] - 1) / 0.4)
    return 1


def _distance(a, b):
    d = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        prev, d[0] = d[0], i
        for j, cb in enumerate(b, 1):
            prev, d[j] = d[j], min(d[j] + 1, d[j - 1] + 1, prev + (ca != cb))
    return d[len(b)]


def brake_inputs(s):
    """The pulled toggles: (side, time function, amplitude [m]) for each side that moves, from brake_left/right
    with brake_start/duration (a smooth ramp) or from brake_table (a table function of the travel in metres)."""
    out = []
    table = s.get("brake_table")
    for side, col in (("left", 1), ("right", 2)):
        if table:
            rows = table["rows"]
            if max(r[col] for r in rows) > 0:
                out.append((side, {"type": "table", "points": [[float(f"{r[0]:.9g}"), float(f"{r[col]:.9g}")]
                                                                for r in rows]}, 1.0))
        elif s.get(f"brake_{side}", 0.0) > 0:
            out.append((side, {"type": "smooth_step", "start": float(f"{s['brake_start']:.9g}"),
                               "duration": float(f"{s['brake_duration']:.9g}")},
                        float(f"{s[f'brake_{side}']:.9g}")))
    return out


def brake_window(s):
    """(start, end) of the brake input [s]: the ramp's, or the table's from the row before its first travel to its
    last row; None without a brake."""
    table = s.get("brake_table")
    if table:
        rows = table["rows"]
        first = next((i for i, r in enumerate(rows) if r[1] > 0 or r[2] > 0), None)
        if first is None:
            return None
        return rows[max(first - 1, 0)][0], rows[-1][0]
    if s.get("brake_left", 0.0) > 0 or s.get("brake_right", 0.0) > 0:
        return s["brake_start"], s["brake_start"] + s["brake_duration"]
    return None


def brake_travel(s):
    """The toggles' travel held at the end [m]: (left, right)."""
    table = s.get("brake_table")
    if table:
        return table["rows"][-1][1], table["rows"][-1][2]
    return s.get("brake_left", 0.0), s.get("brake_right", 0.0)


def settings_table():
    """The settings as a Markdown table (docs/RAMAIR.md "Settings" is this, checked by
    tests/coupled/test_settings_table.py): key, default, range or choices, meaning."""
    def num(v):
        return f"{v:g}" if isinstance(v, float) else str(v)
    rows = ["| key | default | range | meaning |", "|---|---|---|---|"]
    for key, (kind, default, lo, hi, text) in SETTINGS.items():
        dflt = "required" if default is None else num(default)
        if kind == "file":
            dflt, rng = "none", "a CSV file"
        elif kind == "path":
            dflt, rng = "none", "a run's folder or file"
        else:
            rng = ", ".join(kind) if isinstance(kind, list) else f"{num(lo)} – {num(hi)}" + (" (whole)" if kind == "int" else "")
        rows.append(f"| `{key}` | {dflt} | {rng} | {text.replace('|', '/')} |")
    return "\n".join(rows) + "\n"


def load_record(case):
    path = os.path.join(case, "constant", "fluidSettings.json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: {e} (run 'ramair_fluid.py write' first)")
