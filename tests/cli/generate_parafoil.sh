#!/bin/bash
# fsi generate on a parafoil scene: MESH.msh and MESH.stl are written; Gmsh itself reads the .msh; reading the
# .msh back through a scene gives the same nodes, elements and sets; with OpenFOAM (third argument "openfoam")
# its surfaceCheck finds the STL closed, every edge shared by two faces (the surface snappyHexMesh needs).
set -u
FSI=$1
WORK=$2
OPENFOAM=${3:-}
SRC=$(cd "$(dirname "$0")/../data" && pwd)
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

"$FSI" generate "$SRC/parafoil-small.yaml" --out gen > gen.log 2>&1 || { cat gen.log; fail "fsi generate failed"; }
cat gen.log
[ -s gen/wing.msh ] && [ -s gen/wing.stl ] || fail "gen/wing.msh or gen/wing.stl missing"
counts=$(grep 'wing.msh' gen.log | sed 's/^[^ ]*  //; s/, [0-9]* sets//')
[ -n "$counts" ] || fail "no summary line for wing.msh"

# Gmsh reads and re-writes the file with all its physical groups.
command -v gmsh > /dev/null || fail "gmsh is not installed (scripts/install-deps.sh installs it)"
gmsh gen/wing.msh -0 -save_all -format msh22 -o regmsh.msh > gmsh.log 2>&1 || { cat gmsh.log; fail "gmsh cannot read wing.msh"; }
names=$(sed -n '/\$PhysicalNames/{n;p;q}' gen/wing.msh)
renames=$(sed -n '/\$PhysicalNames/{n;p;q}' regmsh.msh)
[ "$names" = "$renames" ] || fail "gmsh kept $renames of $names physical groups"

# Our own reader: the written file as a scene's mesh gives the same nodes and elements, the same outer surface
# (its set 'skin' selects the same triangles), and every set the generator made (the reader adds node sets
# for the element sets, so their number grows).
# (a mesh file's cables are named: the generator's lines are all cables)
sed -e "s|generator: {type: parafoil.*|file: $WORK/gen/wing.msh|" -e '/chordwise_points: 20/d' \
    -e 's/^    cable_material: line$/    cable_material: line\n    cables: all/' \
    "$SRC/parafoil-small.yaml" > reread.yaml
grep -q "^    cables: all" reread.yaml || fail "could not name the re-read scene's cables"
grep -q "file: $WORK/gen/wing.msh" reread.yaml || fail "could not build the re-read scene"
"$FSI" generate reread.yaml --out again > again.log 2>&1 || { cat again.log; fail "re-reading wing.msh failed"; }
recounts=$(grep 'wing.msh' again.log | sed 's/^[^ ]*  //; s/, [0-9]* sets//')
[ "$counts" = "$recounts" ] || fail "re-read gives '$recounts', written '$counts'"
# The reader orders triangles by entity: compare the facets as sets.
/usr/bin/python3 - gen/wing.stl again/wing.stl <<'PY' || fail "the STL of the re-read mesh has other facets"
import sys
def facets(f):
    text = open(f).read().split("facet normal")[1:]
    return sorted(" ".join(t.split()) for t in text)
sys.exit(0 if facets(sys.argv[1]) == facets(sys.argv[2]) else 1)
PY

# --deformed: the skin at a run's last frame. (1) The same scene from its own results.h5: every vertex of the
# STL is a node of the run, at that node's last-frame position. (2) A translation in the results file,
# generated with the chordwise points doubled (another mesh of the same geometry): a constant displacement
# interpolates exactly, so the finer STL is the finer design STL moved by it. (3) A missing run is refused.
"$FSI" run "$SRC/parafoil-small.yaml" --out run -q > run.log 2>&1 || { cat run.log; fail "fsi run failed"; }
"$FSI" generate "$SRC/parafoil-small.yaml" --out deformed --deformed run > deformed.log 2>&1 ||
  { cat deformed.log; fail "fsi generate --deformed failed"; }
grep -q "deformed" deformed.log || fail "generate --deformed did not say what it did"
"$FSI" generate "$SRC/parafoil-small.yaml" --out fine --set meshes.wing.generator.chordwise_points=40 > fine.log 2>&1 ||
  { cat fine.log; fail "fsi generate (finer) failed"; }
/usr/bin/python3 - "$FSI" "$SRC/parafoil-small.yaml" <<'PY' || fail "--deformed does not place the skin at the run's last frame"
import h5py, numpy as np, shutil, subprocess, sys
def verts(f):
    return np.array([[float(x) for x in l.split()[1:4]] for l in open(f) if l.split()[:1] == ["vertex"]])
with h5py.File("run/results.h5", "r") as f:
    last = sorted(f["steps"])[-1]
    x = f[f"steps/{last}/coordinates"][()]
    u = f[f"steps/{last}/displacement"][()]
assert np.abs(u).max() > 1e-6, "the run moved nothing: the check would not see a wrong frame"
v = verts("deformed/wing.stl")
d = np.min(np.linalg.norm(v[:, None, :] - x[None, :, :], axis=2), axis=1)
print(f"(1) {len(v)} STL vertices, largest distance to a last-frame node {d.max():.2e} m")
if d.max() > 1e-7:
    sys.exit(1)
shutil.copy("run/results.h5", "shift.h5")
t = np.array([0.25, -0.5, 1.5])
with h5py.File("shift.h5", "r+") as f:
    ref = x - u
    f[f"steps/{last}/displacement"][...] = np.broadcast_to(t, u.shape)
    f[f"steps/{last}/coordinates"][...] = ref + t
subprocess.run([sys.argv[1], "generate", sys.argv[2], "--out", "shifted", "--deformed", "shift.h5",
                "--set", "meshes.wing.generator.chordwise_points=40"], check=True, stdout=subprocess.DEVNULL)
a, b = verts("fine/wing.stl") + t, verts("shifted/wing.stl")
err = np.abs(a - b).max()
print(f"(2) {len(b)} vertices of the finer skin, translated: largest error {err:.2e} m")
sys.exit(0 if len(a) == len(b) and len(a) > len(v) and err < 1e-6 else 1)
PY
"$FSI" generate "$SRC/parafoil-small.yaml" --out none --deformed no-such-run > none.log 2>&1
rc=$?
[ $rc = 2 ] && grep -q "no-such-run" none.log || { cat none.log; fail "a missing --deformed run: exit $rc, want 2 naming it"; }

if [ "$OPENFOAM" = openfoam ]; then
  export WM_PROJECT_DIR=/usr/share/openfoam  # Debian's OpenFOAM finds its etc/ there (as in tests/adapter)
  surfaceCheck gen/wing.stl > check.log 2>&1 || { tail -20 check.log; fail "surfaceCheck failed"; }
  grep -q "Surface is closed" check.log || { grep -iE "open|illegal|edges" check.log; fail "STL not closed"; }
fi
echo "PASS"
