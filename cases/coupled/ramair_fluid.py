#!/usr/bin/env python3
"""The fluid side of a ram-air wing case: OpenFOAM v1912 dictionaries around the canopy's closed skin (the
STL that `fsi generate` writes), from a small validated settings file; and the case's summary.json.

Usage (run by the case's Allrun; /usr/bin/python3, standard library only):
  ramair_fluid.py check SETTINGS              validate the settings file (exit 2 with FILE:LINE: message)
  ramair_fluid.py generate-args SETTINGS      the `fsi generate --set` arguments of the fluid's skin, one a line
  ramair_fluid.py write SETTINGS STL CASE     system/ and constant/ dictionaries (blockMesh, surface features,
                                              snappyHexMesh, schemes, solution, controlDict with forceCoeffs,
                                              decomposition, transport, turbulence, dynamic mesh) and
                                              constant/fluidSettings.json (settings + derived numbers)
  ramair_fluid.py structure SETTINGS SCENE OUT  the coupled run's structure scene (coupled yes): SCENE with the
                                              ram pressure and line-drag wind of the settings, the skin as
                                              the coupling interface
  ramair_fluid.py fields CASE                 0/ (U, p, pointDisplacement; k, omega, nut for kOmegaSST): after
                                              snappyHexMesh, from constant/fluidSettings.json
  ramair_fluid.py summary CASE                summary.json from the logs, postProcessing/ and constant/polyMesh
  ramair_fluid.py settings-table              the settings as a Markdown table (docs/RAMAIR.md "Settings")
  ramair_fluid.py courant-check LOG SETTINGS  exit 1 naming the step when LOG's Courant number ran away (past
                                              100 x the settings' courant, or NaN): the flow diverged
  ramair_fluid.py patch-area CASE PATCH       area of a boundary patch of constant/polyMesh (ASCII)
  ramair_fluid.py mirror-check CASE           mirror_mesh yes, before mirrorMesh: every point of the patch
                                              `mirror` lies on the plane y = 0
  ramair_fluid.py mirror-finish CASE          after mirrorMesh: the patch `mirror` has no faces left (all
                                              merged); removes it from constant/polyMesh/boundary
  ramair_fluid.py remesh-dicts CASE           a new mesh's background block over the whole box (remeshing)
  ramair_fluid.py split-exclude CASE LOG     after wall_split's splits and checkMesh LOG: exit 0 when the mesh
                                              passes; exit 3 when it has wrong-oriented faces, whose spots
                                              system/topoSetDict now leaves unsplit (split again)
  ramair_fluid.py mesh-gate CASE LOG         exit 1 when a new mesh's checkMesh LOG failed anything but the
                                              skewness check (Allrun's remesh loop, before the run goes on)
  ramair_fluid.py split-stage CASE T DT       a new mesh at time T on a controlDict with step DT: `split N`,
                                              `layers yes|no`, and at wall_after's time that stage's step,
                                              write interval and equilibrium steps (`key value` lines)

Why a generator rather than static dictionaries edited with foamDictionary/sed: the dictionaries depend on the
wing's size and position (domain, refinement boxes, locationInMesh outside the body, reference area), on
derived numbers (time step from a Courant number, k and omega from the intensity) and on the model (which
fields exist at all). Computing those in one place from numbers that were parsed and range-checked is simpler
and safer than editing text: nothing from the settings file reaches a shell, and every value written is a
number this script formatted or a word from a fixed list.
"""
import json
import math
import os
import re
import sys

# ---------------------------------------------------------------------------------------------------------
# Settings: `key value` per line, `#` starts a comment. Every key is known, every value checked.

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
    if values["coupled"] == "yes":
        for key in ("solver", "half_domain", "prism_layers"):
            if key in where and values[key] != SETTINGS[key][1]:
                raise InputError(f"{path}:{where[key]}: {key} {values[key]} is for the rigid wing (coupled no): the "
                                 "coupled canopy moves in time and need not stay symmetric")
        if values["mesh_motion"] not in ("laplacian", "rigidfit"):
            raise InputError(f"{path}:{where['mesh_motion']}: mesh_motion none with coupled yes: the coupled wing "
                             "moves the mesh (mesh_motion laplacian or auto)")
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


# ---------------------------------------------------------------------------------------------------------
# The wing's skin (ASCII STL, as `fsi generate` writes it)


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


# ---------------------------------------------------------------------------------------------------------
# Dictionaries

HEADER = "FoamFile {{ version 2.0; format ascii; class {cls}; object {obj}; }}\n// Written by ramair_fluid.py from {src}: edit the settings, not this file.\n"


def v3(v):
    return "(" + " ".join(f"{x:.9g}" for x in v) + ")"


def write(path, cls, obj, src, body):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER.format(cls=cls, obj=obj, src=src) + body)


def domain(geo, s, h0):
    """The background box: whole background cells, `upstream`/`downstream`/`lateral` chords around the wing."""
    c = geo["chord"]
    lo, hi = geo["min"], geo["max"]
    ext_lo = [lo[0] - s["upstream"] * c, lo[1] - s["lateral"] * c, lo[2] - s["lateral"] * c]
    ext_hi = [hi[0] + s["downstream"] * c, hi[1] + s["lateral"] * c, hi[2] + s["lateral"] * c]
    n = [max(1, math.ceil((ext_hi[i] - ext_lo[i]) / h0)) for i in range(3)]
    # centre the whole cells on the requested box
    mid = [(ext_hi[i] + ext_lo[i]) / 2 for i in range(3)]
    bmin = [mid[i] - n[i] * h0 / 2 for i in range(3)]
    bmax = [mid[i] + n[i] * h0 / 2 for i in range(3)]
    return bmin, bmax, n


def write_block_mesh(sysd, src, bmin, bmax, n, mirror, half=False):
    """system/blockMeshDict: the background box bmin..bmax in n cells (mirror: the half y >= 0 with the plane
    y = 0 as the patch `mirror`; half: the same half with that plane a symmetryPlane)."""
    verts = [(bmin[0], bmin[1], bmin[2]), (bmax[0], bmin[1], bmin[2]), (bmax[0], bmax[1], bmin[2]),
             (bmin[0], bmax[1], bmin[2]), (bmin[0], bmin[1], bmax[2]), (bmax[0], bmin[1], bmax[2]),
             (bmax[0], bmax[1], bmax[2]), (bmin[0], bmax[1], bmax[2])]
    if half:
        what = ("// The half y >= 0 of the background box around the wing, cells of one chord; `mirror` (y = 0) is\n"
                "// the symmetry plane of the rigid wing's symmetric flow, every other outer face the far field.\n")
        patches = ("  farfield { type patch; faces ((0 3 2 1) (4 5 6 7) (0 4 7 3) (1 2 6 5) (3 7 6 2)); }\n"
                   "  mirror { type symmetryPlane; faces ((0 1 5 4)); }\n")
    elif mirror:
        what = ("// The half y >= 0 of the background box around the wing, cells of one chord; `mirror` (y = 0)\n"
                "// disappears when mirrorMesh adds the other half, every other outer face is the far field.\n")
        patches = ("  farfield { type patch; faces ((0 3 2 1) (4 5 6 7) (0 4 7 3) (1 2 6 5) (3 7 6 2)); }\n"
                   "  mirror { type patch; faces ((0 1 5 4)); }\n")
    else:
        what = "// Background box around the wing, cells of one chord; every outer face is the far field.\n"
        patches = "  farfield { type patch; faces ((0 3 2 1) (4 5 6 7) (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)); }\n"
    write(os.path.join(sysd, "blockMeshDict"), "dictionary", "blockMeshDict", src,
          what + "scale 1;\nvertices\n(\n" + "".join(f"  {v3(v)}\n" for v in verts) + ");\n"
          f"blocks ( hex (0 1 2 3 4 5 6 7) ({n[0]} {n[1]} {n[2]}) simpleGrading (1 1 1) );\n"
          "boundary\n(\n" + patches + ");\n")


def write_remesh_dicts(case):
    """A new mesh of the same case around the canopy as a run left it (remesh_below): the whole box, also
    when the first mesh was mirrored (the canopy is no longer symmetric once a brake is pulled); the same
    cells, refinement and locationInMesh, the skin in constant/triSurface/wing.stl replaced by Allrun."""
    rec = load_record(case)
    dom = rec["domain"]
    bmin, bmax, n = list(dom["min"]), list(dom["max"]), list(dom["cells"])
    if rec["settings"]["mirror_mesh"] == "yes":
        bmin[1], n[1] = -bmax[1], 2 * n[1]
    write_block_mesh(os.path.join(case, "system"), os.path.basename(rec["settings_file"]), bmin, bmax, n, False)
    print(f"ramair_fluid: remesh: background {n[0]}x{n[1]}x{n[2]} over the whole box")


