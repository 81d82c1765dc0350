#!/usr/bin/python3
"""Rung 1 of the fluid validation ladder: the canopy's section in 2D at Re 1e6, meshed and solved the way the
3D ram-air case (cases/coupled/ramair_fluid.py) meshes and solves the wing, against independent data.

Run points (each appended to OUT/section_runs.json as soon as it is done):
  section_polar.py run --section ls0417 --alpha -4,0,4 --level coarse,medium --wall functions --out DIR
Build the figures and the summary JSON from one or more run folders:
  section_polar.py report --runs DIR [DIR ...] --json docs/data/section_polar.json --img docs/img

The mesh. A slab one background cell thick (z) around the aerofoil extruded in z, meshed by blockMesh +
snappyHexMesh with the 3D case's controls (surface levels, feature level, a near-wing and a wake box, three
cells between levels, explicit feature snapping, the same quality controls); extrudeMesh then turns the slab's
front face into a one-cell-thick mesh whose front and back patches are `empty`. The background cell is a
quarter chord (--background 0.25) and every level is lowered by two, so the cells at the wing, the boxes and
the wake are those of the 3D case's one-chord background with its levels; only the far field outside the
wake box is finer (a quarter chord instead of one chord). snappyHexMesh splits cells in z too, so a
one-chord background would carry 2^7 cells in z through the fine mesh's meshing; --background 1 reproduces
the 3D case's background exactly (affordable at the coarse level).

The far field: the 3D case's box (8 chords upstream, 16 downstream, 8 above and below) of uniform background
cells; --farfield R surrounds it with a ring of graded blocks out to R chords (a 2D section's disturbance decays
only as 1/r; docs/AERODYNAMICS.md measures what the 3D case's box costs in 2D).

The flow: kOmegaSST, nutUSpaldingWallFunction / omegaWallFunction / kqRWallFunction on the wing,
freestreamVelocity / freestreamPressure far field, free-stream intensity 0.005 and viscosity ratio 10,
linearUpwind for U, upwind for k and omega, 15 m/s, nu 1.5e-5 (Re 1e6 on the 1 m chord). simpleFoam by
default; --solver pimple runs the 3D case's pseudo-transient pimpleFoam (Courant 4 on the finest wing cell,
three outer correctors, p relaxed 0.5, U/k/omega 0.8).

--wall functions: the 3D case's mesh, no prism layers. --wall layers: snappyHexMesh adds prism layers whose
first cell puts y+ in the band of the same wall functions (cell-centre y+ about 30-100; first layer 0.0022 c
thick, expansion 1.2, as many layers as reach half the wall cell). --wall resolved: the same wall functions
on layers whose first cell sits at y+ ~ 1 (first layer 4e-5 c).

Nothing from the command line reaches a shell: OpenFOAM utilities run from argument lists; every number
written into a dictionary was parsed and range-checked here.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# ---------------------------------------------------------------------------------------------------------
# Settings shared with the 3D case (cases/coupled/ramair_fluid.py and rans.settings)

SPEED = 15.0
NU = 1.5e-5
RHO = 1.225
CHORD = 1.0
INTENSITY = 0.005
VISCOSITY_RATIO = 10.0
COURANT = 4.0
UPSTREAM, DOWNSTREAM, LATERAL = 8.0, 16.0, 8.0  # chords from the section's bounds, as the 3D case
THICKNESS = 0.1  # span of the extruded one-cell mesh [m]; Aref = chord * THICKNESS

# The 3D case's levels on a one-chord background: wing surface (min max), feature edges, near box, wake box.
# coarse and medium are the 3D case's; fine continues the pattern (each level one more).
LEVELS = {
    "coarse": {"surface": (4, 5), "features": 5, "near": 3, "wake": 2},
    "medium": {"surface": (5, 6), "features": 6, "near": 4, "wake": 3},
    "fine": {"surface": (6, 7), "features": 7, "near": 5, "wake": 4},
}
# simpleFoam iterations at most per level (residualControl may stop earlier)
MAX_ITER = {"coarse": 2000, "medium": 2500, "fine": 3000}
PIMPLE_STEPS = 300  # the 3D rans.settings runs 100 steps; a pimple point records CL at step 100 too
QUICK_LEVEL = "fine"  # --quick: the level the study found adequate for the wall-function layers

# Wall-function layers (--wall layers): first layer thickness for a cell-centre y+ of about 50 with the
# flat-plate friction of Re_x = 5e5 (White: Cf = 0.027 Re_x^(-1/7) = 0.0041, u_tau/U = 0.045):
# y_centre = 50 nu / u_tau = 1.1e-3 c, first layer 2.2e-3 c.
# --wall resolved: the same wall functions (Spalding's law and the blended omega are valid down to the
# wall) on layers whose first cell centre sits at y+ ~ 1: first layer 4e-5 c.
LAYER_FIRST = {"layers": 0.0022, "resolved": 4e-5}
LAYER_EXPANSION = 1.2
YPLUS_BAND = {"functions": None, "layers": (30.0, 100.0), "resolved": (0.0, 5.0)}
WALLS = ["functions", "layers", "resolved"]


class InputError(Exception):
    pass


# ---------------------------------------------------------------------------------------------------------
# Sections


def naca4(digits, n=200):
    """NACA 4-digit section, closed trailing edge (the -0.1036 coefficient, as the project's generator),
    cosine spacing, Selig order (trailing edge, upper surface, leading edge, lower surface)."""
    m, p, t = int(digits[0]) / 100.0, int(digits[1]) / 10.0, int(digits[2:]) / 100.0
    xs = [0.5 * (1 - math.cos(math.pi * i / n)) for i in range(n + 1)]
    up, lo = [], []
    for x in xs:
        yt = 5 * t * (0.2969 * math.sqrt(x) - 0.1260 * x - 0.3516 * x ** 2 + 0.2843 * x ** 3 - 0.1036 * x ** 4)
        if m == 0:
            yc, dy = 0.0, 0.0
        elif x < p:
            yc, dy = m / p ** 2 * (2 * p * x - x * x), 2 * m / p ** 2 * (p - x)
        else:
            yc, dy = m / (1 - p) ** 2 * (1 - 2 * p + 2 * p * x - x * x), 2 * m / (1 - p) ** 2 * (p - x)
        th = math.atan(dy)
        up.append((x - yt * math.sin(th), yc + yt * math.cos(th)))
        lo.append((x + yt * math.sin(th), yc - yt * math.cos(th)))
    return list(reversed(up)) + lo[1:]


def read_selig(path):
    pts = []
    try:
        with open(path, encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                s = line.split("#", 1)[0].strip()
                if not s:
                    continue
                w = s.split()
                try:
                    x, y = float(w[0]), float(w[1])
                except (ValueError, IndexError):
                    raise InputError(f"{path}:{n}: expected 'x y', got '{s}'")
                if not (math.isfinite(x) and math.isfinite(y)):
                    raise InputError(f"{path}:{n}: not a finite number")
                pts.append((x, y))
    except OSError as e:
        raise InputError(f"{path}: cannot read the section: {e}")
    if len(pts) < 20:
        raise InputError(f"{path}: fewer than 20 points")
    return pts


SECTIONS = {
    "naca4415": {"title": "NACA 4415", "points": lambda: naca4("4415")},
    # The ram-air case's bulged cell at mid-cell (docs/AERODYNAMICS.md rung 2): the generator's bulge of a quarter
    # of the 0.375 m cell width, scaled with the local thickness, makes NACA 4415's thickness 2.2 times larger
    # there (measured on the skin: 33 % of the chord) on the same mean line
    "naca4433": {"title": "NACA 4433 (the bulged mid-cell)", "points": lambda: naca4("4433")},
    "ls0417": {"title": "LS(1)-0417", "points": lambda: read_selig(os.path.join(HERE, "ls0417.dat"))},
}


def polygon(section):
    """The section's closed outline, counter-clockwise, chord 1 from (0,0) to (1,0); the duplicated
    trailing-edge point of a closed section dropped."""
    pts = SECTIONS[section]["points"]()
    if math.dist(pts[0], pts[-1]) < 1e-9:
        pts = pts[:-1]
    area = 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(pts, pts[1:] + pts[:1]))
    if area < 0:
        pts = pts[::-1]
    return pts


def write_stl(path, pts, z0, z1):
    """The outline extruded from z0 to z1 (beyond the slab on both sides), outward normals; ASCII."""
    with open(path, "w") as f:
        f.write("solid wing\n")
        for a, b in zip(pts, pts[1:] + pts[:1]):
            if math.dist(a, b) < 1e-12:
                continue
            dx, dy = b[0] - a[0], b[1] - a[1]
            ln = math.hypot(dx, dy)
            nrm = (dy / ln, -dx / ln, 0.0)
            for tri in (((a[0], a[1], z0), (b[0], b[1], z0), (b[0], b[1], z1)),
                        ((a[0], a[1], z0), (b[0], b[1], z1), (a[0], a[1], z1))):
                f.write(f"facet normal {nrm[0]:.9g} {nrm[1]:.9g} 0\n outer loop\n")
                for p in tri:
                    f.write(f"  vertex {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n")
                f.write(" endloop\nendfacet\n")
        f.write("endsolid wing\n")


# ---------------------------------------------------------------------------------------------------------
# Case dictionaries

HEADER = ("FoamFile {{ version 2.0; format ascii; class {cls}; object {obj}; }}\n"
          "// Written by studies/section/section_polar.py.\n")


def v3(v):
    return "(" + " ".join(f"{x:.9g}" for x in v) + ")"


def wdict(case, rel, body, cls="dictionary"):
    path = os.path.join(case, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER.format(cls=cls, obj=os.path.basename(rel)) + body)


def layer_count(h_wall, first):
    """Layers of `first` growing by LAYER_EXPANSION until a layer reaches half the wall cell."""
    n = 1
    while first * LAYER_EXPANSION ** n < 0.5 * h_wall:
        n += 1
    return n


def ring_grading(length, first, ratio=1.15):
    """Cells and total expansion (last/first) of a graded block of `length` whose first cell is `first`."""
    m = max(1, math.ceil(math.log(1 + length * (ratio - 1) / first) / math.log(ratio)))
    lo_r, hi_r = 1.0 + 1e-9, 3.0
    for _ in range(200):  # first cell of m cells growing by r: length (r - 1) / (r^m - 1) = first
        r = 0.5 * (lo_r + hi_r)
        if length * (r - 1) / (r ** m - 1) > first:
            lo_r = r
        else:
            hi_r = r
    return m, r ** (m - 1)


def write_block_mesh(case, bmin, bmax, n, bg, farfield):
    """system/blockMeshDict: the slab bmin..bmax of uniform background cells bg (the 3D case's domain); with
    farfield R > 0 a ring of graded blocks around it takes the far field to R chords from the section (cells
    growing by 1.15 from bg), the uniform cells where snappyHexMesh refines left as they are."""
    if farfield <= 0:
        xs, ys, nx, ny, gx, gy = [bmin[0], bmax[0]], [bmin[1], bmax[1]], [n[0]], [n[1]], [1.0], [1.0]
    else:
        ext = farfield * CHORD - LATERAL * CHORD
        if ext <= bg:
            raise InputError(f"--farfield {farfield:g}: must exceed the 3D case's {LATERAL:g} chords")
        m, g = ring_grading(ext, bg)
        xs = [bmin[0] - ext, bmin[0], bmax[0], bmax[0] + ext]
        ys = [bmin[1] - ext, bmin[1], bmax[1], bmax[1] + ext]
        nx, ny = [m, n[0], m], [m, n[1], m]
        gx = gy = [1.0 / g, 1.0, g]
    ni, nj = len(xs), len(ys)

    def v(i, j, k):
        return k * ni * nj + j * ni + i

    verts = [(xs[i], ys[j], (0.0, bg)[k]) for k in range(2) for j in range(nj) for i in range(ni)]
    blocks, far, front, back = [], [], [], []
    for j in range(nj - 1):
        for i in range(ni - 1):
            blocks.append(f"  hex ({v(i, j, 0)} {v(i + 1, j, 0)} {v(i + 1, j + 1, 0)} {v(i, j + 1, 0)} "
                          f"{v(i, j, 1)} {v(i + 1, j, 1)} {v(i + 1, j + 1, 1)} {v(i, j + 1, 1)}) "
                          f"({nx[i]} {ny[j]} 1) simpleGrading ({gx[i]:.9g} {gy[j]:.9g} 1)\n")
            front.append(f"({v(i, j, 0)} {v(i, j + 1, 0)} {v(i + 1, j + 1, 0)} {v(i + 1, j, 0)})")
            back.append(f"({v(i, j, 1)} {v(i + 1, j, 1)} {v(i + 1, j + 1, 1)} {v(i, j + 1, 1)})")
            if i == 0:
                far.append(f"({v(i, j, 0)} {v(i, j, 1)} {v(i, j + 1, 1)} {v(i, j + 1, 0)})")
            if i == ni - 2:
                far.append(f"({v(i + 1, j, 0)} {v(i + 1, j + 1, 0)} {v(i + 1, j + 1, 1)} {v(i + 1, j, 1)})")
            if j == 0:
                far.append(f"({v(i, j, 0)} {v(i + 1, j, 0)} {v(i + 1, j, 1)} {v(i, j, 1)})")
            if j == nj - 2:
                far.append(f"({v(i, j + 1, 0)} {v(i, j + 1, 1)} {v(i + 1, j + 1, 1)} {v(i + 1, j + 1, 0)})")
    what = ("// A slab one background cell thick around the section (the 3D case's domain, uniform cells)"
            + (f", in a ring of graded blocks\n// to {farfield:g} chords" if farfield > 0 else "")
            + "; front (z = 0) is extruded into the 2D mesh.\n")
    wdict(case, "system/blockMeshDict", what + "scale 1;\nvertices\n(\n" + "".join(f"  {v3(x)}\n" for x in verts)
          + ");\nblocks\n(\n" + "".join(blocks) + ");\nboundary\n(\n"
          + f"  farfield {{ type patch; faces ({' '.join(far)}); }}\n"
          + f"  front {{ type patch; faces ({' '.join(front)}); }}\n"
          + f"  back {{ type patch; faces ({' '.join(back)}); }}\n);\n")


def write_case(case, p):
    """system/, constant/ and 0/ of one point p (a dict: section, level, wall, alpha, solver, background)."""
    pts = polygon(p["section"])
    lev = LEVELS[p["level"]]
    bg = p["background"] * CHORD
    shift = round(-math.log2(p["background"]))  # levels on this background = the 3D case's minus shift
    rel = {k: (tuple(x - shift for x in v) if isinstance(v, tuple) else v - shift) for k, v in lev.items()}
    if min(rel["wake"], rel["surface"][0]) < 0:
        raise InputError(f"--background {p['background']:g}: finer than the wake box's cells")
    a = math.radians(p["alpha"])
    flow, lift = (math.cos(a), math.sin(a), 0.0), (-math.sin(a), math.cos(a), 0.0)
    xs, ys = [q[0] for q in pts], [q[1] for q in pts]
    lo, hi = (min(xs), min(ys)), (max(xs), max(ys))
    ext_lo = (lo[0] - UPSTREAM * CHORD, lo[1] - LATERAL * CHORD)
    ext_hi = (hi[0] + DOWNSTREAM * CHORD, hi[1] + LATERAL * CHORD)
    n = [max(1, math.ceil((ext_hi[i] - ext_lo[i]) / bg)) for i in range(2)]
    mid = [(ext_hi[i] + ext_lo[i]) / 2 for i in range(2)]
    bmin = [mid[i] - n[i] * bg / 2 for i in range(2)] + [0.0]
    bmax = [mid[i] + n[i] * bg / 2 for i in range(2)] + [bg]
    h_wall = CHORD / 2 ** lev["surface"][1]
    os.makedirs(os.path.join(case, "constant", "triSurface"), exist_ok=True)
    write_stl(os.path.join(case, "constant", "triSurface", "wing.stl"), pts, -bg, 2 * bg)

    write_block_mesh(case, bmin, bmax, n, bg, p.get("farfield", 0.0))
    wdict(case, "system/surfaceFeatureExtractDict",
          "wing.stl\n{\n  extractionMethod extractFromSurface;\n"
          "  extractFromSurfaceCoeffs { includedAngle 150; }\n"
          "  subsetFeatures { nonManifoldEdges no; openEdges no; }\n  writeObj no;\n}\n")
    c = CHORD
    near_lo, near_hi = (lo[0] - 0.5 * c, lo[1] - 0.5 * c, -10), (hi[0] + 1.5 * c, hi[1] + 0.5 * c, 10)
    wake_dy = 7 * c * math.tan(a)
    wake_lo = (lo[0] - c, lo[1] - c + min(0.0, wake_dy), -10)
    wake_hi = (hi[0] + 7 * c, hi[1] + c + max(0.0, wake_dy), 10)
    inside = (lo[0] - 2.0 * c + 0.1137 * bg, 0.5 * (lo[1] + hi[1]) + 0.1791 * bg, 0.4133 * bg)
    layers = p["wall"] in LAYER_FIRST
    first = LAYER_FIRST.get(p["wall"], LAYER_FIRST["layers"])
    nlay = layer_count(h_wall, first) if layers else 0
    wdict(case, "system/snappyHexMeshDict", f"""\
// The 3D case's controls (cases/coupled/ramair_fluid.py) on a background of {p['background']:g} chord: every
// level {shift} below the 3D case's ({p['level']}: surface {lev['surface']}, features {lev['features']}, near {lev['near']}, wake {lev['wake']}).
castellatedMesh true;
snap true;
addLayers {'true' if layers else 'false'};
geometry
{{
  wing.stl {{ type triSurfaceMesh; name wing; }}
  near {{ type searchableBox; min {v3(near_lo)}; max {v3(near_hi)}; }}
  wake {{ type searchableBox; min {v3(wake_lo)}; max {v3(wake_hi)}; }}
}}
castellatedMeshControls
{{
  maxLocalCells 4000000; maxGlobalCells 8000000; minRefinementCells 10; maxLoadUnbalance 0.10;
  nCellsBetweenLevels 3;
  features ( {{ file "wing.eMesh"; level {rel['features']}; }} );
  refinementSurfaces {{ wing {{ level ({rel['surface'][0]} {rel['surface'][1]}); patchInfo {{ type wall; }} }} }}
  resolveFeatureAngle 30;
  refinementRegions
  {{
    near {{ mode inside; levels ((1e15 {rel['near']})); }}
    wake {{ mode inside; levels ((1e15 {rel['wake']})); }}
  }}
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
  // {nlay} layers, the first {first:g} m thick, expansion {LAYER_EXPANSION:g} (--wall {p['wall']})
  relativeSizes false; layers {{ wing {{ nSurfaceLayers {nlay}; }} }}
  firstLayerThickness {first:.9g}; expansionRatio {LAYER_EXPANSION:.9g}; minThickness {0.5 * first:.9g};
  nGrow 0; featureAngle 130; slipFeatureAngle 30; nRelaxIter 5; nSmoothSurfaceNormals 1; nSmoothNormals 3;
  nSmoothThickness 10; maxFaceThicknessRatio 0.5; maxThicknessToMedialRatio 0.3; minMedialAxisAngle 90;
  nBufferCellsNoExtrude 0; nLayerIter 50;
}}
// --wall resolved only: the layer cells (4e-5 m against 0.008 m and more along the wall) fail the 3D case's
// determinant and tet-quality checks, which are relaxed for that variant alone.
meshQualityControls
{{
  maxNonOrtho 65; maxBoundarySkewness 4; maxInternalSkewness 4; maxConcave 80; minVol 1e-13;
  minTetQuality {'-1e30' if p['wall'] == 'resolved' else '1e-15'}; minArea -1; minTwist 0.02; minDeterminant {'1e-6' if p['wall'] == 'resolved' else '0.001'}; minFaceWeight 0.05; minVolRatio 0.01;
  minTriangleTwist -1; nSmoothScale 4; errorReduction 0.75;
  relaxed {{ maxNonOrtho 75; }}
}}
mergeTolerance 1e-6;
""")
    wdict(case, "system/extrudeMeshDict", f"""\
// The slab's front face (z = 0) extruded by one cell of {THICKNESS:g} m: the 2D mesh (front and back become empty).
constructFrom patch;
sourceCase ".";
sourcePatches (front);
exposedPatchName back;
flipNormals false;
extrudeModel plane;
nLayers 1;
expansionRatio 1.0;
planeCoeffs {{ thickness {THICKNESS:.9g}; }}
linearNormalCoeffs {{ thickness {THICKNESS:.9g}; }}
mergeFaces false;
mergeTol 0;
""")
    wdict(case, "constant/transportProperties",
          f"transportModel Newtonian;\nnu {NU:.9g};   // Re = {SPEED * CHORD / NU:.4g}\n")
    wdict(case, "constant/turbulenceProperties",
          "simulationType RAS;\nRAS { RASModel kOmegaSST; turbulence on; printCoeffs on; }\n")
    pimple = p["solver"] == "pimple"
    wdict(case, "system/fvSchemes", f"""\
ddtSchemes {{ default {'Euler' if pimple else 'steadyState'}; }}
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
    solvers = """\
solvers
{
  p { solver GAMG; smoother GaussSeidel; tolerance 1e-7; relTol 0.05; }
  pFinal { $p; relTol 0; }
  "(U|k|omega)" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-9; relTol 0.1; }
  "(U|k|omega)Final" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-9; relTol 0; }
}
"""
    if pimple:
        algo = ("// The 3D case's pseudo-transient PIMPLE (cases/coupled/ramair_fluid.py)\n"
                "PIMPLE { momentumPredictor yes; nOuterCorrectors 3; nCorrectors 1; nNonOrthogonalCorrectors 1; }\n"
                "relaxationFactors { fields { p 0.5; } equations { U 0.8; k 0.8; omega 0.8; } }\n")
    else:
        algo = ("SIMPLE\n{\n  nNonOrthogonalCorrectors 1; consistent yes;\n"
                "  residualControl { p 1e-6; U 1e-6; \"(k|omega)\" 1e-6; }\n}\n"
                "relaxationFactors { equations { U 0.7; k 0.7; omega 0.7; } }\n")
    wdict(case, "system/fvSolution", solvers + algo)
    dt = COURANT * h_wall / SPEED
    if pimple:
        steps = p["steps"]
        timing = (f"// deltaT = Courant {COURANT:g} * finest wing cell {h_wall:.6g} m / {SPEED:g} m/s, {steps} steps\n"
                  f"startFrom startTime; startTime 0; stopAt endTime; endTime {dt * steps:.9g}; deltaT {dt:.9g};\n"
                  f"writeControl timeStep; writeInterval {steps};\n")
    else:
        iters = p["iterations"]
        timing = (f"startFrom startTime; startTime 0; stopAt endTime; endTime {iters}; deltaT 1;\n"
                  f"writeControl timeStep; writeInterval {iters};\n")
    cofr = (0.25 * c, 0.0, 0.5 * THICKNESS)
    wdict(case, "system/controlDict", f"""\
application {'pimpleFoam' if pimple else 'simpleFoam'};
{timing}purgeWrite 0; writeFormat ascii; writePrecision 10; writeCompression off; timeFormat general;
timePrecision 10; runTimeModifiable false;
functions
{{
  // Lift normal to and drag along the free stream; Aref = chord x span of the one-cell mesh; moments about
  // the quarter chord, positive nose up (pitch axis -z: x downstream, y up).
  forceCoeffs
  {{
    type forceCoeffs; libs ("libforces.so"); writeControl timeStep; writeInterval 1; log false;
    patches (wing); rho rhoInf; rhoInf {RHO:.9g};
    liftDir {v3(lift)}; dragDir {v3(flow)}; pitchAxis (0 0 -1);
    CofR {v3(cofr)}; magUInf {SPEED:.9g}; lRef {c:.9g}; Aref {c * THICKNESS:.9g};
  }}
  forces
  {{
    type forces; libs ("libforces.so"); writeControl timeStep; writeInterval 1; log false;
    patches (wing); rho rhoInf; rhoInf {RHO:.9g}; CofR {v3(cofr)};
  }}
  yPlus {{ type yPlus; libs ("libfieldFunctionObjects.so"); writeControl writeTime; log false; }}
  wallSurface
  {{
    type surfaces; libs ("libsampling.so"); writeControl writeTime; surfaceFormat raw;
    fields (p yPlus); interpolationScheme cell;
    surfaces ( wing {{ type patch; patches (wing); interpolate false; }} );
  }}
}}
""")
    k = 1.5 * (INTENSITY * SPEED) ** 2
    om = k / (VISCOSITY_RATIO * NU)
    u = v3([SPEED * x for x in flow])
    meta = {"point": p, "h_wall": h_wall, "deltaT": dt, "k_inf": k, "omega_inf": om, "layers": nlay,
            "background_cells": n, "levels_on_background": rel, "shift": shift, "Aref": c * THICKNESS,
            "bounds": [bmin, bmax]}
    with open(os.path.join(case, "point.json"), "w") as f:
        json.dump(meta, f, indent=1)
    return meta


def write_fields(case, meta):
    k, om = meta["k_inf"], meta["omega_inf"]
    a = math.radians(meta["point"]["alpha"])
    u = v3([SPEED * math.cos(a), SPEED * math.sin(a), 0.0])
    emp = "  \"(front|back)\" { type empty; }\n"
    fields = {
        "U": ("volVectorField", "[0 1 -1 0 0 0 0]", f"uniform {u}",
              f"  farfield {{ type freestreamVelocity; freestreamValue uniform {u}; value uniform {u}; }}\n"
              "  wing { type noSlip; }\n"),
        "p": ("volScalarField", "[0 2 -2 0 0 0 0]", "uniform 0",
              "  farfield { type freestreamPressure; freestreamValue uniform 0; value uniform 0; }\n"
              "  wing { type zeroGradient; }\n"),
        "k": ("volScalarField", "[0 2 -2 0 0 0 0]", f"uniform {k:.9g}",
              f"  farfield {{ type inletOutlet; inletValue uniform {k:.9g}; value uniform {k:.9g}; }}\n"
              f"  wing {{ type kqRWallFunction; value uniform {k:.9g}; }}\n"),
        "omega": ("volScalarField", "[0 0 -1 0 0 0 0]", f"uniform {om:.9g}",
                  f"  farfield {{ type inletOutlet; inletValue uniform {om:.9g}; value uniform {om:.9g}; }}\n"
                  f"  wing {{ type omegaWallFunction; value uniform {om:.9g}; }}\n"),
        "nut": ("volScalarField", "[0 2 -1 0 0 0 0]", "uniform 0",
                "  farfield { type calculated; value uniform 0; }\n"
                "  wing { type nutUSpaldingWallFunction; value uniform 0; }\n"),
    }
    for name, (cls, dims, internal, bcs) in fields.items():
        wdict(case, f"0/{name}", f"dimensions {dims};\ninternalField {internal};\nboundaryField\n{{\n{bcs}{emp}}}\n",
              cls=cls)


def set_empty(case):
    """constant/polyMesh/boundary: front and back become `empty` (extrudeMesh leaves them `patch`)."""
    path = os.path.join(case, "constant", "polyMesh", "boundary")
    with open(path) as f:
        text = f.read()
    found = 0
    for name in ("front", "back"):
        pat = re.compile(r"(\n\s*" + name + r"\s*\n\s*\{[^}]*?\btype\s+)(\w+)(\s*;)")
        text, k = pat.subn(r"\1empty\3", text)
        found += k
        text = re.sub(r"(\n\s*" + name + r"\s*\n\s*\{[^}]*?)\n\s*inGroups[^;]*;", r"\1", text)
    if found != 2:
        raise RuntimeError(f"{path}: patches front and back not both found")
    with open(path, "w") as f:
        f.write(text)


# ---------------------------------------------------------------------------------------------------------
# Running


def run(case, args, log):
    """One OpenFOAM utility, niced, its output to case/log.<name>; an argument list, never a shell string."""
    t0 = time.time()
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")  # Debian's OpenFOAM, as case-functions.sh
    with open(os.path.join(case, log), "w") as f:
        r = subprocess.run(["nice", "-n", "5"] + args, cwd=case, stdout=f, stderr=subprocess.STDOUT, env=env)
    if r.returncode != 0:
        raise RuntimeError(f"{args[0]} failed (exit {r.returncode}): see {os.path.join(case, log)}")
    return time.time() - t0


def read_table(path):
    header, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                w = line[1:].split()
                if w and w[0] == "Time":
                    header = w
                continue
            w = line.split()
            if w:
                try:
                    rows.append([float(x) for x in w])
                except ValueError:
                    pass
    return header, rows


def last_time_dir(case):
    best = None
    for name in os.listdir(case):
        try:
            t = float(name)
        except ValueError:
            continue
        if t > 0 and (best is None or t > best[0]):
            best = (t, name)
    return best[1] if best else None


def read_raw(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            out.append([float(x) for x in line.split()])
    return out


def residuals(logpath):
    """Last initial residual of each solved field in the solver's log, and the iteration count."""
    res, iters, converged = {}, 0, False
    pat = re.compile(r"Solving for (\w+), Initial residual = ([0-9.eE+-]+)")
    with open(logpath) as f:
        for line in f:
            m = pat.search(line)
            if m:
                res[m.group(1)] = float(m.group(2))
            elif line.startswith("Time = "):
                iters += 1
            elif "solution converged in" in line:
                converged = True
    return res, iters, converged


def cells_of(logpath):
    with open(logpath) as f:
        for line in f:
            m = re.match(r"\s*cells:\s+(\d+)", line)
            if m:
                return int(m.group(1))
    return None


def point_id(p):
    a = f"{p['alpha']:+g}".replace("+", "p").replace("-", "m").replace(".", "d")
    bgs = "" if p["background"] == 0.25 else f"-bg{p['background']:g}".replace(".", "d")
    if p.get("farfield", 0.0) > 0:
        bgs += f"-ff{p['farfield']:g}".replace(".", "d")
    return f"{p['section']}-{p['wall']}-{p['level']}-{p['solver']}-a{a}{bgs}"


def run_point(p, workdir):
    case = os.path.join(workdir, point_id(p))
    if os.path.exists(case):
        shutil.rmtree(case)
    os.makedirs(case)
    t_all = time.time()
    meta = write_case(case, p)
    tm = 0.0
    tm += run(case, ["blockMesh"], "log.blockMesh")
    tm += run(case, ["surfaceFeatureExtract"], "log.surfaceFeatureExtract")
    tm += run(case, ["snappyHexMesh", "-overwrite"], "log.snappyHexMesh")
    tm += run(case, ["extrudeMesh"], "log.extrudeMesh")
    for name in ("cellLevel", "pointLevel", "level0Edge", "surfaceIndex", "refinementHistory"):
        path = os.path.join(case, "constant", "polyMesh", name)
        if os.path.exists(path):
            os.remove(path)
    set_empty(case)
    tm += run(case, ["checkMesh"], "log.checkMesh")
    write_fields(case, meta)
    solver = "pimpleFoam" if p["solver"] == "pimple" else "simpleFoam"
    ts = run(case, [solver], f"log.{solver}")
    return case, collect(case, p, meta, tm, ts, time.time() - t_all)


def collect(case, p, meta, t_mesh, t_solve, t_all):
    solver = "pimpleFoam" if p["solver"] == "pimple" else "simpleFoam"
    header, rows = read_table(os.path.join(case, "postProcessing", "forceCoeffs", "0", "coefficient.dat"))
    if not rows or not header:
        raise RuntimeError(f"{case}: no force coefficients")
    col = {k: header.index(k) for k in ("Cd", "Cl", "CmPitch")}
    cl = [r[col["Cl"]] for r in rows]
    cd = [r[col["Cd"]] for r in rows]
    cm = [r[col["CmPitch"]] for r in rows]
    n = len(rows)
    tail = max(1, n // 10)

    def spread(v):
        seg = v[-tail:]
        return (max(seg) - min(seg)) / max(abs(sum(seg) / len(seg)), 1e-9)

    res, iters, conv = residuals(os.path.join(case, f"log.{solver}"))
    t = last_time_dir(case)
    yp, cp = None, None
    if t:
        sdir = os.path.join(case, "postProcessing", "wallSurface", t)
        praw, yraw = os.path.join(sdir, "p_wing.raw"), os.path.join(sdir, "yPlus_wing.raw")
        if os.path.exists(praw):
            q = 0.5 * SPEED ** 2
            cp = [[round(r[0], 5), round(r[1], 5), round(r[3] / q, 5)] for r in read_raw(praw)]
        if os.path.exists(yraw):
            yp = [round(r[3], 3) for r in read_raw(yraw)]
    out = {
        "id": point_id(p), "section": p["section"], "wall": p["wall"], "level": p["level"],
        "surface_levels": list(LEVELS[p["level"]]["surface"]), "background_chords": p["background"],
        "farfield_chords": p.get("farfield", 0.0),
        "alpha": p["alpha"], "solver": p["solver"],
        "CL": cl[-1], "CD": cd[-1], "Cm": cm[-1],
        "CL_spread_last_tenth": spread(cl), "CD_spread_last_tenth": spread(cd),
        "iterations": iters, "residuals_final": res, "residual_control_met": conv,
        "cells": cells_of(os.path.join(case, "log.checkMesh")), "layers": meta["layers"],
        "h_wall": meta["h_wall"], "wall_s_mesh": round(t_mesh, 2), "wall_s_solver": round(t_solve, 2),
        "wall_s": round(t_all, 2),
    }
    if p["solver"] == "pimple":
        out["deltaT"] = meta["deltaT"]
        out["history"] = {"CL": cl, "CD": cd}
        if n >= 100:
            out["CL_step100"], out["CD_step100"] = cl[99], cd[99]
    if yp:
        out["yplus"] = {"min": min(yp), "mean": sum(yp) / len(yp), "max": max(yp), "faces": yp}
    if cp:
        out["cp"] = cp
    return out


class Store:
    """OUT/section_runs.json: every finished point appended at once (a cut-off run keeps what it did)."""

    def __init__(self, out):
        self.path = os.path.join(out, "section_runs.json")
        self.lock = threading.Lock()

    def add(self, rec):
        with self.lock:
            data = {"points": []}
            if os.path.exists(self.path):
                with open(self.path) as f:
                    data = json.load(f)
            data["points"] = [q for q in data["points"] if q["id"] != rec["id"]] + [rec]
            tmp = self.path + ".tmp"
            with open(tmp, "w") as f:
                json.dump(data, f)
            os.replace(tmp, self.path)


def parse_alpha(text):
    out = []
    for w in text.split(","):
        w = w.strip()
        if not w:
            continue
        try:
            a = float(w)
        except ValueError:
            raise InputError(f"--alpha: '{w}' is not a number")
        if not (math.isfinite(a) and -20 <= a <= 25):
            raise InputError(f"--alpha: {w} is outside [-20, 25] degrees")
        out.append(a)
    if not out:
        raise InputError("--alpha: no angle given")
    return out


def parse_words(text, valid, what):
    out = [w.strip() for w in text.split(",") if w.strip()]
    for w in out:
        if w not in valid:
            raise InputError(f"--{what}: '{w}' is not one of {', '.join(valid)}")
    if not out:
        raise InputError(f"--{what}: nothing given")
    return out


def cmd_run(a):
    if a.quick:
        # CI size (test_section.py): LS(1)-0417 at 4 deg on the wall-function-layer mesh, far field at 100 c
        sections, alphas, levels, walls, solver = ["ls0417"], [4.0], [QUICK_LEVEL], ["layers"], "simple"
        a.farfield = 100.0
    else:
        sections = parse_words(a.section, list(SECTIONS), "section")
        alphas = parse_alpha(a.alpha)
        levels = parse_words(a.level, list(LEVELS), "level")
        walls = parse_words(a.wall, WALLS, "wall")
        solver = a.solver
    if a.background not in (1.0, 0.5, 0.25, 0.125):
        raise InputError("--background must be 1, 0.5, 0.25 or 0.125 chords")
    if not (a.farfield == 0 or LATERAL + 1 <= a.farfield <= 1000):
        raise InputError(f"--farfield must be 0 (the 3D case's box) or {LATERAL + 1:g}..1000 chords, not {a.farfield:g}")
    if not 1 <= a.jobs <= 8:
        raise InputError("--jobs must be 1..8")
    if a.iterations is not None and not 50 <= a.iterations <= 100000:
        raise InputError("--iterations must be 50..100000")
    if a.steps is not None and not 10 <= a.steps <= 100000:
        raise InputError("--steps must be 10..100000")
    for tool in ("blockMesh", "snappyHexMesh", "extrudeMesh", "simpleFoam", "pimpleFoam", "nice"):
        if shutil.which(tool) is None:
            raise InputError(f"{tool} not found on PATH (OpenFOAM v1912: scripts/install-deps.sh)")
    os.makedirs(a.out, exist_ok=True)
    work = os.path.join(a.out, "cases")
    os.makedirs(work, exist_ok=True)
    store = Store(a.out)
    points = []
    for s in sections:
        for w in walls:
            for lv in levels:
                for al in alphas:
                    points.append({"section": s, "wall": w, "level": lv, "alpha": al, "solver": solver,
                                   "background": a.background, "farfield": a.farfield,
                                   "iterations": a.iterations or MAX_ITER[lv], "steps": a.steps or PIMPLE_STEPS})
    failures = []

    def one(p):
        t0 = time.time()
        try:
            case, rec = run_point(p, work)
        except (RuntimeError, OSError, ValueError) as e:
            failures.append((point_id(p), str(e)))
            print(f"FAILED {point_id(p)}: {e}", flush=True)
            return
        store.add(rec)
        yp = rec.get("yplus", {})
        print(f"{rec['id']}: CL {rec['CL']:.4f} CD {rec['CD']:.5f} Cm {rec['Cm']:.4f} | cells {rec['cells']} "
              f"iters {rec['iterations']} | y+ {yp.get('min', 0):.1f}-{yp.get('max', 0):.1f} "
              f"(mean {yp.get('mean', 0):.1f}) | {time.time() - t0:.0f} s", flush=True)

    if a.jobs == 1:
        for p in points:
            one(p)
    else:
        from concurrent.futures import ThreadPoolExecutor
        with ThreadPoolExecutor(a.jobs) as ex:
            list(ex.map(one, points))
    print(f"results: {store.path}")
    return 1 if failures else 0


# ---------------------------------------------------------------------------------------------------------
# Report: figures and docs/data/section_polar.json


def read_reference():
    path = os.path.join(HERE, "ghoreyshi2016_ls0417.csv")
    cla, cdl = [], []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            s = line.strip()
            if not s or s.startswith("#"):
                continue
            w = s.split(",")
            if len(w) != 4:
                raise InputError(f"{path}:{n}: expected 4 comma-separated fields")
            if w[0] == "cl_alpha":
                cla.append((float(w[1]), float(w[2])))
            elif w[0] == "cd_cl":
                cdl.append((float(w[2]), float(w[3])))
            else:
                raise InputError(f"{path}:{n}: unknown kind '{w[0]}'")
    return {"source": "Ghoreyshi et al. 2016, J. Aircraft (DOI 10.2514/1.C033763), Fig. 10, wind tunnel, "
                      "Re 1.9e6, M 0.15; digitised by alexmm10/Paratech_ramair_design",
            "Re": 1.9e6, "cl_alpha": cla, "cd_cl": cdl}


# NACA 4415 references. Thin-aerofoil theory (computed here from the mean line): zero-lift angle and 2 pi.
def thin_aerofoil_alpha0(m, p, n=20000):
    """alpha_L0 = -(1/pi) int_0^pi dyc/dx (cos th - 1) dth for the NACA 4-digit mean line [deg]."""
    s = 0.0
    for i in range(n):
        th = (i + 0.5) * math.pi / n
        x = 0.5 * (1 - math.cos(th))
        dy = 2 * m / p ** 2 * (p - x) if x < p else 2 * m / (1 - p) ** 2 * (p - x)
        s += dy * (math.cos(th) - 1) * math.pi / n
    return math.degrees(-s / math.pi)


def polar_metrics(pts, linear=(-4.0, 6.0)):
    """Lift slope (least squares over the linear range), zero-lift angle, CD at CL 0.55, CL_max and its angle."""
    pts = sorted(pts, key=lambda q: q[0])
    lin = [q for q in pts if linear[0] - 1e-9 <= q[0] <= linear[1] + 1e-9]
    out = {"linear_range_deg": list(linear), "n_linear": len(lin)}
    if len(lin) >= 2:
        xs, ys = [q[0] for q in lin], [q[1] for q in lin]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        sxx = sum((x - mx) ** 2 for x in xs)
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
        out["slope_per_deg"] = slope
        out["slope_per_rad"] = math.degrees(slope)
        out["alpha0_deg"] = mx - my / slope
    if pts:
        i = max(range(len(pts)), key=lambda j: pts[j][1])
        out["CL_max"], out["alpha_CL_max"] = pts[i][1], pts[i][0]
        out["CL_max_is_last_angle"] = i == len(pts) - 1
        # CD at CL 0.55 on the rising branch (CL increasing with alpha up to CL_max)
        rising = pts[: i + 1]
        for a, b in zip(rising, rising[1:]):
            if len(a) > 2 and a[1] <= 0.55 <= b[1] and b[1] > a[1]:
                w = (0.55 - a[1]) / (b[1] - a[1])
                out["CD_at_CL055"] = a[2] + w * (b[2] - a[2])
    return out


def order_of(f1, f2, f3, r=2.0):
    """Observed order from fine f1, medium f2, coarse f3 (refinement ratio r) and the Richardson value."""
    e21, e32 = f2 - f1, f3 - f2
    out = {"fine": f1, "medium": f2, "coarse": f3}
    if e21 == 0 or e32 == 0 or e32 / e21 <= 0:
        out["order"] = None
        out["note"] = "oscillatory or no change: no order"
        return out
    pr = math.log(e32 / e21) / math.log(r)
    out["order"] = pr
    if 0.5 <= pr <= 4:
        ext = f1 + (f1 - f2) / (r ** pr - 1)
        out["richardson"] = ext
        out["gci_fine"] = 1.25 * abs((f1 - f2) / f1) / (r ** pr - 1) if f1 else None
    else:
        out["note"] = "order outside 0.5-4: no extrapolation"
    return out


MAIN_FARFIELD = 100.0  # the far field of the study's main points [chords]


def farfield_of(q):
    if "farfield_chords" in q:
        return q["farfield_chords"]
    m = re.search(r"-ff(\d+(?:d\d+)?)", q["id"])
    return float(m.group(1).replace("d", ".")) if m else 0.0


def twin_of(q, pool):
    return next((t for t in pool if t["section"] == q["section"] and t["wall"] == q["wall"]
                 and t["level"] == q["level"] and t["alpha"] == q["alpha"]), None)


def cmd_report(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts = []
    for d in a.runs:
        path = os.path.join(d, "section_runs.json")
        if not os.path.exists(path):
            raise InputError(f"{path}: no results")
        with open(path) as f:
            pts += json.load(f)["points"]
    ref = read_reference()
    steady = [q for q in pts if q["solver"] == "simple" and q["background_chords"] == 0.25
              and farfield_of(q) == MAIN_FARFIELD]
    a0_thin = thin_aerofoil_alpha0(0.04, 0.4)
    out = {"what": "2D sections at Re 1e6 meshed and solved as the 3D ram-air case (docs/AERODYNAMICS.md)",
           "flow": {"speed": SPEED, "nu": NU, "Re": SPEED * CHORD / NU, "model": "kOmegaSST",
                    "wall": "nutUSpaldingWallFunction, omegaWallFunction, kqRWallFunction",
                    "turbulence_intensity": INTENSITY, "viscosity_ratio": VISCOSITY_RATIO,
                    "Aref": CHORD * THICKNESS, "moments": "quarter chord, nose up positive",
                    "farfield_chords": MAIN_FARFIELD, "background_chords": 0.25},
           "levels": LEVELS, "layers": {"first_thickness": LAYER_FIRST, "expansion": LAYER_EXPANSION,
                                        "yplus_band": YPLUS_BAND},
           "reference": {"ls0417": ref,
                         "naca4415": {"alpha0_thin_aerofoil_deg": a0_thin, "slope_theory_per_rad": 2 * math.pi,
                                      "source": "thin-aerofoil theory from the NACA 4415 mean line"}},
           "sections": {}, "metrics": {}, "convergence": {}, "pimple": [], "farfield_check": [],
           "background_check": []}
    out["metrics"]["ls0417/data"] = polar_metrics([(x, y) for x, y in ref["cl_alpha"]])
    cdl = sorted(ref["cd_cl"])
    for p0, p1 in zip(cdl, cdl[1:]):
        if p0[0] <= 0.55 <= p1[0]:
            out["metrics"]["ls0417/data"]["CD_at_CL055"] = p0[1] + (0.55 - p0[0]) / (p1[0] - p0[0]) * (p1[1] - p0[1])
    out["metrics"]["naca4415/thin-aerofoil"] = {"slope_per_rad": 2 * math.pi,
                                               "slope_per_deg": math.radians(2 * math.pi), "alpha0_deg": a0_thin}

    def slim(q):
        keep = {k: v for k, v in q.items() if k not in ("cp", "history")}
        if "yplus" in keep:
            keep["yplus"] = {k: v for k, v in keep["yplus"].items() if k != "faces"}
        return keep

    for q in steady:
        out["sections"].setdefault(q["section"], {}).setdefault(q["wall"], {}).setdefault(q["level"], []).append(slim(q))
    for s, walls in out["sections"].items():
        for w, levels in walls.items():
            for lv, lst in levels.items():
                lst.sort(key=lambda q: q["alpha"])
                if len(lst) >= 3:
                    out["metrics"][f"{s}/{w}/{lv}"] = polar_metrics([(q["alpha"], q["CL"], q["CD"]) for q in lst])
            if all(lv in levels for lv in ("coarse", "medium", "fine")):
                common = set(q["alpha"] for q in levels["fine"]) & set(q["alpha"] for q in levels["medium"]) \
                    & set(q["alpha"] for q in levels["coarse"])
                for al in sorted(common):
                    f = {lv: next(q for q in levels[lv] if q["alpha"] == al) for lv in ("coarse", "medium", "fine")}
                    c = {k: order_of(f["fine"][k], f["medium"][k], f["coarse"][k]) for k in ("CL", "CD", "Cm")}
                    if w == "resolved" and f["coarse"].get("yplus", {}).get("mean", 0) > 5:
                        # snappyHexMesh added no layers on the coarse level: not the same family of meshes
                        for k in ("CL", "CD", "Cm"):
                            c[k].update(order=None, richardson=None, gci_fine=None,
                                        note="the coarse level got no layers (y+ >> 1): no order")
                    c["yplus_mean"] = {lv: f[lv].get("yplus", {}).get("mean") for lv in f}
                    c["cells"] = {lv: f[lv]["cells"] for lv in f}
                    c["wall_s"] = {lv: f[lv]["wall_s"] for lv in f}
                    out["convergence"][f"{s}/{w}/alpha{al:g}"] = c
    for q in pts:
        if q["solver"] == "pimple":
            pool = [t for t in steady if farfield_of(t) == farfield_of(q)]
            tw = twin_of(q, pool)
            hist = q.get("history", {})
            at = {n: (hist["CL"][n - 1], hist["CD"][n - 1]) for n in (100, 300) if len(hist.get("CL", [])) >= n}
            out["pimple"].append({"id": q["id"], "CL": q["CL"], "CD": q["CD"], "Cm": q["Cm"],
                                  "CL_step100": q.get("CL_step100"), "CD_step100": q.get("CD_step100"),
                                  "CL_step300": at.get(300, (None, None))[0], "CD_step300": at.get(300, (None, None))[1],
                                  "CL_spread_last_tenth": q["CL_spread_last_tenth"],
                                  "steps": q["iterations"], "deltaT": q.get("deltaT"), "wall_s": q["wall_s"],
                                  "simple_CL": tw["CL"] if tw else None, "simple_CD": tw["CD"] if tw else None,
                                  "simple_wall_s": tw["wall_s"] if tw else None})
        elif q["background_chords"] == 1.0 or farfield_of(q) != MAIN_FARFIELD:
            tw = twin_of(q, steady)
            rec = {"id": q["id"], "farfield_chords": farfield_of(q), "background_chords": q["background_chords"],
                   "CL": q["CL"], "CD": q["CD"], "Cm": q["Cm"], "cells": q["cells"], "wall_s": q["wall_s"],
                   "yplus": {k: v for k, v in q.get("yplus", {}).items() if k != "faces"},
                   "main_CL": tw["CL"] if tw else None, "main_CD": tw["CD"] if tw else None}
            if q["background_chords"] == 1.0:
                same = next((t for t in pts if t["solver"] == "simple" and t["background_chords"] == 0.25
                             and farfield_of(t) == farfield_of(q) and t["section"] == q["section"]
                             and t["wall"] == q["wall"] and t["level"] == q["level"] and t["alpha"] == q["alpha"]), None)
                rec["quarter_chord_background_CL"] = same["CL"] if same else None
                rec["quarter_chord_background_CD"] = same["CD"] if same else None
                out["background_check"].append(rec)
            else:
                out["farfield_check"].append(rec)
    os.makedirs(os.path.dirname(os.path.abspath(a.json)), exist_ok=True)
    with open(a.json, "w") as f:
        json.dump(out, f, indent=1)
    print(f"wrote {a.json}")
    print_tables(out)
    os.makedirs(a.img, exist_ok=True)
    plot_polar(plt, out, ref, os.path.join(a.img, "section_polar.png"))
    plot_convergence(plt, out, steady, os.path.join(a.img, "section_convergence.png"))
    plot_yplus(plt, steady, os.path.join(a.img, "section_yplus.png"))
    plot_cp(plt, steady, os.path.join(a.img, "section_cp.png"), a.cp_alpha)
    return 0


def fmt(v, spec):
    return "-" if v is None else format(v, spec)


def print_tables(out):
    """The tables of docs/AERODYNAMICS.md (markdown) on stdout."""
    print("\n| section, wall, level | slope [1/rad] | alpha0 [deg] | CD at CL 0.55 | CL_max (at deg) | points |")
    print("|---|---|---|---|---|---|")
    for key, m in out["metrics"].items():
        lst = None
        parts = key.split("/")
        if len(parts) == 3:
            lst = out["sections"][parts[0]][parts[1]][parts[2]]
        cl = f"{m['CL_max']:.3f} ({m['alpha_CL_max']:g})" if "CL_max" in m else "-"
        if m.get("CL_max_is_last_angle"):
            cl += " last angle"
        print(f"| {key} | {fmt(m.get('slope_per_rad'), '.2f')} | {fmt(m.get('alpha0_deg'), '.2f')} | "
              f"{fmt(m.get('CD_at_CL055'), '.4f')} | {cl} | {len(lst) if lst else '-'} |")
    print("\n| convergence | CL c/m/f | p | Richardson | CD c/m/f | p | Richardson | y+ mean c/m/f |")
    print("|---|---|---|---|---|---|---|---|")
    for key, c in out["convergence"].items():
        row = [key]
        for k in ("CL", "CD"):
            o = c[k]
            row += [f"{o['coarse']:.4f} / {o['medium']:.4f} / {o['fine']:.4f}", fmt(o.get("order"), ".2f"),
                    fmt(o.get("richardson"), ".4f")]
        row.append(" / ".join(fmt(c["yplus_mean"][lv], ".0f") for lv in ("coarse", "medium", "fine")))
        print("| " + " | ".join(row) + " |")
    print("\n| far field: the 3D case's box (8/16/8 c) | CL | CD | with the ring to 100 c: CL | CD | cells | s |")
    print("|---|---|---|---|---|---|---|")
    for r in out["farfield_check"]:
        print(f"| {r['id']} | {r['CL']:.4f} | {r['CD']:.5f} | {fmt(r['main_CL'], '.4f')} | {fmt(r['main_CD'], '.5f')} "
              f"| {r['cells']} | {r['wall_s']:.0f} |")
    print("\n| background: 1 chord (the 3D case's) | CL | CD | 1/4 chord, same box: CL | CD | cells | s |")
    print("|---|---|---|---|---|---|---|")
    for r in out["background_check"]:
        print(f"| {r['id']} | {r['CL']:.4f} | {r['CD']:.5f} | {fmt(r['quarter_chord_background_CL'], '.4f')} | "
              f"{fmt(r['quarter_chord_background_CD'], '.5f')} | {r['cells']} | {r['wall_s']:.0f} |")
    print("\n| pimple | steps | CL at 100 / 300 / end | CD at 100 / 300 / end | simpleFoam CL, CD | s (pimple / simple) |")
    print("|---|---|---|---|---|---|")
    for r in out["pimple"]:
        print(f"| {r['id']} | {r['steps']} | {fmt(r['CL_step100'], '.4f')} / {fmt(r['CL_step300'], '.4f')} / {r['CL']:.4f} | "
              f"{fmt(r['CD_step100'], '.5f')} / {fmt(r['CD_step300'], '.5f')} / {r['CD']:.5f} | "
              f"{fmt(r['simple_CL'], '.4f')}, {fmt(r['simple_CD'], '.5f')} | "
              f"{r['wall_s']:.0f} / {fmt(r['simple_wall_s'], '.0f')} |")
    print("\n| section, wall, level | alpha | CL | CD | Cm | y+ min/mean/max | cells | iterations (CL spread, last tenth) | s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for s, walls in out["sections"].items():
        for w, levels in walls.items():
            for lv, lst in levels.items():
                for q in lst:
                    y = q.get("yplus", {})
                    print(f"| {s} {w} {lv} | {q['alpha']:g} | {q['CL']:.4f} | {q['CD']:.5f} | {q['Cm']:.4f} | "
                          f"{fmt(y.get('min'), '.1f')}/{fmt(y.get('mean'), '.0f')}/{fmt(y.get('max'), '.0f')} | "
                          f"{q['cells']} | {q['iterations']}{'' if q['residual_control_met'] else '*'} "
                          f"({100 * q['CL_spread_last_tenth']:.2g} %) | {q['wall_s']:.0f} |")


STYLE = {("functions", "coarse"): ("tab:red", "o"), ("functions", "medium"): ("tab:orange", "s"),
         ("functions", "fine"): ("tab:brown", "^"), ("layers", "coarse"): ("tab:blue", "o"),
         ("layers", "medium"): ("tab:cyan", "s"), ("layers", "fine"): ("tab:purple", "^"),
         ("resolved", "coarse"): ("limegreen", "o"), ("resolved", "medium"): ("tab:olive", "s"),
         ("resolved", "fine"): ("tab:green", "^")}
WALL_WORDS = {"functions": "wall functions, no layers (3D case)", "layers": "wall-function layers (y+ 30-100)",
              "resolved": "resolved layers (y+ ~ 1)"}


def plot_polar(plt, out, ref, path):
    fig, ax = plt.subplots(2, 2, figsize=(13, 10))
    for row, s in enumerate(("ls0417", "naca4415")):
        a1, a2 = ax[row]
        data = out["sections"].get(s, {})
        for w in WALLS:
            for lv in ("coarse", "medium", "fine"):
                lst = data.get(w, {}).get(lv, [])
                if not lst:
                    continue
                col, mk = STYLE[(w, lv)]
                lab = f"{WALL_WORDS[w]}, {lv} {tuple(LEVELS[lv]['surface'])}"
                ls = "-" if len(lst) >= 3 else "none"  # the convergence runs' two angles: markers only
                a1.plot([q["alpha"] for q in lst], [q["CL"] for q in lst], marker=mk, ls=ls, color=col, label=lab, ms=4)
                a2.plot([q["CD"] for q in lst], [q["CL"] for q in lst], marker=mk, ls=ls, color=col, label=lab, ms=4)
        if s == "ls0417":
            a1.plot(*zip(*ref["cl_alpha"]), "k*", ms=9, label="wind tunnel, Ghoreyshi et al. 2016 (Re 1.9e6)")
            cd = sorted(ref["cd_cl"])
            a2.plot([c[1] for c in cd], [c[0] for c in cd], "k*", ms=9, label="wind tunnel, Ghoreyshi et al. 2016")
        else:
            a0 = out["reference"]["naca4415"]["alpha0_thin_aerofoil_deg"]
            al = [-6, 12]
            a1.plot(al, [2 * math.pi * math.radians(x - a0) for x in al], "k--",
                    label=f"thin-aerofoil theory: 2$\\pi$/rad, $\\alpha_0$ = {a0:.2f}°")
        a1.set_xlabel("α [deg]")
        a1.set_ylabel("CL")
        a1.set_title(f"{SECTIONS[s]['title']}, Re 1e6 (kOmegaSST): lift")
        a2.set_xlim(0, 0.08)
        a2.set_xlabel("CD (axis cut at 0.08: the stalled coarse points lie beyond)")
        a2.set_ylabel("CL")
        a2.set_title(f"{SECTIONS[s]['title']}: drag polar")
        for a_ in (a1, a2):
            a_.grid(alpha=0.3)
            a_.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")


def plot_convergence(plt, out, steady, path):
    keys = sorted(out["convergence"])
    if not keys:
        return
    fig, ax = plt.subplots(2, 2, figsize=(13, 9))
    for key in keys:
        s, w, al = key.split("/")
        row = 0 if s == "ls0417" else 1
        alpha = float(al[5:])
        lst = sorted([q for q in steady if q["section"] == s and q["wall"] == w and q["alpha"] == alpha],
                     key=lambda q: q["h_wall"])
        col = STYLE[(w, "fine")][0]
        for a_, k in zip(ax[row], ("CL", "CD")):
            h = [q["h_wall"] for q in lst]
            v = [q[k] for q in lst]
            o = out["convergence"][key][k]
            lab = f"{w}, α={alpha:g}°: p = " + (f"{o['order']:.2f}" if o.get("order") is not None else "none")
            a_.plot(h, v, "-o" if alpha == 4 else "--s", color=col, label=lab, ms=4)
            if o.get("richardson") is not None:
                a_.plot([0], [o["richardson"]], "x", color=col, ms=9)
    for row, s in enumerate(("ls0417", "naca4415")):
        for a_, k in zip(ax[row], ("CL", "CD")):
            a_.set_xlabel("wall cell h / c (levels 5, 6, 7); x at h = 0: Richardson value")
            a_.set_ylabel(k)
            a_.set_xlim(-0.002, 0.034)
            a_.grid(alpha=0.3)
            a_.legend(fontsize=7)
            a_.set_title(f"{SECTIONS[s]['title']}: {k} against the wall cell size")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")


def plot_yplus(plt, steady, path):
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5), sharey=True)
    for a_, w in zip(ax, WALLS):
        for lv in ("coarse", "medium", "fine"):
            lst = [q for q in steady if q["wall"] == w and q["level"] == lv and q["section"] == "ls0417"
                   and q["alpha"] == 4 and "yplus" in q]
            if not lst:
                continue
            col, _ = STYLE[(w, lv)]
            f = lst[0]["yplus"]["faces"]
            bins = [10 ** (x / 10) for x in range(-10, 36)]
            a_.hist(f, bins=bins, histtype="step", color=col, lw=1.5, weights=[100.0 / len(f)] * len(f),
                    label=f"{lv}: {min(f):.1f}-{max(f):.0f}, mean {sum(f) / len(f):.1f}")
        a_.set_xscale("log")
        if w != "resolved":
            a_.axvspan(30, 100, color="0.9", zorder=0, label="log-law band 30-100")
        else:
            a_.axvspan(0.1, 5, color="0.9", zorder=0, label="viscous sublayer y+ < 5")
        a_.set_xlabel("y+ at the wall faces (cell centre)")
        a_.set_title(f"LS(1)-0417, α = 4°: {WALL_WORDS[w]}", fontsize=9)
        a_.grid(alpha=0.3)
        a_.legend(fontsize=7)
    ax[0].set_ylabel("% of the wing's faces")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")


def plot_cp(plt, steady, path, alpha):
    fig, ax = plt.subplots(1, 2, figsize=(13, 5), sharey=True)
    for a_, s in zip(ax, ("ls0417", "naca4415")):
        for w, lv in (("functions", "coarse"), ("functions", "fine"), ("layers", "fine"), ("resolved", "fine")):
            q = next((q for q in steady if q["section"] == s and q["wall"] == w and q["level"] == lv
                      and q["alpha"] == alpha and "cp" in q), None)
            if not q:
                continue
            col, _ = STYLE[(w, lv)]
            pts = sorted(q["cp"], key=lambda r: r[0])
            up = [r for r in pts if r[1] >= camber_at(s, r[0])]
            lo = [r for r in pts if r[1] < camber_at(s, r[0])]
            lab = f"{WALL_WORDS[w]}, {lv}: CL {q['CL']:.3f}"
            a_.plot([r[0] for r in up], [r[2] for r in up], "-", color=col, lw=1.3, label=lab + " (upper —, lower --)")
            a_.plot([r[0] for r in lo], [r[2] for r in lo], "--", color=col, lw=1.3)
        a_.invert_yaxis()
        a_.set_xlabel("x / c")
        a_.set_title(f"{SECTIONS[s]['title']}, α = {alpha:g}°, Re 1e6: surface pressure")
        a_.grid(alpha=0.3)
        a_.legend(fontsize=7)
    ax[0].set_ylabel("Cp (axis reversed)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")


_CAMBER = {}


def camber_at(section, x):
    """Mid-line y of the section at x (mean of its upper and lower surface), for splitting Cp by side."""
    if section not in _CAMBER:
        pts = SECTIONS[section]["points"]()
        i = min(range(len(pts)), key=lambda j: pts[j][0])
        up = sorted(pts[: i + 1])
        lo = sorted(pts[i:])
        _CAMBER[section] = (up, lo)
    up, lo = _CAMBER[section]

    def interp(s, xx):
        xx = min(max(xx, s[0][0]), s[-1][0])
        for a, b in zip(s, s[1:]):
            if a[0] <= xx <= b[0]:
                return a[1] if b[0] == a[0] else a[1] + (xx - a[0]) / (b[0] - a[0]) * (b[1] - a[1])
        return s[-1][1]

    return 0.5 * (interp(up, x) + interp(lo, x))


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="run points (appended to OUT/section_runs.json)")
    r.add_argument("--section", default="ls0417", help="comma list of: " + ", ".join(SECTIONS))
    r.add_argument("--alpha", default="4", help="comma list of angles of attack [deg]")
    r.add_argument("--level", default="coarse", help="comma list of: coarse (4 5), medium (5 6), fine (6 7)")
    r.add_argument("--wall", default="functions", help="comma list of: functions (no layers), layers")
    r.add_argument("--solver", default="simple", choices=["simple", "pimple"])
    r.add_argument("--background", type=float, default=0.25, help="background cell [chords]: 1, 0.5, 0.25")
    r.add_argument("--farfield", type=float, default=0.0,
                   help="a graded ring of blocks takes the far field to this many chords (0: the 3D case's box)")
    r.add_argument("--iterations", type=int, default=None, help="simpleFoam iterations at most")
    r.add_argument("--steps", type=int, default=None, help="pimpleFoam steps")
    r.add_argument("--out", required=True)
    r.add_argument("--quick", action="store_true",
                   help="CI size: LS(1)-0417, 4 deg, wall-function layers, far field 100 chords (one point)")
    r.add_argument("--jobs", type=int, default=1, help="points run at once (each serial)")
    q = sub.add_parser("report", help="docs JSON and figures from run folders")
    q.add_argument("--runs", nargs="+", required=True)
    q.add_argument("--json", required=True)
    q.add_argument("--img", required=True)
    q.add_argument("--cp-alpha", type=float, default=4.0)
    a = ap.parse_args(argv[1:])
    try:
        return cmd_run(a) if a.cmd == "run" else cmd_report(a)
    except InputError as e:
        print(f"section_polar: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
