# Shared by the coupled cases' Allrun scripts (sourced): finds Debian's OpenFOAM and the adapter library,
# runs an application with its output in log.<name>, and times the run.
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
lib_dir=${FSI_ADAPTER_LIB_DIR:-$repo/build/lib}
if [ ! -f "$lib_dir/libfsiFoam.so" ]; then
  echo "Allrun: $lib_dir/libfsiFoam.so not found: build the project first (scripts/build.sh), or set FSI_ADAPTER_LIB_DIR" >&2
  exit 2
fi
export LD_LIBRARY_PATH="$lib_dir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
command -v pimpleFoam > /dev/null || { echo "Allrun: pimpleFoam not found (scripts/install-openfoam.sh)" >&2; exit 2; }

# runApplication NAME [ARGS...]: runs NAME, output in log.NAME (log.NAME.N if it exists); stops on failure
runApplication() {
  local app=$1; shift
  local log="log.$app"
  local n=1
  while [ -e "$log" ]; do log="log.$app.$n"; n=$((n + 1)); done
  echo "Running $app on $PWD (log: $log)"
  "$app" "$@" > "$log" 2>&1 || { echo "$app failed; the end of $log:" >&2; tail -20 "$log" >&2; exit 1; }
}
# Debian's python (numpy, yaml, h5py from apt), also when another python3 comes first on PATH.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
