# Sourced by the ram-air tests (run_ramair_fluid_test.sh, run_ramair_coupled_test.sh) with src, build, work
# set: skips (exit 77) without Debian's OpenFOAM binaries, copies the case's tracked files out of the source
# tree into $work/ramair-kt the way a user copies a case, sources the build's fsi-env.sh and enters the copy.
for app in blockMesh surfaceFeatureExtract snappyHexMesh checkMesh pimpleFoam; do
  command -v "$app" > /dev/null || { echo "SKIP: $app not found (OpenFOAM is not installed)"; exit 77; }
done
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work/ramair-kt" || exit 1
case_files=$(git -C "$src" ls-files cases/coupled/ramair-kt)
[ -n "$case_files" ] || fail "no tracked files in cases/coupled/ramair-kt"
for f in $case_files; do cp "$src/$f" "$work/ramair-kt/"; done
unset FSI_SHARE_DIR
# shellcheck disable=SC1091
. "$build/share/fsi/fsi-env.sh"
# foamDictionary needs the installation's etc/; mpirun refuses root unless told (containers, CI)
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
if [ "$(id -u)" = 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
cd "$work/ramair-kt" || exit 1
