# Functions of the coupled cases' Allrun scripts (sourced; installed as share/fsi/case-functions.sh next to
# summarize.py and fsi-env.sh, like OpenFOAM's bin/tools/RunFunctions). The Allrun finds this file through
# $FSI_SHARE_DIR (set by fsi-env.sh), the fsi command on PATH, or the build/ of the source tree it sits in.
#
# Allrun [-continue] [-parallel] [END_TIME]
#   END_TIME   end time of this run (default: the case's system/controlDict); written to the untracked
#              system/controlDict.override, which controlDict includes last (#sinclude), so no tracked
#              file is edited; with a write interval that makes END_TIME a write time if it is not one
#   -continue  go on from the latest time directory (controlDict has `startFrom latestTime`; fluid and
#              structure restart together) to END_TIME or the case's end time
#   -parallel  decomposePar, mpirun -np N pimpleFoam -parallel (N: system/decomposeParDict), reconstructPar
# Without -continue, a folder that already holds results is refused (exit 2) with a one-line message.
# Ctrl-C or SIGTERM: the run stops at the end of the window with its state written, exit 130 (SIGINT) or 143
# (SIGTERM); -continue goes on from there. A second Allrun in a folder where one runs is refused (exit 2).

fsi_here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
fsi_root=$(cd "$fsi_here/../.." && pwd)
# the lock and the stoppable solver run (Ctrl-C, SIGTERM: the state kept), shared with ramair-kt/Allrun
. "$fsi_here/run-functions.sh"
export FSI_SHARE_DIR=$fsi_here
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}

# The adapter library: the lib/ next to this share/fsi (build tree or install prefix), else LD_LIBRARY_PATH.
fsiFindAdapter() {
  local d
  if [ -f "$fsi_root/lib/libfsiFoam.so" ]; then
    case ":${LD_LIBRARY_PATH:-}:" in *":$fsi_root/lib:"*) ;; *) export LD_LIBRARY_PATH="$fsi_root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ;; esac
    return 0
  fi
  local IFS=:
  for d in ${LD_LIBRARY_PATH:-}; do [ -f "$d/libfsiFoam.so" ] && return 0; done
  echo "Allrun: libfsiFoam.so is neither in $fsi_root/lib nor on LD_LIBRARY_PATH: build the adapter (cmake --build build) or source the fsi-env.sh of a build or install that has it" >&2
  exit 2
}
fsiFindAdapter
command -v pimpleFoam > /dev/null || { echo "Allrun: pimpleFoam not found (Debian's OpenFOAM: scripts/install-openfoam.sh)" >&2; exit 2; }
# Debian's python (numpy, yaml, h5py from apt), also when another python3 comes first on PATH.
python=/usr/bin/python3
[ -x "$python" ] || python=python3

fsi_case=$(basename "$PWD")
fsi_override=system/controlDict.override

fsiUsage() {
  sed -n 's/^# \{0,1\}//; /^Allrun \[/,/^Without/p' "$fsi_here/case-functions.sh"
}

# fsiTimes DIR: the time directories of DIR (names that are numbers), smallest first
fsiTimes() {
  local d
  for d in "$1"/[0-9]* "$1"/[-.][0-9]*; do
    [ -d "$d" ] || continue
    d=${d##*/}
    [[ $d =~ ^-?[0-9.]+([eE][-+]?[0-9]+)?$ ]] && echo "$d"
  done | sort -g
}
# fsiLatestTime: the latest time of this run (processor0 for a decomposed case), 0 if none
fsiLatestTime() {
  local t
  if [ -d processor0 ]; then t=$(fsiTimes processor0 | tail -n 1); else t=$(fsiTimes . | tail -n 1); fi
  echo "${t:-0}"
}
# fsiGreater A B: A > B as numbers
fsiGreater() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 > b + 0) }'; }

# fsiEntry KEY: a top-level entry of the case's system/controlDict, not of the override
fsiEntry() { foamDictionary -disableFunctionEntries -entry "$1" -value system/controlDict 2> /dev/null; }