def split_stage(case, time, delta_t):
    """What a new mesh made at TIME gets (Allrun's remesh loop): `split N` (wall_split's splits) and `layers
    yes|no` (wall_layers: snappyHexMesh with system/snappyHexMeshDict.wall), the thin wall cells from the start or
    from wall_after's time on; when this is wall_after's new mesh (the controlDict's DELTA_T still the plain
    step), also that stage's `deltaT`, `writeInterval` and `equilibriumSteps`."""
    rec = load_record(case)
    s, d = rec["settings"], rec["derived"]
    t, dt_now = float(time), float(delta_t)
    if s["wall_after"] > 0 and t < s["wall_after"] * d["deltaT"] - 0.5 * d["deltaT"]:
        return ["split 0", "layers no"]
    out = [f"split {s['wall_split']}", f"layers {'yes' if s['wall_layers'] > 0 else 'no'}"]
    f = wall_factor(s)
    if s["wall_after"] > 0 and abs(dt_now - d["deltaT"]) <= 1e-6 * d["deltaT"]:
        every = min(s["steps"], s["write_interval"] or s["steps"])
        out += [f"deltaT {d['deltaT'] / f:.12g}", f"writeInterval {every * f}",
                f"equilibriumSteps {max(1, round(s['equilibrium_steps'] / f))}"]
    return out


def write_split_set(sysd, src, bmin, bmax, keep, excluded):
    """system/topoSetDict for wall_split: the cells refineWallLayer may split, all but those within `keep` of
    the tips' side (the outer 8 % of the half-span) and those in the `excluded` spheres ([x, y, z, radius]:
    where a split made wrong-oriented faces, split-exclude)."""
    actions = [f"  {{ name wallSplit; type cellSet; action new; source boxToCell;\n"
               f"    box ({bmin[0] - 1:.6g} {-keep:.6g} {bmin[2] - 1:.6g}) ({bmax[0] + 1:.6g} {keep:.6g} {bmax[2] + 1:.6g}); }}\n"]
    actions += [f"  {{ name wallSplit; type cellSet; action subtract; source sphereToCell; origin {v3(p[:3])}; "
                f"radius {p[3]:.6g}; }}\n" for p in excluded]
    write(os.path.join(sysd, "topoSetDict"), "dictionary", "topoSetDict", src,
          "// wall_split: the cells refineWallLayer may split (all but the outer 8 % of the half-span"
          + (f" and {len(excluded)} spots where a split made wrong-oriented faces" if excluded else "") + ")\n"
          "actions\n(\n" + "".join(actions) + ");\n")


def split_exclude(case, log):
    """After wall_split's refineWallLayer and checkMesh LOG: True when the split mesh passes (the skewness at
    the trailing edge excepted). Otherwise the centres of checkMesh's wrongOrientedFaces (cells split on a
    skin the snapped cells follow badly, e.g. around a deformed canopy) join constant/wallSplitExcluded.json
    and system/topoSetDict leaves the cells within 3 wall cells of them unsplit (twice that around a spot
    that stays wrong): False, split again."""
    m = check_mesh(case, log)
    if m["ok"] or m["only_skewness"]:
        return True
    other = [x for x in m["failed"] if "skew" not in x and "face pyramids" not in x]
    if other:
        raise InputError(f"{os.path.join(case, log)}: the split mesh fails " + "; ".join(x.lstrip("*") for x in other))
    mesh = os.path.join(case, "constant", "polyMesh")
    path = os.path.join(mesh, "sets", "wrongOrientedFaces")
    try:
        with open(path) as f:
            t = f.read()
    except OSError as e:
        raise InputError(f"{path}: {e} (checkMesh names the wrong-oriented faces there)")
    m = re.compile(r"^(\d+)\s*\(([^)]*)\)", re.M).search(t, t.index("}") if "FoamFile" in t else 0)
    if not m:
        raise InputError(f"{path}: not an ASCII OpenFOAM list of face labels")
    ids = [int(x) for x in m.group(2).split()][:int(m.group(1))]
    with open(os.path.join(mesh, "points")) as f:
        t = f.read()
    n, pos = _foam_list(t, t.index("}") if "FoamFile" in t else 0)
    pts = [tuple(map(float, p.split())) for p in re.findall(r"\(([^()]+)\)", t[pos:])[:n]]
    with open(os.path.join(mesh, "faces")) as f:
        t = f.read()
    n, pos = _foam_list(t, t.index("}") if "FoamFile" in t else 0)
    faces = re.findall(r"\d+\(([^()]*)\)", t[pos:])
    centres = []
    for fi in ids:
        v = [pts[int(i)] for i in faces[fi].split()]
        centres.append([sum(p[k] for p in v) / len(v) for k in range(3)])
    # a spot: [x, y, z, radius]; a wrong face inside a spot already kept unsplit doubles that spot's radius
    # (the split cells around it still cut its edges), any other starts a spot of 3 wall cells
    rec = load_record(case)
    store = os.path.join(case, "constant", "wallSplitExcluded.json")
    excluded = json.load(open(store)) if os.path.exists(store) else []
    r0 = 3.0 * rec["derived"]["h_wing"]
    grown = set()
    for c in centres:
        near = [i for i, e in enumerate(excluded) if math.dist(c, e[:3]) <= e[3]]
        if near:
            grown.update(near)
        else:
            excluded.append(c + [r0])
    for i in grown:
        excluded[i][3] *= 2
    with open(store, "w") as f:
        json.dump(excluded, f)
    lo, hi, dom = rec["wing"]["min"], rec["wing"]["max"], rec["domain"]
    write_split_set(os.path.join(case, "system"), os.path.basename(rec["settings_file"]), dom["min"], dom["max"],
                    0.92 * max(abs(lo[1]), abs(hi[1])), excluded)
    new = centres
    print(f"ramair_fluid: wall_split: {len(new)} wrong-oriented faces after the split; {len(excluded)} spots left "
          "unsplit, splitting again")
    return False


