#!/usr/bin/env bash
# A coupled case of one's own from the template (cases/coupled/template, README.md "Coupling your own OpenFOAM
# case"): a channel with a flexible stretch of its bottom wall, a case nobody ships, written here the way the
# recipe says (blockMesh, the fsiCoupling function, dynamicMeshDict, pointDisplacement, structure.yaml; no
# reference.yaml), with the template's Allrun, Allrun.parallel and Allclean copied in. Checks:
#   refused    without the fsiCoupling function (and without libs) Allrun stops before running anything, exit
#              2, naming system/controlDict and what to add
#   run        ./Allrun runs to its end (exit 0): summary.json with every window, the interface force balanced
#              (< 1e-6), the structure's probe, no comparison claimed; CASE.foam, plots/, log.pimpleFoam; the
#              console says where the summary is only because there is one
#   continue   ./Allrun -continue END goes on to END (summary.json's windows)
#   clean      ./Allclean leaves exactly the case's own files (the mesh and 0/ that Allrun made are removed)
#   parallel   ./Allrun.parallel (2 ranks) runs to its end
# Usage: run_template_test.sh BUILD_DIR WORK_DIR
set -uo pipefail
build=$1 work=$2
repo="$(cd "$(dirname "$0")/../.." && pwd)"
fail() { echo "FAIL: $*"; exit 1; }
command -v blockMesh > /dev/null || [ -x /usr/bin/blockMesh ] || { echo "no OpenFOAM: skipped"; exit 77; }
. "$build/share/fsi/fsi-env.sh" > /dev/null || fail "sourcing $build/share/fsi/fsi-env.sh"
rm -rf "$work" && mkdir -p "$work/channel" && cd "$work/channel" || exit 1
mkdir -p system constant 0.orig
h="FoamFile { version 2.0; format ascii; class dictionary; object"
# x along the channel (3 m), z across it (0.5 m), y the depth of one cell; the bottom from x = 1 to 2 flexible
cat > system/blockMeshDict <<DICT
$h blockMeshDict; }
scale 1;
vertices ( (0 0 0) (1 0 0) (2 0 0) (3 0 0) (0 0 0.5) (1 0 0.5) (2 0 0.5) (3 0 0.5)
           (0 0.05 0) (1 0.05 0) (2 0.05 0) (3 0.05 0) (0 0.05 0.5) (1 0.05 0.5) (2 0.05 0.5) (3 0.05 0.5) );
blocks ( hex (0 1 9 8 4 5 13 12) (16 1 10) simpleGrading (1 1 1)
         hex (1 2 10 9 5 6 14 13) (16 1 10) simpleGrading (1 1 1)
         hex (2 3 11 10 6 7 15 14) (16 1 10) simpleGrading (1 1 1) );
boundary
(
  inlet { type patch; faces ((0 8 12 4)); }
  outlet { type patch; faces ((3 7 15 11)); }
  flexible { type wall; faces ((1 2 10 9)); }
  walls { type wall; faces ((0 1 9 8) (2 3 11 10) (4 12 13 5) (5 13 14 6) (6 14 15 7)); }
  frontAndBack { type empty; faces ((0 4 5 1) (1 5 6 2) (2 6 7 3) (8 9 13 12) (9 10 14 13) (10 11 15 14)); }
);
DICT
cat > system/controlDict <<DICT
$h controlDict; }
application pimpleFoam;
startFrom latestTime; startTime 0; stopAt endTime; endTime 0.2; deltaT 0.01;
writeControl timeStep; writeInterval 10; purgeWrite 0; writeFormat ascii; writePrecision 12;
timeFormat general; timePrecision 6; runTimeModifiable false; adjustTimeStep no;
libs ("libfsiFoam.so");
functions
{
  fsi { type fsiCoupling; libs ("libfsiFoam.so"); patches (flexible); rho 1; pRef 0; scene "structure.yaml";
        scheme implicit; acceleration IQN-ILS; omega 0.1; reuse 8; tolerance 1e-6; maxIterations 40; }
}
#sinclude "controlDict.override"
DICT
cat > system/fvSchemes <<DICT
$h fvSchemes; }
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linearUpwind grad(U); div((nuEff*dev2(T(grad(U))))) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
DICT
cat > system/fvSolution <<DICT
$h fvSolution; }
solvers
{
  "(p|pcorr)" { solver PCG; preconditioner DIC; tolerance 1e-8; relTol 0.01; }
  "(p|pcorr)Final" { \$p; relTol 0; }
  "U(Final)?" { solver PBiCGStab; preconditioner DILU; tolerance 1e-8; relTol 0; }
  "cellDisplacement(Final)?" { solver PCG; preconditioner DIC; tolerance 1e-8; relTol 0; }
}
PIMPLE { nOuterCorrectors 1; nCorrectors 2; nNonOrthogonalCorrectors 0; correctPhi yes; }
DICT
cat > system/decomposeParDict <<DICT
$h decomposeParDict; }
numberOfSubdomains 2; method simple; simpleCoeffs { n (2 1 1); delta 0.001; }
DICT
cat > constant/transportProperties <<DICT
$h transportProperties; }
transportModel Newtonian; nu 0.01;
DICT
cat > constant/turbulenceProperties <<DICT
$h turbulenceProperties; }
simulationType laminar;
DICT
cat > constant/dynamicMeshDict <<DICT
$h dynamicMeshDict; }
dynamicFvMesh dynamicMotionSolverFvMesh; motionSolverLibs ("libfvMotionSolvers.so");
motionSolver displacementLaplacian; displacementLaplacianCoeffs { diffusivity quadratic inverseDistance (flexible); }
DICT
cat > 0.orig/U <<DICT
FoamFile { version 2.0; format ascii; class volVectorField; object U; }
dimensions [0 1 -1 0 0 0 0]; internalField uniform (0 0 0);
boundaryField { inlet { type fixedValue; value uniform (0.5 0 0); } outlet { type zeroGradient; }
  "(flexible|walls)" { type movingWallVelocity; value uniform (0 0 0); } frontAndBack { type empty; } }