# fsiOverrideEnd END: the controlDict entries of a run to END: `endTime END;` and, if END is not a write time,
# a write interval that makes it one: OpenFOAM writes the fields only at write times, and a continued run
# starts from the fields of the last one (e.g. every 50 steps instead of 100 for END = 0.5 at 0.01 s).
fsiOverrideEnd() {
  "$python" - "$1" "$(fsiEntry deltaT)" "$(fsiEntry writeControl)" "$(fsiEntry writeInterval)" <<'PY'
import math, sys
end, dt, control, interval = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3], float(sys.argv[4])
steps = round(end / dt)
if steps < 1 or abs(steps * dt - end) > 1e-6 * dt:
    sys.exit(f"Allrun: END_TIME {sys.argv[1]} is not a multiple of the time step deltaT {sys.argv[2]}")
if control not in ("timeStep", "runTime", "adjustableRunTime"):
    sys.exit(f"Allrun: writeControl {control} in system/controlDict: END_TIME needs timeStep or runTime")
every = round(interval) if control == "timeStep" else round(interval / dt)
print(f"endTime {sys.argv[1]};")
if steps % every:
    print(f"writeControl timeStep; writeInterval {math.gcd(steps, every)};")
PY
}

# fsiArgs "$@": reads the options; refuses to overwrite results; writes or removes the END_TIME override.
# Sets fsi_continue, fsi_parallel, fsi_end (empty: the case's own end time).
fsiArgs() {
  fsi_continue=0 fsi_parallel=0 fsi_end=
  while [ $# -gt 0 ]; do
    case $1 in
      -continue | --continue) fsi_continue=1 ;;
      -parallel | --parallel) fsi_parallel=1 ;;
      -h | -help | --help) fsiUsage; exit 0 ;;
      -*) echo "Allrun: unknown option $1 (valid: -continue -parallel END_TIME)" >&2; exit 2 ;;
      *)
        [[ $1 =~ ^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$ ]] || { echo "Allrun: END_TIME must be a number, not '$1'" >&2; exit 2; }
        [ -z "$fsi_end" ] || { echo "Allrun: two end times ($fsi_end and $1)" >&2; exit 2; }
        fsi_end=$1 ;;
    esac
    shift
  done
  local again="./Allrun"
  [ "$fsi_parallel" = 1 ] && again="./Allrun.parallel"
  fsiLock
  local latest leftovers
  latest=$(fsiLatestTime)
  leftovers=$(ls -d processor* structure log.pimpleFoam* summary.json 2> /dev/null)
  # every refusal names a command that works from this folder's state
  if [ "$fsi_continue" = 0 ]; then
    if fsiGreater "$latest" 0; then
      echo "Allrun: $PWD holds results of an earlier run (latest time $latest): $again -continue [END_TIME] goes on from t = $latest, ./Allclean && $again starts again" >&2
      exit 2
    elif [ -n "$leftovers" ]; then
      echo "Allrun: $PWD holds what an earlier run left before it wrote anything after t = 0: ./Allclean && $again starts again" >&2
      exit 2
    fi
  else
    if ! fsiGreater "$latest" 0; then
      if [ -n "$leftovers" ]; then
        echo "Allrun: the earlier run in $PWD wrote nothing after t = 0, so there is nothing to continue: ./Allclean && $again [END_TIME] starts again" >&2
      else
        echo "Allrun: no earlier run to continue in $PWD: $again [END_TIME] starts one" >&2
      fi
      exit 2
    fi
    if [ "$fsi_parallel" = 1 ] && [ ! -d processor0 ]; then
      echo "Allrun: the earlier run was serial (no processor* folders): continue it with ./Allrun -continue" >&2
      exit 2
    fi
    if [ "$fsi_parallel" = 0 ] && [ -d processor0 ]; then
      echo "Allrun: the earlier run was parallel (processor* folders): continue it with ./Allrun.parallel -continue" >&2
      exit 2
    fi
  fi
  # the case's own entries, without an override of an earlier run
  local end=$fsi_end
  [ -n "$end" ] || end=$(fsiEntry endTime) || { echo "Allrun: cannot read endTime from system/controlDict" >&2; exit 2; }
  if [ "$fsi_continue" = 1 ] && ! fsiGreater "$end" "$latest"; then
    echo "Allrun: the run already reached t = $latest (end time $end): give a later end time, $again -continue END_TIME" >&2
    exit 2
  fi
  if [ "$fsi_continue" = 1 ] && fsiGreater "$latest" 0; then
    local fields=$latest/U
    [ -d processor0 ] && fields=processor0/$latest/U
    [ -f "$fields" ] || { echo "Allrun: the latest time $latest has no fields ($fields): it cannot be continued; ./Allclean to start again" >&2; exit 2; }
  fi
  local override=
  if [ -n "$fsi_end" ]; then override=$(fsiOverrideEnd "$fsi_end") || exit 2; fi
  rm -f "$fsi_override"
  [ -z "$override" ] || printf '// Written by Allrun (%s) for END_TIME %s; removed by Allclean.\n%s\n' \
    "$(date '+%F %T')" "$fsi_end" "$override" > "$fsi_override"
  fsi_end=$end
  fsi_start_wall=$(date +%s.%N)
  local from=0 every=${override##*writeInterval }
  [ "$fsi_continue" = 1 ] && from=$latest
  case $override in
    *writeInterval*) echo "$fsi_case: t = $from to $fsi_end, fields written every ${every%;} steps (so that t = $fsi_end is written: a continued run starts there)" ;;
    *) echo "$fsi_case: t = $from to $fsi_end" ;;
  esac
}