def write_case(settings_path, stl_path, case):
    s = read_settings(settings_path)
    tris = read_stl(stl_path)
    a = math.radians(s["angle"])
    geo = wing_geometry(tris, (-math.sin(a), 0.0, math.cos(a)))
    d = derived(s, geo)
    res = RESOLUTIONS[s["resolution"]]
    src = os.path.basename(settings_path)
    c = geo["chord"]
    lo, hi = geo["min"], geo["max"]
    bmin, bmax, n = domain(geo, s, d["h0"])
    sysd, cons = os.path.join(case, "system"), os.path.join(case, "constant")
    mirror = s["mirror_mesh"] == "yes"
    half = s["half_domain"] == "yes"
    if mirror or half:
        # The half y >= 0, its far side as far out as the whole box's; mirrorMesh adds the other half.
        span = hi[1] - lo[1]
        if abs(hi[1] + lo[1]) > 1e-6 * span:
            raise InputError(f"{settings_path}: mirror_mesh yes needs a wing symmetric about y = 0; the skin "
                             f"{stl_path} spans y = {lo[1]:.6g} .. {hi[1]:.6g}")
        n[1] = max(1, math.ceil((hi[1] + s["lateral"] * c) / d["h0"]))
        bmin[1], bmax[1] = 0.0, n[1] * d["h0"]

    if mirror:
        write(os.path.join(sysd, "mirrorMeshDict"), "dictionary", "mirrorMeshDict", src,
              "// The half mesh's mirror image about y = 0; the faces on the plane become internal faces.\n"
              "planeType pointAndNormal;\npointAndNormalDict { point (0 0 0); normal (0 1 0); }\n"
              "planeTolerance 1e-6;\n")
    write_block_mesh(sysd, src, bmin, bmax, n, mirror, half)

    write(os.path.join(sysd, "surfaceFeatureExtractDict"), "dictionary", "surfaceFeatureExtractDict", src,
          "// Sharp edges of the skin (trailing edge, rib seams at the tips) for snappyHexMesh's feature snapping.\n"
          "wing.stl\n{\n  extractionMethod extractFromSurface;\n"
          "  extractFromSurfaceCoeffs { includedAngle 150; }\n"
          "  subsetFeatures { nonManifoldEdges no; openEdges yes; }\n  writeObj no;\n}\n")

    # Refinement boxes: near the wing (half a chord around it, 1.5 chords behind), the wake (7 chords behind,
    # one chord around, along the flow).
    near_lo = [lo[0] - 0.5 * c, lo[1] - 0.5 * c, lo[2] - 0.5 * c]
    near_hi = [hi[0] + 1.5 * c, hi[1] + 0.5 * c, hi[2] + 0.5 * c]
    wake_dz = 7 * c * math.tan(a)
    wake_lo = [lo[0] - c, lo[1] - c, lo[2] - c + min(0.0, wake_dz)]
    wake_hi = [hi[0] + 7 * c, hi[1] + c, hi[2] + c + max(0.0, wake_dz)]
    # A point of the fluid: upstream of the wing, off every plane of background cell faces.
    inside = [lo[0] - 2.0 * c + 0.1137 * d["h0"], 0.0733 * d["h0"], 0.5 * (lo[2] + hi[2]) + 0.1791 * d["h0"]]
    if not all(bmin[i] < inside[i] < bmax[i] for i in range(3)) or lo[0] <= inside[0] <= hi[0]:
        raise InputError("locationInMesh would not lie in the fluid: domain too small")
    # wall_split: the set of cells refineWallLayer may split (Allrun): all but those near the tips, whose sharp
    # edge between the skin and the tip rib gives inverted face pyramids when split
    if s["wall_split"] > 0:
        write_split_set(sysd, src, bmin, bmax, 0.92 * max(abs(lo[1]), abs(hi[1])), [])
    # prism_layers: the first layer's centre at y+ ~ 50 with flat-plate friction at Re_x = 5e5 on the chord
    # (Cf = 0.027 Re_x^(-1/7), White): 0.0022 chord thick, growing by 1.2 until a layer reaches half the wall cell
    plain_spec = ("relativeSizes true; layers { }; expansionRatio 1.2; finalLayerThickness 0.5; "
                  "minThickness 0.1;")
    layers_on, layer_spec = "false", plain_spec
    if s["prism_layers"] == "yes":
        first, growth = 0.0022 * c, 1.2
        nlay = 0
        while first * growth ** nlay < 0.5 * d["h_wing"]:
            nlay += 1
        layers_on = "true"
        layer_spec = (f"// {nlay} layers, the first {first:.4g} m thick, growing by {growth:g}\n"
                      f"  relativeSizes false; layers {{ wing {{ nSurfaceLayers {nlay}; }} }}; expansionRatio {growth:g};\n"
                      f"  firstLayerThickness {first:.6g}; minThickness {0.5 * first:.6g};")
    wall_spec = (f"// wall_layers: {s['wall_layers']} layers sized on the wall cell, the outermost 0.4 of it\n"
                 f"  relativeSizes true; layers {{ wing {{ nSurfaceLayers {s['wall_layers']}; }} }}; expansionRatio 1.3; "
                 "finalLayerThickness 0.4; minThickness 0.05;")
    if s["wall_layers"] > 0 and s["wall_after"] == 0:
        layers_on, layer_spec = "true", wall_spec

    def snappy_dict(layers_on, layer_spec):
        return f"""\
castellatedMesh true;
snap true;
addLayers {layers_on};   // prism_layers (docs/AERODYNAMICS.md): without them y+ is whatever the wall cell gives
geometry
{{
  wing.stl {{ type triSurfaceMesh; name wing; }}
  near {{ type searchableBox; min {v3(near_lo)}; max {v3(near_hi)}; }}
  wake {{ type searchableBox; min {v3(wake_lo)}; max {v3(wake_hi)}; }}
}}
castellatedMeshControls
{{
  maxLocalCells 2000000; maxGlobalCells 4000000; minRefinementCells 10; maxLoadUnbalance 0.10;
  nCellsBetweenLevels 3;
  features ( {{ file "wing.eMesh"; level {res["features"]}; }} );
  refinementSurfaces {{ wing {{ level ({res["surface"][0]} {res["surface"][1]}); patchInfo {{ type wall; }} }} }}
  resolveFeatureAngle 30;
  refinementRegions
  {{
    near {{ mode inside; levels ((1e15 {res["near"]})); }}
    wake {{ mode inside; levels ((1e15 {res["wake"]})); }}
  }}
  // The fluid is outside the closed skin: this point lies upstream of the wing.
  locationInMesh {v3(inside)};
  allowFreeStandingZoneFaces true;
}}
snapControls
{{
  nSmoothPatch 3; tolerance 2.0; nSolveIter 100; nRelaxIter 5;
  nFeatureSnapIter 10; implicitFeatureSnap false; explicitFeatureSnap true; multiRegionFeatureSnap false;
}}
addLayersControls
{{
  {layer_spec}
  nGrow 0; featureAngle 60; nRelaxIter 3; nSmoothSurfaceNormals 1; nSmoothNormals 3; nSmoothThickness 10;
  maxFaceThicknessRatio 0.5; maxThicknessToMedialRatio 0.3; minMedialAxisAngle 90; nBufferCellsNoExtrude 0;
  nLayerIter 50;
}}
// maxBoundarySkewness 4 (not the usual 20): snapping leaves the two or so faces at the sharp trailing edge
// that would exceed checkMesh's skewness limit (4) a little short of the edge instead of failing checkMesh
// there (coarse mesh: skewness 4.21 -> 3.49, the same cells, the wing patch area unchanged to 1e-5). Those
// faces are also where mesh motion first inverts cells (feasibility trial).
meshQualityControls
{{
  maxNonOrtho 65; maxBoundarySkewness 4; maxInternalSkewness 4; maxConcave 80; minVol 1e-13;
  minTetQuality 1e-15; minArea -1; minTwist 0.02; minDeterminant 0.001; minFaceWeight 0.05; minVolRatio 0.01;
  minTriangleTwist -1; nSmoothScale 4; errorReduction 0.75;
  relaxed {{ maxNonOrtho 75; }}
}}
mergeTolerance 1e-6;
"""
    write(os.path.join(sysd, "snappyHexMeshDict"), "dictionary", "snappyHexMeshDict", src,
          snappy_dict(layers_on, layer_spec))
    if s["wall_layers"] > 0 and s["wall_after"] > 0:
        # wall_after: the new mesh with the thin wall cells (Allrun: snappyHexMesh -dict)
        write(os.path.join(sysd, "snappyHexMeshDict.wall"), "dictionary", "snappyHexMeshDict", src,
              "// wall_after: the mesh from that step on, with wall_layers\n" + snappy_dict("true", wall_spec))

    rans = s["model"] == "kOmegaSST"
    write(os.path.join(cons, "transportProperties"), "dictionary", "transportProperties", src,
          f"transportModel Newtonian;\nnu {s['nu']:.9g};   // Re = {d['Re']:.4g} on the chord {c:.4g} m\n")
    write(os.path.join(cons, "turbulenceProperties"), "dictionary", "turbulenceProperties", src,
          "simulationType RAS;\nRAS { RASModel kOmegaSST; turbulence on; printCoeffs on; }\n" if rans
          else "simulationType laminar;\n")
    if s["mesh_motion"] == "laplacian":
        motion = ("dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolverLibs (\"libfvMotionSolvers.so\");\n"
                  "motionSolver displacementLaplacian;\n"
                  "// Diffusivity falling with the distance from the wing keeps the cells next to it rigid.\n"
                  f"displacementLaplacianCoeffs {{ diffusivity {DIFFUSIVITY[s['motion_diffusivity']]}; }}\n")
    elif s["mesh_motion"] == "rigidfit":
        inner, outer = s["rigid_inner"] * c, s["rigid_outer"] * c
        # The far field of the whole domain: with mirror_mesh the box's plane y = 0 is no boundary of the fluid.
        far_lo = [bmin[0], -bmax[1] if mirror else bmin[1], bmin[2]]
        clearance = min(min(w_lo - b_lo, b_hi - w_hi) for b_lo, b_hi, w_lo, w_hi in zip(far_lo, bmax, lo, hi))
        if not outer < clearance:
            raise InputError(f"{settings_path}: rigid_outer {s['rigid_outer']:g} chords reaches the far field, "
                             f"{clearance / c:.3g} chords from the wing: the far field must stay put")
        motion = ("dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolverLibs (\"libfsiFoam.so\");\n"
                  "// The wing's best-fit rigid motion (its swing on the lines) moves the cells within innerDistance\n"
                  "// rigidly and fades out by outerDistance; the Laplacian carries the rest (the canopy's deformation).\n"
                  "motionSolver fsiRigidFitDisplacementLaplacian;\n"
                  f"displacementLaplacianCoeffs\n{{\n  diffusivity {DIFFUSIVITY[s['motion_diffusivity']]};\n"
                  f"  patches (wing);\n  innerDistance {inner:.6g};   // {s['rigid_inner']:g} chords\n"
                  f"  outerDistance {outer:.6g};   // {s['rigid_outer']:g} chords\n}}\n")
    else:
        motion = "// Rigid wing: no mesh motion (mesh_motion laplacian in the settings moves it).\ndynamicFvMesh staticFvMesh;\n"
    write(os.path.join(cons, "dynamicMeshDict"), "dictionary", "dynamicMeshDict", src, motion)

    steady = s["solver"] == "simple"
    write(os.path.join(sysd, "fvSchemes"), "dictionary", "fvSchemes", src, f"""\
ddtSchemes {{ default {"steadyState" if steady else "Euler"}; }}
gradSchemes {{ default Gauss linear; grad(U) cellLimited Gauss linear 1; }}
divSchemes
{{
  default none;
  div(phi,U) bounded Gauss linearUpwind grad(U);
  div(phi,k) bounded Gauss upwind;
  div(phi,omega) bounded Gauss upwind;
  div((nuEff*dev2(T(grad(U))))) Gauss linear;
}}
laplacianSchemes {{ default Gauss linear limited corrected 0.33; }}
interpolationSchemes {{ default linear; }}
snGradSchemes {{ default limited corrected 0.33; }}
wallDist {{ method meshWave; }}
""")
    if steady:
        algorithm = f"""\
// Steady (solver simple): SIMPLE with under-relaxation, {s['steps']} iterations; the residuals and the forces'
// spread over the last fifth of the iterations say whether it converged (summary.json).
SIMPLE
{{
  nNonOrthogonalCorrectors 1; consistent no;
  residualControl {{ p 1e-5; U 1e-6; "(k|omega)" 1e-6; }}   // initial residuals: stop when all are below
}}
relaxationFactors {{ fields {{ p 0.3; }} equations {{ U 0.7; k 0.7; omega 0.7; }} }}
"""
    else:
        algorithm = f"""\
// Pseudo-transient: large steps (Courant {s['courant']:g} at the wing), outer correctors under-relaxed, the
// final corrector of each step not relaxed.
PIMPLE
{{
  momentumPredictor yes; nOuterCorrectors {s['outer_correctors']}; nCorrectors 1; nNonOrthogonalCorrectors 1;
  correctPhi {s['correct_phi']};
}}
relaxationFactors {{ fields {{ p 0.5; }} equations {{ U 0.8; k 0.8; omega 0.8; }} }}
"""
    write(os.path.join(sysd, "fvSolution"), "dictionary", "fvSolution", src, f"""\
solvers
{{
  p {{ solver GAMG; smoother GaussSeidel; tolerance 1e-6; relTol 0.05; }}
  pFinal {{ $p; relTol 0; }}
  "(pcorr|pcorrFinal)" {{ solver GAMG; smoother GaussSeidel; tolerance 1e-6; relTol 0; }}
  "cellDisplacement.*" {{ solver GAMG; smoother GaussSeidel; tolerance 1e-8; relTol 0; }}
  "(U|k|omega)" {{ solver smoothSolver; smoother symGaussSeidel; tolerance 1e-8; relTol 0.1; }}
  "(U|k|omega)Final" {{ solver smoothSolver; smoother symGaussSeidel; tolerance 1e-8; relTol 0; }}
}}
""" + algorithm)

    coupling_libs, coupling = "", ""
    if s["coupled"] == "yes":
        coupling_libs = ("// The interface boundary condition (pointDisplacement on the wing) comes from the adapter.\n"
                         "libs (\"libfsiFoam.so\");\n")
        implicit = (f" tolerance {s['tolerance']:.9g}; maxIterations {s['max_iterations']};"
                    if s["scheme"] == "implicit" else "")
        carry_from = (f"\n    equilibriumCarryFrom {s['carry_after'] * d['deltaT']:.9g};   // after "
                      f"{s['carry_after']} steps from rest" if s["carry_after"] > 0 else "")
        mode = (f"structureMode equilibrium; equilibriumSteps {s['equilibrium_steps']}; "
                f"equilibriumStart {s['equilibrium_start']};{carry_from}"
                if s["structure_mode"] == "equilibrium" else
                f"structureMode timeAccurate; subcycles {s['subcycles']};")
        remesh = (f"\n    remeshBelow {s['remesh_below']:.9g};   // then Allrun snaps a new mesh to the canopy"
                  if s["remesh_below"] > 0 else "")
        if s["wall_after"] > 0:
            remesh += (f"\n    remeshAt {s['wall_after'] * d['deltaT']:.12g};   // wall_after {s['wall_after']} "
                       "steps: a new mesh with thin wall cells")
        if remesh:
            remesh += "\n    remeshSurface \"constant/triSurface/generated/wing.stl\";   // the design skin, moved"
        coupling = f"""\
  // The canopy of structure-coupled.yaml (structure.yaml with this case's ram pressure, line-drag wind and
  // coupling interface) on the wing patch; the fluid's pressure is gauge (freestreamPressure 0) like the ram
  // pressure inside the skin, so the net load on the skin is outside minus inside.
  fsi
  {{
    type fsiCoupling; libs ("libfsiFoam.so");
    patches (wing); rho {s['rho']:.9g}; pRef 0; viscous yes;
    scene "structure-coupled.yaml";
    scheme {s['scheme']};{implicit}
    {mode}
    loadRelaxation {s['load_relaxation']:.9g}; keepSide {s['keep_side']};
    gapCorrection {s['gap_correction']}; smoothingLength {s['smoothing_length']:.9g};
    conserveMoment {s['conserve_moment']};{remesh}
  }}
  // The wall shear stress on the wing (kinematic, like p) with the fields: with p the load on each face of
  // the skin for the summary's spanwise lift distribution (ramair_wing.py)
  wallShearStress
  {{
    type wallShearStress; libs ("libfieldFunctionObjects.so"); patches (wing); writeControl writeTime; log false;
  }}
"""
    # A run that stops for new meshes restarts from a time directory's name: 12 digits keep the restarted
    # times on the steps' (8 drifted by 5e-9 s per restart until OpenFOAM lengthened the names itself).
    precision = 12 if s["remesh_below"] > 0 or s["wall_after"] > 0 else 8

    # half_domain: the half wing's forces over half the reference area are the whole wing's coefficients
    aref = d["Aref"] / 2 if half else d["Aref"]
    y_plus = ("  // y+ of the first cell centre on the wing (wall functions: valid for about 30-300), written with the\n"
              "  // fields and as min/max/mean per step in postProcessing/yPlus\n"
              "  yPlus { type yPlus; libs (\"libfieldFunctionObjects.so\"); writeControl writeTime; log false; }\n"
              if s["model"] == "kOmegaSST" else "")

    def control_dict(libs, fsi, steps, end, every):
        if steady:
            timing = (f"application simpleFoam;\n// steady: {steps} SIMPLE iterations (time = iteration)\n"
                      f"startFrom latestTime; startTime 0; stopAt endTime; endTime {steps}; deltaT 1;")
        else:
            timing = (f"application pimpleFoam;\n// deltaT = courant {s['courant']:g} * finest wing cell "
                      f"{d['h_wing']:.6g} m / speed {s['speed']:g} m/s; {steps} steps\n"
                      f"startFrom latestTime; startTime 0; stopAt endTime; endTime {end:.12g}; deltaT {d['deltaT']:.12g};")
        return f"""\
{timing}
writeControl timeStep; writeInterval {every}; purgeWrite 0; writeFormat ascii; writePrecision 10;
writeCompression off; timeFormat general; timePrecision {precision}; runTimeModifiable false; adjustTimeStep no;
{libs}functions
{{
{fsi}{y_plus}  // CL, CD about the free stream; reference area = the wing's area projected on the plane normal to the lift
  // direction ({d['Aref']:.6g} m^2{"; the half wing's: half of it" if half else ""}), reference length = the centre
  // chord ({c:.6g} m), moments about its quarter chord.
  forceCoeffs
  {{
    type forceCoeffs; libs ("libforces.so"); writeControl timeStep; writeInterval 1; log false;
    patches (wing); rho rhoInf; rhoInf {s['rho']:.9g};
    liftDir {v3(d['lift_dir'])}; dragDir {v3(d['flow_dir'])}; pitchAxis (0 1 0);
    CofR {v3(d['CofR'])}; magUInf {s['speed']:.9g}; lRef {c:.9g}; Aref {aref:.9g};
  }}
  forces
  {{
    type forces; libs ("libforces.so"); writeControl timeStep; writeInterval 1; log false;
    patches (wing); rho rhoInf; rhoInf {s['rho']:.9g}; CofR {v3(d['CofR'])};
  }}
}}
"""

    write(os.path.join(sysd, "controlDict"), "dictionary", "controlDict", src,
          control_dict(coupling_libs, coupling, s["steps"], d["endTime"],
                       min(s["steps"], s["write_interval"] or s["steps"])))
    if s["coupled"] == "yes" and s["rigid_steps"] > 0:
        # The rigid start (Allrun swaps these in, runs, copies the last fields to 0/ and swaps them back).
        nr = s["rigid_steps"]
        write(os.path.join(sysd, "controlDict.rigid"), "dictionary", "controlDict", src,
              "// The rigid wing's start-up run before the coupling (rigid_steps).\n"
              + control_dict("", "", nr, nr * d["deltaT"], nr))  # the rigid start writes its end only
        write(os.path.join(cons, "dynamicMeshDict.rigid"), "dictionary", "dynamicMeshDict", src,
              "// The rigid wing's start-up run: no mesh motion.\ndynamicFvMesh staticFvMesh;\n")

    write(os.path.join(sysd, "decomposeParDict"), "dictionary", "decomposeParDict", src,
          "// hierarchical, cut along x: Debian's scotch library is a stub that stops decomposePar.\n"
          f"numberOfSubdomains {s['ranks']};\nmethod hierarchical;\n"
          f"hierarchicalCoeffs {{ n ({s['ranks']} 1 1); delta 0.001; order xyz; }}\n")

    record = {"settings": s, "settings_file": os.path.abspath(settings_path), "stl": os.path.abspath(stl_path),
              "wing": geo, "derived": d, "domain": {"min": bmin, "max": bmax, "cells": n},
              "locationInMesh": inside, "refinement": res}
    with open(os.path.join(cons, "fluidSettings.json"), "w") as f:
        json.dump(record, f, indent=1)
    print(f"ramair_fluid: {s['model']} at {s['speed']:g} m/s, inflow angle {s['angle']:g} deg (wing incidence "
          f"{geo['incidence_deg']:.3g} deg), Re {d['Re']:.4g}; {s['resolution']} mesh, background {n[0]}x{n[1]}x{n[2]}; "
          f"deltaT {d['deltaT']:.4g} s x {s['steps']} steps; Aref {d['Aref']:.4g} m^2, AR {d['aspect_ratio']:.3g}")


