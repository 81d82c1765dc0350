# Functions every coupled case's Allrun shares (sourced by case-functions.sh and by ramair-kt/Allrun; installed as
# share/fsi/run-functions.sh): one Allrun per case folder (a lock), and a solver run that Ctrl-C or SIGTERM
# stops with its state kept.
#
# What the user gets (README.md "Stopping and continuing a run", docs/ROBUSTNESS.md):
#   Ctrl-C, or SIGTERM to Allrun (a scheduler's time limit): the coupling ends the run at the end of the current
#   window, writes the fluid's fields and the structure's state at that time (every rank), and Allrun exits 130
#   (SIGINT) or 143 (SIGTERM) with one line naming the command that continues. A second Ctrl-C stops the
#   solver at once, without writing (what the last write time holds is kept). `touch fsi.stop` in the case
#   does what Ctrl-C does, from another terminal.
# How: the solver runs in its own session (setsid), so the terminal's Ctrl-C and a SIGTERM sent to Allrun reach
# Allrun only (mpirun would kill its ranks within a second of either); Allrun's trap writes fsi.stop, which the
# fsiCoupling function object reads at the end of every window (adapter/fsiStopRequest.H).

# fsiLock: refuses a second Allrun in this folder while one runs (exit 2, naming the running one's pid and how to
# stop it). The lock is held by this shell and what it starts (the solver keeps it if Allrun is killed).
fsiLock() {
  command -v flock > /dev/null || return 0
  exec 9<> .allrun.lock
  if ! flock -n 9; then
    local pid
    pid=$(head -c 32 .allrun.lock | tr -cd '0-9')
    echo "Allrun: another Allrun runs in $PWD${pid:+ (pid $pid)}: wait for it to end, or stop it with" \
      "kill -INT ${pid:-PID} (it writes its state and exits; then ./Allrun -continue goes on)" >&2
    exit 2
  fi
  echo "$$" > .allrun.lock
}

# fsiSignalExit SIG: Allrun's exit code after a stop on SIG (INT: 130, TERM: 143)
fsiSignalExit() { [ "$1" = TERM ] && echo 143 || echo 130; }

# fsiOnSignal SIG: Allrun's trap while the solver runs (fsi_coupled_run=0: a solver without the coupling, which
# cannot stop at a window's end: stopped at once)
fsiOnSignal() {
  if [ -n "$fsi_signal" ] || [ "${fsi_coupled_run:-1}" = 0 ]; then
    fsi_signal=${fsi_signal:-$1}
    echo "Allrun: SIG$1: the solver stops now, without writing" >&2
    local pid
    pid=$(tr -cd '0-9' < .fsi.pid 2> /dev/null)
    # mpirun takes SIGTERM down to its ranks; a serial solver ignores it until the coupling starts: KILL
    if [ -n "$pid" ]; then
      if [ "$fsi_mpi" = 1 ]; then kill -TERM "$pid" 2> /dev/null; else kill -KILL "$pid" 2> /dev/null; fi
    fi
    return 0
  fi
  fsi_signal=$1
  echo "$1" > fsi.stop
  echo "Allrun: SIG$1: the run stops at the end of this window and writes its state (Ctrl-C again: stop now, without writing)" >&2
}

# fsiRunStoppable LOG FILTER CMD [ARGS...]: runs CMD in its own session, its output in LOG and through the
# function FILTER to the console. Sets fsi_rc (CMD's exit code) and fsi_signal (INT, TERM or empty).
fsiRunStoppable() {
  local log=$1 filter=$2
  shift 2
  fsi_signal= fsi_mpi=0
  [ "$1" = mpirun ] && fsi_mpi=1
  rm -f fsi.stop .fsi.rc .fsi.pid structure/interrupted
  # The pipeline ignores INT and TERM (tee, the filter: they must outlive the solver's last lines); the solver
  # too until the coupling installs its handlers; Allrun's trap is set after the fork.
  trap '' INT TERM
  (
    setsid -w bash -c 'echo $$ > .fsi.pid; exec "$@"' fsi-solver "$@" < /dev/null 2>&1 | tee "$log" | "$filter"
    echo "${PIPESTATUS[0]}" > .fsi.rc
  ) &
  local job=$!
  trap 'fsiOnSignal INT' INT
  trap 'fsiOnSignal TERM' TERM
  # wait returns early when a trapped signal arrives: wait again until the job has ended
  while kill -0 "$job" 2> /dev/null; do wait "$job"; done
  wait "$job" 2> /dev/null
  trap - INT TERM
  fsi_rc=$(tr -cd '0-9' < .fsi.rc 2> /dev/null)
  [ -n "$fsi_rc" ] || fsi_rc=1
  rm -f .fsi.rc .fsi.pid fsi.stop
}

# fsiStoppedExit AGAIN LATEST: after a run that a signal stopped: one line saying where it stopped and the
# command that continues (AGAIN: ./Allrun or ./Allrun.parallel; LATEST: the latest time with fields), exit
fsiStoppedExit() {
  local again=$1 latest=$2 t
  if [ -f structure/interrupted ]; then
    t=$(sed -n 's/^time //p' structure/interrupted)
    echo "Allrun: stopped on SIG$fsi_signal at t = $t s; the fields and the structure's state are written there: $again -continue [END_TIME] goes on" >&2
  elif [ "${fsi_rc:-1}" = 0 ]; then
    return 0  # the run reached its end before the stop request took effect
  elif awk -v a="$latest" 'BEGIN { exit !(a + 0 > 0) }'; then
    echo "Allrun: stopped on SIG$fsi_signal before the next window ended; the latest written time is t = $latest s: $again -continue [END_TIME] goes on from there" >&2
  else
    echo "Allrun: stopped on SIG$fsi_signal before anything was written after t = 0: ./Allclean && $again starts again" >&2
  fi
  exit "$(fsiSignalExit "$fsi_signal")"
}