# fsiCheckCase: what a coupled case needs before anything runs (the template's Allrun, README.md "Coupling your own
# OpenFOAM case"), each missing piece named with the file and what to add; exit 2. Sets fsi_function (the
# fsiCoupling function object's name), fsi_patches and fsi_scene.
fsiCheckCase() {
  local f name fields=0
  [ -f system/controlDict ] || { echo "Allrun: $PWD is not an OpenFOAM case: no system/controlDict" >&2; exit 2; }
  fsi_function=
  for name in $(foamDictionary -disableFunctionEntries -entry functions -keywords system/controlDict 2> /dev/null); do
    if [ "$(foamDictionary -disableFunctionEntries -entry "functions/$name/type" -value system/controlDict 2> /dev/null)" = fsiCoupling ]; then
      fsi_function=$name
      break
    fi
  done
  [ -n "$fsi_function" ] || {
    echo "Allrun: system/controlDict has no function object of type fsiCoupling: add one to its functions, e.g." \
      "fsi { type fsiCoupling; libs (\"libfsiFoam.so\"); patches (PATCH); scene \"structure.yaml\"; rho 1000; }" \
      "(options: docs/COUPLING.md)" >&2
    exit 2
  }
  fsi_patches=$(foamDictionary -disableFunctionEntries -entry "functions/$fsi_function/patches" -value system/controlDict 2> /dev/null | tr -d '()')
  fsi_scene=$(foamDictionary -disableFunctionEntries -entry "functions/$fsi_function/scene" -value system/controlDict 2> /dev/null | tr -d '"')
  [ -n "$fsi_patches" ] || { echo "Allrun: system/controlDict: functions/$fsi_function has no patches (the flexible patches, e.g. patches (flap);)" >&2; exit 2; }
  [ -n "$fsi_scene" ] || { echo "Allrun: system/controlDict: functions/$fsi_function has no scene (the structure, e.g. scene \"structure.yaml\";)" >&2; exit 2; }
  [ -f "$fsi_scene" ] || { echo "Allrun: system/controlDict: functions/$fsi_function names the scene $fsi_scene, which is not in $PWD" >&2; exit 2; }
  foamDictionary -disableFunctionEntries -entry libs -value system/controlDict 2> /dev/null | grep -q libfsiFoam ||
    { echo "Allrun: system/controlDict: add libs (\"libfsiFoam.so\"); at its top level (the interface's pointDisplacement condition lives there)" >&2; exit 2; }
  [ -f constant/dynamicMeshDict ] || { echo "Allrun: no constant/dynamicMeshDict: the coupled patches move the mesh (e.g. dynamicFvMesh dynamicMotionSolverFvMesh; motionSolver displacementLaplacian; displacementLaplacianCoeffs { diffusivity quadratic inverseDistance (PATCH); })" >&2; exit 2; }
  for f in 0/pointDisplacement 0.orig/pointDisplacement; do
    [ -f "$f" ] || continue
    fields=1
    grep -q fsiInterfaceDisplacement "$f" ||
      { echo "Allrun: $f: the coupled patches ($fsi_patches) need { type fsiInterfaceDisplacement; value uniform (0 0 0); }" >&2; exit 2; }
  done
  [ "$fields" = 1 ] || fsiGreater "$(fsiLatestTime)" 0 || { echo "Allrun: no 0/pointDisplacement (or 0.orig/pointDisplacement): the mesh motion's field, type fsiInterfaceDisplacement on $fsi_patches" >&2; exit 2; }
  return 0
}