DICT
cat > 0.orig/p <<DICT
FoamFile { version 2.0; format ascii; class volScalarField; object p; }
dimensions [0 2 -2 0 0 0 0]; internalField uniform 0;
boundaryField { inlet { type zeroGradient; } outlet { type fixedValue; value uniform 0; }
  "(flexible|walls)" { type zeroGradient; } frontAndBack { type empty; } }
DICT
cat > 0.orig/pointDisplacement <<DICT
FoamFile { version 2.0; format ascii; class pointVectorField; object pointDisplacement; }
dimensions [0 1 0 0 0 0 0]; internalField uniform (0 0 0);
boundaryField { flexible { type fsiInterfaceDisplacement; value uniform (0 0 0); }
  "(inlet|outlet|walls)" { type fixedValue; value uniform (0 0 0); } frontAndBack { type empty; } }
DICT
cat > structure.yaml <<'YAML'
title: the flexible stretch of a channel's bottom wall (a membrane strip of the fluid's depth, clamped ends)
materials:
  skin: {type: membrane, young: 2000, poisson: 0, thickness: 0.002, density: 500}
meshes:
  strip:
    generator: {type: rectangle, size: [1, 0.05], divisions: [12, 1], center: [1.5, 0.025, 0]}
    material: skin
constraints:
  - {nodes: [strip/xmin, strip/xmax], fix: all}
  - {nodes: strip, extrude: {direction: [0, 1, 0], hold: true}}
coupling: {interface: strip}
probes:
  mid_z: {type: displacement, nodes: {box: {min: [1.49, -1, -1], max: [1.51, 1, 1]}}, component: z, reduce: mean}
YAML
cp "$repo"/cases/coupled/template/{Allrun,Allrun.parallel,Allclean} . || fail "copying the template"
own=$(find . -type f | sort)

# refused: no fsiCoupling function, then no libs
cp system/controlDict controlDict.keep
sed -i 's/type fsiCoupling;/type fsiCouplingX;/' system/controlDict
./Allrun > refused.log 2>&1; rc=$?
[ "$rc" = 2 ] && grep -q "system/controlDict has no function object of type fsiCoupling" refused.log ||
  { cat refused.log; fail "refused: exit $rc without the fsiCoupling function"; }
cp controlDict.keep system/controlDict && sed -i 's/^libs ("libfsiFoam.so");$//' system/controlDict
./Allrun > refused.log 2>&1; rc=$?
[ "$rc" = 2 ] && grep -q 'add libs ("libfsiFoam.so")' refused.log || { cat refused.log; fail "refused: exit $rc without libs"; }
[ ! -d constant/polyMesh ] && [ ! -d 0 ] || fail "refused: Allrun made the mesh or 0/ before refusing"
mv controlDict.keep system/controlDict && rm refused.log
echo "ok   refused without the function object and without libs (exit 2, named)"

# run
./Allrun > run.log 2>&1; rc=$?
[ "$rc" = 0 ] || { tail -30 run.log; fail "run: Allrun exit $rc"; }
grep -q "summary.json (the numbers above)" run.log || fail "run: the console does not point at summary.json"
grep -q "no reference.yaml" run.log || fail "run: the summary does not say it compared nothing"
for f in summary.json channel.foam log.pimpleFoam structure/results.xdmf; do [ -e "$f" ] || fail "run: no $f"; done
ls plots/*.png > /dev/null 2>&1 || fail "run: no plots"
/usr/bin/python3 - <<'PY' || fail "run: summary.json"
import json, sys
s = json.load(open("summary.json"))
it, probes = s["iterations"], s.get("probes", {})
ok = (it["windows"] == 20 and s["reference"] is None and s["interface_force_relative_difference"] < 1e-6
      and "mid_z" in probes and probes["mid_z"]["final"] == probes["mid_z"]["final"] and abs(s["end_time"] - 0.2) < 1e-9)
print(f"{'ok  ' if ok else 'FAIL'} run: {it['windows']} windows to t = {s['end_time']}, force difference "
      f"{s['interface_force_relative_difference']:.1e}, mid_z {probes.get('mid_z')}")
sys.exit(0 if ok else 1)
PY

# continue
./Allrun -continue 0.3 > continue.log 2>&1 || { tail -20 continue.log; fail "continue: Allrun -continue 0.3"; }
w=$(/usr/bin/python3 -c "import json; print(json.load(open('summary.json'))['iterations']['windows'])")
[ "$w" = 30 ] || fail "continue: $w windows after -continue 0.3, not 30"
echo "ok   continue: 30 windows to t = 0.3"

# clean
rm -f run.log continue.log
./Allclean
now=$(find . -type f | sort)
[ "$now" = "$own" ] || { diff <(echo "$own") <(echo "$now"); fail "clean: Allclean left or removed files"; }
echo "ok   clean: only the case's own files left"

# parallel
./Allrun.parallel 0.05 > parallel.log 2>&1 || { tail -20 parallel.log; fail "parallel: Allrun.parallel"; }
w=$(/usr/bin/python3 -c "import json; print(json.load(open('summary.json'))['iterations']['windows'])")
[ "$w" = 5 ] || fail "parallel: $w windows to 0.05, not 5"
echo "ok   parallel: 5 windows on 2 ranks"
echo "PASS template"