def write_fields(case):
    rec = load_record(case)
    s, d = rec["settings"], rec["derived"]
    src = os.path.basename(rec["settings_file"])
    z = os.path.join(case, "0")
    u = v3(d["u_inf"])
    # half_domain: every field's entry for the symmetry plane y = 0
    sym = "  mirror { type symmetryPlane; }\n" if s.get("half_domain") == "yes" else ""
    write(os.path.join(z, "U"), "volVectorField", "U", src, f"""\
dimensions [0 1 -1 0 0 0 0];
internalField uniform {u};   // a uniform start: potentialFoam spiked at the sharp trailing edge
boundaryField
{{
  farfield {{ type freestreamVelocity; freestreamValue uniform {u}; value uniform {u}; }}
  wing {{ type movingWallVelocity; value uniform (0 0 0); }}   // = noSlip while the wing is rigid
{sym}}}
""")
    write(os.path.join(z, "p"), "volScalarField", "p", src, """\
dimensions [0 2 -2 0 0 0 0];   // kinematic
internalField uniform 0;
boundaryField
{
  farfield { type freestreamPressure; freestreamValue uniform 0; value uniform 0; }
  wing { type zeroGradient; }
""" + sym + """}
""")
    wing = ("wing { type fsiInterfaceDisplacement; value uniform (0 0 0); }   // the structure's displacement"
            if s["coupled"] == "yes" else
            "wing { type fixedValue; value uniform (0 0 0); }   // rigid (coupled yes: fsiInterfaceDisplacement)")
    write(os.path.join(z, "pointDisplacement"), "pointVectorField", "pointDisplacement", src, """\
dimensions [0 1 0 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
  """ + wing + """
  farfield { type fixedValue; value uniform (0 0 0); }
  "procBoundary.*" { type processor; value uniform (0 0 0); }
""" + sym + """}
""")
    if s["model"] == "kOmegaSST":
        k, om = d["k_inf"], d["omega_inf"]
        for name, val, wall in (("k", k, f"kqRWallFunction; value uniform {k:.9g}"),
                                ("omega", om, f"omegaWallFunction; value uniform {om:.9g}")):
            dims = "[0 2 -2 0 0 0 0]" if name == "k" else "[0 0 -1 0 0 0 0]"
            write(os.path.join(z, name), "volScalarField", name, src, f"""\
dimensions {dims};
internalField uniform {val:.9g};
boundaryField
{{
  farfield {{ type inletOutlet; inletValue uniform {val:.9g}; value uniform {val:.9g}; }}
  wing {{ type {wall}; }}
{sym}}}
""")
        write(os.path.join(z, "nut"), "volScalarField", "nut", src, """\
dimensions [0 2 -1 0 0 0 0];
internalField uniform 0;
boundaryField
{
  farfield { type calculated; value uniform 0; }
  wing { type nutUSpaldingWallFunction; value uniform 0; }   // no prism layers: y+ 75-3000 (docs/RAMAIR.md)
""" + sym + """}
""")