# fsiPrepareMesh: blockMesh when there is no mesh and system/blockMeshDict says how to make one (Allclean removes
# only a mesh made here); otherwise the case's own mesh (snappyHexMesh, gmshToFoam, ... made by you)
fsiPrepareMesh() {
  [ -d constant/polyMesh ] && return 0
  [ -f system/blockMeshDict ] || { echo "Allrun: no mesh (constant/polyMesh) and no system/blockMeshDict to make one: mesh the case first" >&2; exit 2; }
  runApplication blockMesh
  touch constant/polyMesh/.madeByAllrun
}

# fsiPrepareFields: 0/ from 0.orig/ when the case keeps its initial fields there (Allclean removes only a 0/
# made here)
fsiPrepareFields() {
  [ -d 0.orig ] && [ ! -d 0 ] || return 0
  cp -r 0.orig 0
  touch 0/.madeByAllrun
}

# fsiFresh: true unless this is a continued run (the mesh and initial fields are prepared only then)
fsiFresh() { [ "$fsi_continue" = 0 ]; }

# runApplication NAME [ARGS...]: runs NAME, output in log.NAME (log.NAME.N if it exists); stops on failure
fsiLogName() {
  local log="log.$1" n=1
  while [ -e "$log" ]; do log="log.$1.$n"; n=$((n + 1)); done
  echo "$log"
}
runApplication() {
  local app=$1 log
  shift
  log=$(fsiLogName "$app")
  echo "Running $app (log: $log)"
  "$app" "$@" > "$log" 2>&1 || { echo "$app failed; the end of $log:" >&2; tail -20 "$log" >&2; exit 1; }
}

# runLogged LOG NAME [ARGS...]: runs NAME with its output in LOG (a name of the caller's choosing: the new
# meshes of a remeshing run, log.snappyHexMesh.remesh1, ...); stops on failure
runLogged() {
  local log=$1 app=$2
  shift 2
  echo "Running $app (log: $log)"
  "$app" "$@" > "$log" 2>&1 || { echo "$app failed; the end of $log:" >&2; tail -20 "$log" >&2; exit 1; }
}

# fsiProgress: the coupling's progress lines from the solver output on stdin. Lines with a time ("t = ")
# come every window, so they are shown at most every 2 s of wall time (and the last one at the end);
# other lines (set-up, warnings, non-converged windows, totals) are shown as they come.
fsiProgress() {
  local line pending='' last=-10
  while IFS= read -r line; do
    case $line in
      *"NOT CONVERGED"* | *[Ww]arning* | *[Ee]rror*) echo "$line" ;;
      *"t = "*)
        if [ $((SECONDS - last)) -ge 2 ]; then echo "$line"; last=$SECONDS; pending=; else pending=$line; fi ;;
      *) [ -n "$pending" ] && { echo "$pending"; pending=; }; echo "$line" ;;
    esac
  done
  [ -n "$pending" ] && echo "$pending"
  return 0
}

