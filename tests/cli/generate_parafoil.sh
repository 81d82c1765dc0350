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

if [ "$OPENFOAM" = openfoam ]; then
  export WM_PROJECT_DIR=/usr/share/openfoam  # Debian's OpenFOAM finds its etc/ there (as in tests/adapter)
  surfaceCheck gen/wing.stl > check.log 2>&1 || { tail -20 check.log; fail "surfaceCheck failed"; }
  grep -q "Surface is closed" check.log || { grep -iE "open|illegal|edges" check.log; fail "STL not closed"; }
fi
echo "PASS"