def write_structure(settings_path, scene_path, out_path):
    """The coupled run's structure scene: structure.yaml with the ram pressure q = rho U^2 / 2 of these settings
    inside the skin, the free stream as the line-drag wind and the skin as the coupling interface; the
    structure-only `time` entries (end time, static-state test) are dropped: the fluid's time drives the run.
    /usr/bin/python3's yaml (python3-yaml), safe loader only: the scene is data, nothing in it runs."""
    import yaml  # Debian's python3-yaml (scripts/install-deps.sh)

    s = read_settings(settings_path)
    try:
        with open(scene_path, encoding="utf-8") as f:
            scene = yaml.safe_load(f)
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as e:
        raise InputError(f"{scene_path}: cannot read the scene: {e}")
    if not isinstance(scene, dict) or not isinstance(scene.get("effects"), dict):
        raise InputError(f"{scene_path}: no 'effects' map: a coupled ram-air wing needs its internal pressure there")
    eff = scene["effects"]
    pressure = eff.get("pressure")
    if not isinstance(pressure, dict) or pressure.get("triangles") != "wing/skin":
        raise InputError(f"{scene_path}: effects.pressure must be the ram pressure inside the skin "
                         "({triangles: wing/skin, value: ...}): its value is set from the settings' speed and rho")
    a = math.radians(s["angle"])
    q = 0.5 * s["rho"] * s["speed"] ** 2
    pressure["value"] = float(f"{q:.9g}")
    if isinstance(eff.get("line_drag"), dict):
        eff["line_drag"]["wind"] = [float(f"{s['speed'] * v:.9g}") for v in (math.cos(a), 0.0, math.sin(a))]
        eff["line_drag"]["density"] = float(f"{s['rho']:.9g}")
    if s["trailing_edge_tape"] == "yes":
        gen = scene.get("meshes", {}).get("wing", {}).get("generator") if isinstance(scene.get("meshes"), dict) else None
        if not isinstance(gen, dict) or gen.get("type") != "parafoil":
            raise InputError(f"{scene_path}: trailing_edge_tape needs the canopy as meshes.wing.generator "
                             "(type: parafoil)")
        gen["trailing_edge_tape"] = True
    # Brakes: each pulled toggle leaves the held points and is drawn down (-z), by a smooth ramp or the table
    for side, function, amplitude in brake_inputs(s):
        cons = scene.get("constraints")
        toggle = f"wing/toggle_{side}"
        held = next((c for c in cons if isinstance(c, dict) and c.get("fix") == "all"
                     and isinstance(c.get("nodes"), list) and toggle in c["nodes"]), None) \
            if isinstance(cons, list) else None
        if held is None:
            raise InputError(f"{scene_path}: brake_{side} needs a constraint {{nodes: [..., {toggle}], fix: all}} "
                             f"holding the {side} toggle")
        held["nodes"] = [n for n in held["nodes"] if n != toggle]
        cons.append({"nodes": toggle, "prescribe": {"direction": [0, 0, -1], "amplitude": amplitude,
                                                     "function": function}})
    if "coupling" in scene:
        raise InputError(f"{scene_path}: has a 'coupling' entry: the case sets it (interface: wing/skin)")
    scene["coupling"] = {"interface": "wing/skin"}
    time = scene.get("time")
    if isinstance(time, dict):
        kept = {k: v for k, v in time.items() if k in ("mass_scaling_min_dt",)}
        if kept:
            scene["time"] = kept
        else:
            del scene["time"]
    with open(out_path, "w", encoding="utf-8") as f:
        f.write(f"# Written by ramair_fluid.py from {os.path.basename(scene_path)} and "
                f"{os.path.basename(settings_path)}: edit those, not this file.\n"
                f"# Ram pressure q = {q:.6g} Pa ({s['speed']:g} m/s, rho {s['rho']:g}); wind = the free stream.\n")
        yaml.safe_dump(scene, f, sort_keys=False, default_flow_style=None, width=110)
    print(f"ramair_fluid: {out_path}: q = {q:.5g} Pa inside the skin, interface wing/skin")


def load_record(case):
    path = os.path.join(case, "constant", "fluidSettings.json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: {e} (run 'ramair_fluid.py write' first)")


# ---------------------------------------------------------------------------------------------------------
# Reading the results


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


def read_table(path):
    rows, header = [], None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                words = line[1:].split()
                if words and words[0] == "Time":
                    header = words
                continue
            w = line.replace("(", " ").replace(")", " ").split()
            if w:
                rows.append([float(x) for x in w])
    return header, rows


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