# fsiConsole: the console's share of the solver output: the [fsi] lines (set-up, progress, totals) and what needs
# a look (a window that did not converge, warnings, errors); the per-window `fsiCoupling: t = ...` lines stay in
# the log
fsiConsole() {
  grep --line-buffered -E '^\[fsi\] |NOT CONVERGED|[Ww]arning|FATAL|[Ee]rror([^s]|$)' | fsiProgress
}

# runSolver: pimpleFoam, serial or on the ranks of system/decomposeParDict; the full output goes to
# log.pimpleFoam (log.pimpleFoam.N for a continued run), the coupling's progress lines (`[fsi] ...`, or
# `fsiCoupling: ...` from older adapters) to the console.
runSolver() {
  local log cmd=(pimpleFoam)
  log=$(fsiLogName pimpleFoam)
  if [ "$fsi_parallel" = 1 ]; then
    local np
    np=$(foamDictionary -entry numberOfSubdomains -value system/decomposeParDict) ||
      { echo "Allrun: no numberOfSubdomains in system/decomposeParDict" >&2; exit 2; }
    [ -d processor0 ] || runApplication decomposePar
    # Open MPI refuses to start as root unless told so (containers and CI run as root); MPICH ignores these.
    [ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    # --oversubscribe: Open MPI counts physical cores as slots and would refuse more ranks than that.
    cmd=(mpirun -np "$np")
    # --bind-to none: Open MPI pins each of 2 ranks to a core, and with it the master rank's structure threads
    # (solver.threads) to the master's one core; unpinned, they use the cores the other ranks free while they
    # sleep in the structure's part of the window (adapter/fsiRankWait.H, docs/PERFORMANCE.md).
    mpirun --version 2> /dev/null | grep -q "Open MPI" && cmd+=(--oversubscribe --bind-to none)
    cmd+=(pimpleFoam -parallel)
  fi
  echo "Running ${cmd[*]} (log: $log)"
  # Ctrl-C / SIGTERM: the run stops at the end of the window with its state written (run-functions.sh)
  fsiRunStoppable "$log" fsiConsole "${cmd[@]}"
  local rc=$fsi_rc again="./Allrun"
  [ "$fsi_parallel" = 1 ] && again="./Allrun.parallel"
  [ -n "$fsi_signal" ] && fsiStoppedExit "$again" "$(fsiLatestTime)"
  if [ "$rc" != 0 ]; then
    echo "pimpleFoam failed (exit $rc); the end of $log:" >&2
    tail -20 "$log" >&2
    exit 1
  fi
  # One time series for ParaView's reader (Reconstructed Case, its default); processor* stay for -continue.
  [ "$fsi_parallel" = 1 ] && runApplication reconstructPar -newTimes
  return 0
}

# fsiFinish: summary.json and its human-readable summary, plots (fsi plot), CASE.foam for ParaView.
fsiFinish() {
  local wall status=0 fsi_cmd=
  wall=$(awk -v a="$fsi_start_wall" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
  local continued=()
  [ "$fsi_continue" = 1 ] && continued=(--continued)
  local summary="summary.json (the numbers above)"
  "$python" "$fsi_here/summarize.py" . "$wall" "${continued[@]}" || { status=1; summary="no summary: summarize.py failed (above)"; }
  touch "$fsi_case.foam"
  if [ -x "$fsi_root/bin/fsi" ]; then fsi_cmd=$fsi_root/bin/fsi; else fsi_cmd=$(command -v fsi); fi
  local plots="no plots (this fsi command has no 'plot')"
  if [ -z "$fsi_cmd" ]; then
    plots="no plots (no fsi command)"
  elif "$fsi_cmd" --help 2> /dev/null | grep -qE '^ +plot '; then
    if "$fsi_cmd" plot . > log.plot 2>&1; then
      plots="plots/ (fsi plot)"
    else
      plots="no plots: fsi plot failed, see log.plot"
      status=1
    fi
  fi
  echo "Results in $PWD:"
  echo "  $summary, $fsi_case.foam (ParaView: the fluid), structure/*.xdmf (the structure), $plots"
  return $status
}
