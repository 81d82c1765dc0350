#!/bin/sh
# The malformed-input corpus through the fsi command line: every file must end the command with exit code 2
# and one "error: FILE..." message, never a crash (signal), another code or a silent result; no script may
# run. Usage: run_cli.sh FSI_BINARY WORK_DIR
set -u
fsi=$1
work=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failed=0

expect2() {  # expect2 WHAT_MUST_APPEAR COMMAND...
  what=$1
  shift
  "$@" > out.txt 2> err.txt
  code=$?
  if [ $code -ne 2 ] || ! grep -q "^error: .*$what" err.txt; then
    echo "FAIL (exit $code): $*"
    cat err.txt
    failed=1
  fi
}

good=$here/gmsh/valid_square_41.msh
for f in "$here"/gmsh/*.msh; do
  case $(basename "$f") in valid_square_41.msh) continue ;; esac
  expect2 "$f" "$fsi" map-check "$f" "$good"
  expect2 "$f" "$fsi" map-check "$good" "$f"
done
for d in "$here"/openfoam/*/; do
  d=${d%/}
  case $(basename "$d") in valid_two_cells) continue ;; esac
  expect2 "$d" "$fsi" map-check "$d:walls" "$here/openfoam/valid_two_cells:walls"
done

# A scene naming a Gmsh script: refused with the scene's line, the script not run.
cat > scene.yaml <<YAML
materials:
  film: {type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}
meshes:
  sheet:
    file: $here/gmsh/script.geo
    material: film
time:
  end: 0.01
YAML
expect2 "scene.yaml:5.*script.geo.*gmsh -2" "$fsi" run scene.yaml --out out
if [ -e fsi_corpus_geo_script_was_executed ]; then
  echo "FAIL: the .geo script ran"
  failed=1
fi

# The valid files map (exit 0), so the errors above come from the defects.
"$fsi" map-check "$good" "$good" > /dev/null || { echo "FAIL: valid Gmsh file"; failed=1; }
"$fsi" map-check "$here/openfoam/valid_two_cells:walls" "$here/openfoam/valid_two_cells:walls" > /dev/null ||
  { echo "FAIL: valid OpenFOAM case"; failed=1; }
[ $failed -eq 0 ] && echo "corpus: all files refused with exit code 2"
exit $failed