def read_force_coeffs(case):
    """postProcessing/forceCoeffs/START/coefficient.dat of every run segment (a restart or a new mesh starts
    a new START), joined in time: a segment restarted at START writes the steps after it, and replaces what
    an earlier one wrote for them.
    Returns (header, rows, the first file)."""
    base = os.path.join(case, "postProcessing", "forceCoeffs")
    starts = []
    if os.path.isdir(base):
        for name in os.listdir(base):
            if NUMBER.match(name) and os.path.exists(os.path.join(base, name, "coefficient.dat")):
                starts.append((float(name), name))
    header, rows, first = None, [], os.path.join(base, "0", "coefficient.dat")
    for i, (t0, name) in enumerate(sorted(starts)):
        path = os.path.join(base, name, "coefficient.dat")
        h, r = read_table(path)
        if i == 0:
            header, first = h, path
        elif h != header:
            raise InputError(f"{path}: columns {h} differ from those of {first}")
        rows = [row for row in rows if row[0] <= t0 * (1 + 1e-9)] + r
    return header, rows, first


def remeshes(case):
    """The new meshes of a run with remesh_below: time, window and reason of each (structure/remesh.N/request),
    and the checkMesh of each new mesh (log.checkMesh.remeshN)."""
    out = []
    n = 1
    while os.path.exists(os.path.join(case, "structure", f"remesh.{n}", "request")):
        with open(os.path.join(case, "structure", f"remesh.{n}", "request")) as f:
            r = dict(line.rstrip("\n").split(" ", 1) for line in f if " " in line)
        item = {"time": float(r.get("time", "nan")), "window": int(r.get("window", "-1")), "reason": r.get("reason", "")}
        log = f"log.checkMesh.remesh{n}"
        if os.path.exists(os.path.join(case, log)):
            item["mesh"] = check_mesh(case, log)
        out.append(item)
        n += 1
    return out


