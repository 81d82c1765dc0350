#!/usr/bin/env bash
# One measurement of issue 16's scaling study: writes the case (make_case.py) for about N interface points on
# RANKS ranks into $FSI_SCALE_DIR/N<N>-np<RANKS> (default /tmp/fsi-adapter-scale), runs it (serial, or
# mpirun -np RANKS through the case functions, which add --oversubscribe for Open MPI), and records `uptime`
# before and after the run in uptime.txt there. collect.py reads the results.
# Usage: run.sh N RANKS [WINDOWS [PROJECTION [THREADS]]]  (source fsi-env.sh first; defaults 4, auto, 1)
# With THREADS > 1 the case folder is N<N>-np<RANKS>-t<THREADS>.
set -euo pipefail
[ $# -ge 2 ] && [ $# -le 5 ] || { echo "usage: $0 N RANKS [WINDOWS [PROJECTION [THREADS]]]" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
root=${FSI_SCALE_DIR:-/tmp/fsi-adapter-scale}
threads=${5:-1}
case_dir=$root/N$1-np$2
[ "$threads" != 1 ] && case_dir=$case_dir-t$threads
mkdir -p "$root"
"$here/make_case.py" "$1" "$2" "$case_dir" --windows "${3:-4}" --projection "${4:-auto}" --threads "$threads"
flag=
[ "$2" -gt 1 ] && flag=-parallel
{ echo "before: $(uptime)"; echo "cores: $(nproc)"; } > "$case_dir/uptime.txt"
start=$(date +%s.%N)
"$case_dir/Allrun" $flag
end=$(date +%s.%N)
echo "after: $(uptime)" >> "$case_dir/uptime.txt"
awk -v a="$start" -v b="$end" 'BEGIN { printf "Allrun wall %.1f s\n", b - a }' | tee -a "$case_dir/uptime.txt"
