"""The ram-air case's inputs (part of ramair_fluid.py, the case generator): system/ and constant/
dictionaries from the validated settings and the wing's skin (blockMesh, surface features, snappyHexMesh,
schemes, solution, controlDict with forceCoeffs, decomposition, transport, turbulence, dynamic mesh), the
dictionaries of a new mesh during a run (remesh_below) and of wall_split's stages, and the coupled run's
structure scene. Every value written is a number formatted here or a word from a fixed list.
"""
import json
import math
import os
import re

from ramair_geometry import derived, read_stl, v3, wing_geometry
from ramair_mesh import _foam_list, check_mesh
from ramair_settings import (DIFFUSIVITY, RESOLUTIONS, InputError, brake_inputs, load_record, read_settings,
                             wall_factor)


HEADER = "FoamFile {{ version 2.0; format ascii; class {cls}; object {obj}; }}\n// Written by ramair_fluid.py from {src}: edit the settings, not this file.\n"


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
            raise InputError(f"{settings_path}: {'mirror_mesh' if mirror else 'half_domain'} yes needs a wing symmetric about y = 0; the skin "
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
    # along the flow: it drifts sideways with sideslip (the air from the right: the wake to the left, -y)
    wake_dz = 7 * c * math.tan(a)
    wake_dy = -7 * c * math.tan(math.radians(s["sideslip"]))
    wake_lo = [lo[0] - c, lo[1] - c + min(0.0, wake_dy), lo[2] - c + min(0.0, wake_dz)]
    wake_hi = [hi[0] + 7 * c, hi[1] + c + max(0.0, wake_dy), hi[2] + c + max(0.0, wake_dz)]
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
    // The projection this case was validated with (docs/AERODYNAMICS.md rungs 3-4): the L2 evaluation at
    // quadrature level 1. With the adapter's newer defaults (pointwise evaluation, level auto) the anchored
    // canopy's lift does not settle within 5 % and both brakes held leave a yaw (docs/PROJECTION.md).
    evaluation l2; quadratureLevel 1;
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
    slip = f", sideslip {s['sideslip']:g} deg" if s["sideslip"] else ""
    print(f"ramair_fluid: {s['model']} at {s['speed']:g} m/s, inflow angle {s['angle']:g} deg{slip} (wing incidence "
          f"{geo['incidence_deg']:.3g} deg), Re {d['Re']:.4g}; {s['resolution']} mesh, background {n[0]}x{n[1]}x{n[2]}; "
          f"deltaT {d['deltaT']:.4g} s x {s['steps']} steps; Aref {d['Aref']:.4g} m^2, AR {d['aspect_ratio']:.3g}")


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