def summary(case):
    rec = load_record(case)
    s, d = rec["settings"], rec["derived"]
    out = {"case": os.path.basename(os.path.abspath(case)), "settings": s,
           "reference": {"Aref_m2": d["Aref"], "Aref_is": "wing area projected on the plane normal to the lift direction",
                         "lRef_m": d["lRef"], "CofR": d["CofR"], "aspect_ratio": d["aspect_ratio"],
                         "span_projected_m": d["span_projected"], "Re": d["Re"], "q_Pa": d["q"]},
           "mesh": check_mesh(case)}
    area, nf = patch_area(case, "wing")
    stl = rec["wing"]["area"] / (2 if s.get("half_domain") == "yes" else 1)  # half_domain: the half wing
    out["mesh"].update({"wing_faces": nf, "wing_patch_area": area, "stl_area": stl,
                        "area_relative_difference": (area - stl) / stl})
    est = {"formula": "Helmbold: CL = a0 a / (sqrt(1 + (a0/(pi AR))^2) + a0/(pi AR)), a0 = 2 pi, "
                      "a = incidence + inflow angle - zero-lift angle",
           "attitude": "design: the rigid design skin's centre chord and aspect ratio (a coupled run's estimate at "
                       "the flown attitude: wing.estimate)",
           "incidence_deg": rec["wing"]["incidence_deg"], "alpha_effective_deg": d["alpha_effective_deg"],
           "CL": d["CL_helmbold"]}
    out["estimate"] = est
    header, rows, coeff = read_force_coeffs(case)
    if rows and not (header and all(k in header for k in ("Time", "Cd", "Cl", "Cs", "CmPitch"))):
        raise InputError(f"{coeff}: no 'Time Cd Cs Cl ... CmPitch' header")
    if rows:
        col = {name: i for i, name in enumerate(header)}
        hist = {k: [r[col[k]] for r in rows] for k in ("Cl", "Cd", "Cs", "CmPitch")}
        n = len(rows)
        tail = max(2, n // 5)

        def spread(x):
            last = x[-tail:]
            return (max(last) - min(last)) / max(abs(x[-1]), 1e-30)

        finite = all(math.isfinite(v) for k in hist for v in hist[k])
        out["flow"] = {"steps": n, "time": rows[-1][0], "CL": hist["Cl"][-1], "CD": hist["Cd"][-1],
                       "CS": hist["Cs"][-1], "CmPitch": hist["CmPitch"][-1],
                       "L_over_D": hist["Cl"][-1] / hist["Cd"][-1] if hist["Cd"][-1] else None,
                       "lift_N": hist["Cl"][-1] * d["q"] * d["Aref"], "drag_N": hist["Cd"][-1] * d["q"] * d["Aref"],
                       "CL_spread_last_fifth": spread(hist["Cl"]), "CD_spread_last_fifth": spread(hist["Cd"]),
                       "finite": finite, "CL_over_estimate": hist["Cl"][-1] / d["CL_helmbold"],
                       "history": {"CL": hist["Cl"], "CD": hist["Cd"]}}
        for log in ("log.pimpleFoam", "log.simpleFoam"):
            p = os.path.join(case, log)
            if os.path.exists(p):
                with open(p) as f:
                    times = [float(x) for x in re.findall(r"^ExecutionTime = ([\d.eE+-]+) s", f.read(), re.M)]
                if len(times) > 2:
                    out["flow"]["wall_s_per_step"] = (times[-1] - times[0]) / (len(times) - 1)
                    out["flow"]["wall_s"] = times[-1]
    if s.get("coupled") == "yes":
        out["coupled"] = coupled_summary(case, d)
        if os.path.exists(os.path.join(case, "log.checkMesh.final")):
            out["mesh_final"] = check_mesh(case, "log.checkMesh.final")
        out["remeshes"] = remeshes(case)
        if brake_window(s) and out["coupled"].get("windows"):
            out["coupled"]["brake"] = brake_response(case, s, d, out["remeshes"])
        if out["coupled"].get("windows"):
            sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
            import ramair_wing  # the wing engineer's numbers and plots (same folder)
            try:
                out["wing"] = ramair_wing.analyse(case, rec, out["coupled"])
            except ramair_wing.InputError as e:
                raise InputError(str(e))
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(out, f, indent=1)
    m = out["mesh"]
    print(f"mesh: {m['cells']} cells, checkMesh {'OK' if m['ok'] else 'failed ' + str(m['failed_checks'])}"
          f"{' (only skewness: ' + str(m['max_skewness']) + ')' if m['only_skewness'] else ''}, max non-ortho "
          f"{m['max_non_orthogonality']}; wing patch {area:.5g} m^2 vs STL {stl:.5g} m^2 "
          f"({100 * m['area_relative_difference']:+.2f} %)")
    if "mesh_final" in out:
        mf = out["mesh_final"]
        print(f"moved mesh at the end: checkMesh {'OK' if mf['ok'] else 'failed ' + str(mf['failed_checks'])}, "
              f"max non-ortho {mf['max_non_orthogonality']}, max skewness {mf['max_skewness']}")
    if "coupled" in out and out["coupled"].get("windows"):
        write_table(case, out)
        c = out["coupled"]
        print(f"coupled: {c['windows']} windows, {c['iterations_mean']:.2f} iterations per window (at most "
              f"{c['iterations_max']}, {c['not_converged']} not converged); interface force fluid vs structure "
              f"{c['force_fluid_vs_structure_max_relative']:.1e}, moment "
              f"{c['moment_fluid_vs_structure_max_relative'] or float('nan'):.1e}")
        print(f"  canopy: lift {c['lift_N']:.2f} N, drag {c['drag_N']:.2f} N, side {c['side_N']:.3f} N")
        if "wing" in out:
            import ramair_wing
            for line in ramair_wing.headline(out["wing"]):
                print(line)
        print(f"  anchor + toggles {v3(c['support_reaction_N'])} N vs applied {v3(c['applied_load_N'])} N "
              f"(balance {c['equilibrium_relative']:.1e})")
        print(f"  skin stress mean {c['skin_stress_mean_Pa'] / 1e3:.1f} kPa, max "
              f"{c['skin_stress_max_Pa'] / 1e3:.1f} kPa (ratio {c['stress_max_over_mean']:.2f})")
    for i, r in enumerate(out.get("remeshes", []), 1):
        m = r.get("mesh", {})
        print(f"remesh {i}: t = {r['time']:g} s (window {r['window']}), {r['reason']}; new mesh {m.get('cells', '?')} "
              f"cells, max skewness {m.get('max_skewness', '?')}")
    b = out.get("coupled", {}).get("brake")
    if b and b["held"]:
        h, p = b["held"], b["before"]
        turn = "a right turn" if h["yaw_Nm"] < 0 else "a left turn"
        print(f"brakes left/right {b['travel_left_m']:g} / {b['travel_right_m']:g} m (asks for a "
              f"{b['turn_asked']} turn), held for {b['held_windows']} windows: load about the anchor yaw "
              f"{h['yaw_Nm']:.3f} N m ({turn}; before "
              f"{p['yaw_Nm']:.3f}), roll {h['roll_Nm']:.3f} N m (before {p['roll_Nm']:.3f}), side force "
              f"{h['side_N']:.2f} N, brake lines right/left {h['brake_right_N']:.1f} / {h['brake_left_N']:.1f} N; "
              f"{len(b['new_meshes'])} new meshes since the pull began; plots/brake.png")
    elif b:
        print("brakes: the run ended before the pull did (plots/brake.png)")
    if "flow" in out:
        fl = out["flow"]
        print(f"flow: {fl['steps']} steps, CL {fl['CL']:.4f}, CD {fl['CD']:.4f}, L/D {fl['L_over_D']:.2f} "
              f"(spread over the last fifth: CL {100 * fl['CL_spread_last_fifth']:.2f} %, CD "
              f"{100 * fl['CD_spread_last_fifth']:.2f} %); Helmbold CL {est['CL']:.3f} at the design attitude (AR "
              f"{d['aspect_ratio']:.2f}, alpha {d['alpha_effective_deg']:.2f} deg from zero lift); "
              f"{fl.get('wall_s_per_step', float('nan')):.3f} s per step")


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


def brake_response(case, s, d, new_meshes):
    """What the pulled brakes do (brake_left, brake_right or brake_table): the loads on the wing before the pull
    (the mean of the last 20 windows before it starts) and while the toggles are held (the mean of the windows
    after the ramp or the table's last row), and their histories in plots/brake.png. Signs as a pilot reads them, for the flow's load on the
    wing about the anchor (the supports' reaction with the opposite sign; x downstream, y to the right, z up):
    yaw < 0 turns the nose (-x) towards +y, a right turn; roll > 0 lifts the right wing."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import summarize

    rows = summarize.coupling_rows(case)
    t0, t1 = brake_window(s)
    left, right = brake_travel(s)
    lift_dir, flow_dir = d["lift_dir"], d["flow_dir"]

    def dot(a, b):
        return sum(x * y for x, y in zip(a, b))

    def series(r):
        f = [float(r[f"F{c}_fluid"]) for c in "xyz"]
        return {"yaw_Nm": -float(r["anchor_moment_z"]), "roll_Nm": -float(r["anchor_moment_x"]),
                "side_N": f[1], "lift_N": dot(f, lift_dir), "drag_N": dot(f, flow_dir),
                "brake_right_N": float(r["brake_tension_right"]), "brake_left_N": float(r["brake_tension_left"])}

    t = [float(r["time"]) for r in rows]
    v = [series(r) for r in rows]
    before = [x for x, tt in zip(v, t) if tt <= t0][-20:]
    held = [x for x, tt in zip(v, t) if tt >= t1]

    def mean(part):
        return {k: sum(x[k] for x in part) / len(part) for k in part[0]} if part else None

    out = {"start_s": t0, "end_of_ramp_s": t1, "travel_m": right, "travel_left_m": left, "travel_right_m": right,
           "before": mean(before),
           "held": mean(held), "held_windows": len(held),
           "new_meshes": [m["time"] for m in new_meshes if m["time"] >= t0 - 1e-9]}
    if held:
        h = out["held"]
        out["right_turn"] = h["yaw_Nm"] < 0 and h["brake_right_N"] > h["brake_left_N"]
        out["left_turn"] = h["yaw_Nm"] > 0 and h["brake_left_N"] > h["brake_right_N"]
        # the turn the inputs ask for: the side pulled further (a symmetric pull asks for none)
        out["turn_asked"] = "right" if right > left else "left" if left > right else "none"
        out["held_range"] = {k: [min(x[k] for x in held), max(x[k] for x in held)] for k in held[0]}
    plot_brake(case, t, v, out)
    return out


def plot_brake(case, t, v, b):
    """plots/brake.png: yaw and roll of the load about the anchor, side force, lift and drag, brake line
    tensions, from shortly before the pull to the end; the ramp shaded, new meshes marked."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("ramair_fluid: no matplotlib: plots/brake.png not written", file=sys.stderr)
        return
    lo = b["start_s"] - 0.5 * (b["end_of_ramp_s"] - b["start_s"])
    keep = [i for i, tt in enumerate(t) if tt >= lo]
    tt = [t[i] for i in keep]
    panels = [("moments [N m]", [("yaw_Nm", "yaw of the load about the anchor (< 0: nose to the right)"),
                                 ("roll_Nm", "roll (> 0: right wing up)")]),
              ("side force [N]", [("side_N", "side force (+y: right)")]),
              ("lift and drag [N]", [("lift_N", "lift"), ("drag_N", "drag")]),
              ("brake lines [N]", [("brake_right_N", "right"), ("brake_left_N", "left")])]
    fig, axes = plt.subplots(len(panels), 1, figsize=(8, 9), sharex=True)
    for ax, (label, curves) in zip(axes, panels):
        for key, name in curves:
            ax.plot(tt, [v[i][key] for i in keep], label=name)
        ax.axvspan(b["start_s"], b["end_of_ramp_s"], color="0.9", label="pull (ramp)")
        for i, tm in enumerate(b["new_meshes"]):
            ax.axvline(tm, color="tab:red", ls=":", lw=0.8, label="new mesh" if i == 0 else None)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    axes[-1].set_xlabel("time [s]")
    fig.suptitle(f"brakes left {b['travel_left_m']:g} m, right {b['travel_right_m']:g} m down, from "
                 f"{b['start_s']:g} to {b['end_of_ramp_s']:g} s")
    fig.tight_layout()
    os.makedirs(os.path.join(case, "plots"), exist_ok=True)
    fig.savefig(os.path.join(case, "plots", "brake.png"), dpi=110)
    plt.close(fig)


def write_table(case, out):
    """summary.md: the coupled run's answers in one table, with the references they are compared with."""
    c, e, d = out["coupled"], out["estimate"], out["reference"]
    rows = [("windows (fluid steps), coupling", f"{c['windows']}, {c['iterations_mean']:.2f} iterations per window", "")]
    if "wing" in out:
        import ramair_wing
        rows += ramair_wing.table_rows(out["wing"])
    else:  # a run without the structure's mesh and frames: the flow's force on the design area only
        rows.append(("CL, CD of the canopy, L/D (design projected area)",
                     f"{c['CL']:.4f}, {c['CD']:.4f}, {c['L_over_D']:.2f}", f"A = {d['Aref_m2']:.3f} m^2"))
    rows += [
        ("side force [N]", f"{c['side_N']:.3f}", "mirror symmetry: 0"),
        ("anchor + toggles reaction [N]", v3(c["support_reaction_N"]), "minus the applied load at equilibrium"),
        ("applied load (flow + ram pressure + line drag) [N]", v3(c["applied_load_N"]),
         f"balance {c['equilibrium_relative']:.1e}"),
        ("supports' moments about the anchor (confluence point) [N m]", v3(c["anchor_moment_Nm"]), "x: roll, z: yaw"),
        ("interface force fluid vs structure (max over windows)", f"{c['force_fluid_vs_structure_max_relative']:.1e}",
         "conservative transfer: round-off"),
        ("interface moment fluid vs structure (max over windows)",
         f"{c['moment_fluid_vs_structure_max_relative'] or float('nan'):.1e}", "round-off with conserve_moment yes (default); the surfaces' gap with no"),
        ("skin principal stress mean, max [kPa]", f"{c['skin_stress_mean_Pa'] / 1e3:.1f}, {c['skin_stress_max_Pa'] / 1e3:.1f}",
         "Kalro-Tezduyar: 758, 4337 (110, 629 lb/in^2)"),
        ("max / mean", f"{c['stress_max_over_mean']:.2f}", "Kalro-Tezduyar: 5.7"),
    ]
    b = c.get("brake")
    if b and b["held"]:
        h, p = b["held"], b["before"]
        rows += [
            (f"brakes held (left {b['travel_left_m']:g} m, right {b['travel_right_m']:g} m): yaw, roll of the load "
             "about the anchor [N m]",
             f"{h['yaw_Nm']:.3f}, {h['roll_Nm']:.3f} (before the pull {p['yaw_Nm']:.3f}, {p['roll_Nm']:.3f})",
             "yaw < 0: the nose turns right (a right turn), > 0 left; roll > 0: the right wing lifted"),
            ("brakes held: side force, lift, drag [N]",
             f"{h['side_N']:.2f}, {h['lift_N']:.2f}, {h['drag_N']:.2f} (before {p['side_N']:.2f}, {p['lift_N']:.2f}, "
             f"{p['drag_N']:.2f})", f"means over the {b['held_windows']} windows after the ramp; plots/brake.png"),
        ]
    elif b:
        rows.append(("brakes", "the run ended before the pull did", "plots/brake.png"))
    if c.get("skin_folds") is not None:
        rows.append(("skin edges turned > 90 deg from the design (folds probe)", f"{c['skin_folds']:.0f}",
                     "the trailing edge's crumple (docs/RAMAIR.md)"))
    with open(os.path.join(case, "summary.md"), "w") as f:
        f.write(f"# {out['case']}: coupled ram-air wing, {out['settings']['speed']:g} m/s, q = {d['q_Pa']:.4g} Pa, "
                f"Re {d['Re']:.3g}\n\n| quantity | this run | reference |\n|---|---|---|\n")
        for r in rows:
            f.write(f"| {r[0]} | {r[1]} | {r[2]} |\n")


def coupled_summary(case, d):
    """The coupled run from structure/coupling.csv (one row per window: interface force on both sides, the
    structure's probes): coupling statistics, the forces on the wing and on its anchor at the last window, the
    balance of the two (static equilibrium: the supports hold everything applied), line tensions, stresses."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import summarize  # the coupled cases' reader of coupling.csv (same folder)

    rows = summarize.coupling_rows(case)
    if not rows:
        return {"windows": 0}
    last = {k: float(v) for k, v in rows[-1].items()}
    q, aref = d["q"], d["Aref"]
    lift_dir, flow_dir = d["lift_dir"], d["flow_dir"]

    def vec(prefix, suffix=""):
        return [last.get(f"{prefix}{c}{suffix}", float("nan")) for c in "xyz"]

    def dot(a, b):
        return sum(x * y for x, y in zip(a, b))

    fluid = [last[f"F{c}_fluid"] for c in "xyz"]  # the flow's force on the wing (pressure + shear)
    applied = vec("applied_load_")  # everything applied to the structure: flow, ram pressure, line drag
    support = [a + b for a, b in zip(vec("anchor_force_"), vec("toggles_force_"))]
    # the applied load minus the flow's force on the skin: the line drag, and the difference between the relaxed
    # load the structure carries (load_relaxation) and the flow's latest (the line drag alone: wing.forces)
    applied_minus_flow = [a - f for a, f in zip(applied, fluid)]
    scale = max(_norm(applied), 1e-30)
    iters = [int(r["iterations"]) for r in rows]
    hist = {k: [float(r[k]) for r in rows] for k in ("time", "Fx_fluid", "Fz_fluid", "anchor_force_x",
                                                      "anchor_force_z", "residual")}
    if rows and "chord_pitch_angle" in rows[0]:
        hist["chord_pitch_angle"] = [float(r["chord_pitch_angle"]) for r in rows]
    # per window: the flow's lift and drag on the canopy
    f_w = [[float(r[f"F{k}_fluid"]) for k in "xyz"] for r in rows]
    hist["lift_N"] = [dot(f, lift_dir) for f in f_w]
    hist["drag_N"] = [dot(f, flow_dir) for f in f_w]
    lift = dot(fluid, lift_dir)
    drag = dot(fluid, flow_dir)
    smean, smax = last.get("skin_stress_mean", float("nan")), last.get("skin_stress_max", float("nan"))
    return {
        "windows": len(rows), "time": last["time"],
        "iterations_mean": sum(iters) / len(iters), "iterations_max": max(iters),
        "not_converged": sum(1 for r in rows if r["converged"] == "0"),
        "force_fluid_vs_structure_max_relative": summarize.force_difference(rows),
        "moment_fluid_vs_structure_max_relative": summarize.moment_difference(rows),
        "moment_fluid_Nm": vec("M", "_fluid"), "moment_structure_Nm": vec("M", "_structure"),
        "fluid_force_N": fluid, "lift_N": lift, "drag_N": drag, "side_N": fluid[1],
        "CL": lift / (q * aref), "CD": drag / (q * aref), "L_over_D": lift / drag if drag else None,
        "applied_minus_flow_N": applied_minus_flow, "applied_load_N": applied, "support_reaction_N": support,
        "anchor_force_N": vec("anchor_force_"), "toggles_force_N": vec("toggles_force_"),
        "equilibrium_relative": _norm([a + b for a, b in zip(applied, support)]) / scale,
        "anchor_moment_Nm": vec("anchor_moment_"),
        # the x-z angle between the mean of all leading-edge and all trailing-edge nodes: a probe of the whole
        # canopy's pitch, not a section's angle of attack (those: summary.json's wing.section_alpha)
        "mean_chord_pitch_deg": last.get("chord_pitch_angle"),
        "line_tension_max_N": last.get("line_tension_max"),
        "lines_left_sum_N": last.get("lines_left_sum"), "lines_right_sum_N": last.get("lines_right_sum"),
        "brake_tension_left_N": last.get("brake_tension_left"),
        "brake_tension_right_N": last.get("brake_tension_right"),
        "skin_stress_mean_Pa": smean, "skin_stress_max_Pa": smax,
        "stress_max_over_mean": smax / smean if smean else None,
        "enclosed_volume_m3": last.get("enclosed_volume"),
        "skin_folds": last.get("skin_folds"),
        "history": hist,
    }


def courant_check(log_path, settings_path):
    """A pimpleFoam log whose Courant number ran away (past 100 times the settings' `courant`, or not a number):
    the message naming the log, the worst Courant number and its time; None when the run stayed sane."""
    limit = 100 * read_settings(settings_path)["courant"]
    worst, when, t = None, None, None
    try:
        with open(log_path, errors="replace") as f:
            for line in f:
                if line.startswith("Time = "):
                    t = line.split()[2]
                elif line.startswith("Courant Number mean:"):
                    v = float(line.split()[-1])
                    if worst is None or (worst == worst and not v <= worst):  # a NaN is the worst and stays
                        worst, when = v, t
    except (OSError, ValueError, IndexError) as e:
        raise InputError(f"{log_path}: cannot read its Courant numbers ({e})")
    if worst is not None and not worst <= limit:
        return (f"{log_path}: the flow diverged: Courant number {worst:.4g} at t = {when} s, more than 100 times the "
                f"asked {limit / 100:g}: lower courant in {settings_path} (thin wall cells, wall_split, need a "
                "smaller step)")
    return None


def settings_table():
    """The settings as a Markdown table (docs/RAMAIR.md "Settings" is this, checked by
    tests/fluid/test_settings_table.py): key, default, range or choices, meaning."""
    def num(v):
        return f"{v:g}" if isinstance(v, float) else str(v)
    rows = ["| key | default | range | meaning |", "|---|---|---|---|"]
    for key, (kind, default, lo, hi, text) in SETTINGS.items():
        dflt = "required" if default is None else num(default)
        if kind == "file":
            dflt, rng = "none", "a CSV file"
        else:
            rng = ", ".join(kind) if isinstance(kind, list) else f"{num(lo)} – {num(hi)}" + (" (whole)" if kind == "int" else "")
        rows.append(f"| `{key}` | {dflt} | {rng} | {text.replace('|', '/')} |")
    return "\n".join(rows) + "\n"


def main(argv):
    cmds = {"generate-args": 1, "check": 1, "write": 3, "structure": 3, "fields": 1, "summary": 1,
            "settings-table": 0, "courant-check": 2,
            "patch-area": 2, "mirror-check": 1, "mirror-finish": 1, "remesh-dicts": 1, "split-stage": 3, "mesh-gate": 2,
            "split-exclude": 2}
    if len(argv) < 2 or argv[1] not in cmds or len(argv) != 2 + cmds[argv[1]]:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    try:
        cmd, args = argv[1], argv[2:]
        if cmd == "check":
            s = read_settings(args[0])
            # one word per key (a brake table as its file): Allrun reads these with sed
            print(" ".join(f"{k}={v['file'] if isinstance(v, dict) else v}" for k, v in s.items()))
        elif cmd == "generate-args":
            # The skin the fluid sees: the same generator, sampled finer than the structure (the coupling
            # maps between the two). Only validated whole numbers are printed.
            s = read_settings(args[0])
            for key in ("chordwise_points", "span_divisions"):
                if s["stl_" + key] > 0:
                    print("--set")
                    print(f"meshes.wing.generator.{key}={int(s['stl_' + key])}")
            if s["stl_bulge"] >= 0:
                print("--set")
                print(f"meshes.wing.generator.bulge={s['stl_bulge']:.9g}")
        elif cmd == "write":
            write_case(*args)
        elif cmd == "structure":
            write_structure(*args)
        elif cmd == "fields":
            write_fields(*args)
        elif cmd == "summary":
            summary(*args)
        elif cmd == "settings-table":
            sys.stdout.write(settings_table())
        elif cmd in ("courant-check", "mesh-gate"):  # a check: exit 1 with its message
            msg = (courant_check if cmd == "courant-check" else mesh_gate)(*args)
            if msg:
                print(f"ramair_fluid: {msg}", file=sys.stderr)
                return 1
        elif cmd == "mirror-check":
            mirror_check(*args)
        elif cmd == "mirror-finish":
            mirror_finish(*args)
        elif cmd == "remesh-dicts":
            write_remesh_dicts(*args)
        elif cmd == "split-exclude":
            return 0 if split_exclude(*args) else 3
        elif cmd == "split-stage":
            print("\n".join(split_stage(*args)))
        else:
            area, n = patch_area(*args)
            print(f"{area:.9g} {n}")
    except InputError as e:
        print(f"ramair_fluid: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"ramair_fluid: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
