#!/usr/bin/env bash
# Runs the README's two commands on a brand-new minimal Debian 12, so that a package the project's scripts
# forget to install fails here instead of on a user's machine (issue 10: CI passed only because this machine
# already had lbzip2 and python3-yaml).
#
# 1. debootstrap --variant=minbase bookworm into a scratch root, from this machine's own apt mirror (CI
#    machines reach only Debian's package registry);
# 2. inside it (chroot, as root): apt-get install --no-install-recommends g++ cmake make git python3 —
#    what the issue's fresh machine had, without the recommended extras, so that every other package must
#    come from scripts/install-deps.sh;
# 3. git clone of this repository at HEAD (the commit being tested; uncommitted changes are not part of it);
# 4. scripts/main.sh, then scripts/test.sh, exactly as the README says (test.sh told where the main job's
#    results are, so that its test of the main job checks them instead of running the case again). Either
#    failing fails the check,
#    with the tail of its log.
#
# Must run as root (debootstrap, mount, chroot); re-runs itself through sudo otherwise.
# Environment:
#   FSI_FRESH_DIR=DIR     scratch parent (default ${TMPDIR:-/tmp}); the root goes to DIR/fsi-fresh.XXXXXX
#   FSI_FRESH_KEEP=1      keep the root and logs at the end (debugging); default: delete them
#   FSI_FRESH_USER=1      run the README commands as a user with sudo (the README's other case) instead of
#                         root: adds the sudo package and a user "fsi" with passwordless sudo
#   FSI_FRESH_CACHE=FILE  reuse the base root (steps 1-2, nothing of the project) from the tarball FILE, or
#                         write FILE after building it — for fast local reruns; CI leaves it unset and
#                         starts from nothing. Delete FILE when the mirror or the base package list changes.
# Usage: scripts/fresh-machine-check.sh
set -euo pipefail

if [ "$(id -u)" -ne 0 ]; then
  exec sudo --preserve-env=FSI_FRESH_DIR,FSI_FRESH_KEEP,FSI_FRESH_CACHE,FSI_FRESH_USER,TMPDIR "$0" "$@"
fi

repo="$(cd "$(dirname "$0")/.." && pwd)"
base_packages=(g++ cmake make git python3)
suite=bookworm

t_all=$SECONDS
say() { echo "[fresh] $*"; }

# --- this machine's apt entries: "URI SUITE COMPONENTS..." per binary (deb) source -------------------------
host_apt_entries() {
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    # deb822: blank-line separated stanzas; one entry per URI x suite of a stanza whose Types has "deb"
    awk 'function flush(  i, j, nu, ns, u, s) {
           if (types ~ /(^| )deb( |$)/) {
             nu = split(uris, u, " "); ns = split(suites, s, " ")
             for (i = 1; i <= nu; i++) for (j = 1; j <= ns; j++) print u[i], s[j], comps
           }
           types = uris = suites = comps = ""
         }
         /^[ \t]*#/ { next }
         /^[ \t]*$/ { flush(); next }
         { key = tolower($1); sub(/^[^:]*:[ \t]*/, "") }
         key == "types:" { types = $0 } key == "uris:" { uris = $0 }
         key == "suites:" { suites = $0 } key == "components:" { comps = $0 }
         key == "enabled:" && tolower($0) == "no" { types = "" }
         END { flush() }' "$f"
  done
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    # one-line format: deb [options] URI SUITE COMPONENTS...
    sed -n -e 's/^[ \t]*deb[ \t]\+\(\[[^]]*\][ \t]\+\)\?//p' "$f"
  done
}
entries="$(host_apt_entries)"
mirror="$(awk -v s="$suite" '$2 == s && / main( |$)/ { print $1; exit }' <<< "$entries")"
if [ -z "$mirror" ]; then
  say "no '$suite' entry in /etc/apt/sources.list or /etc/apt/sources.list.d/: cannot pick the Debian mirror"
  exit 2
fi

# --- scratch root; every exit path kills what runs in it, unmounts and deletes it --------------------------
scratch="${FSI_FRESH_DIR:-${TMPDIR:-/tmp}}"
mkdir -p "$scratch"
# the root grows to about 3 GB (OpenFOAM, gmsh, the build), the optional cache is about 0.9 GB
avail_kb=$(df --output=avail -k "$scratch" | tail -n 1)
if [ "$avail_kb" -lt $((5 * 1024 * 1024)) ]; then
  say "$scratch has $((avail_kb / 1024)) MB free; the check needs 5 GB (set FSI_FRESH_DIR to another folder)"
  exit 2
fi
work="$(mktemp -d "$scratch/fsi-fresh.XXXXXX")"
root="$work/root"
logs="$work/logs"
mkdir -p "$root" "$logs"

mounts_under_root() { awk -v r="$root" '$2 == r || index($2, r "/") == 1 { print $2 }' /proc/self/mounts; }
# kill_tree PID: PID and all its descendants (a phase that runs on this machine: debootstrap, tar, git)
kill_tree() {
  local -A kids=()
  local p stat ppid queue=("$1") all=()
  for p in /proc/[0-9]*; do
    stat="$(cat "$p/stat" 2>/dev/null)" || continue
    read -r _ ppid _ <<< "${stat##*) }"
    kids[$ppid]+=" ${p#/proc/}"
  done
  while [ ${#queue[@]} -gt 0 ]; do
    all+=("${queue[0]}")
    # shellcheck disable=SC2206 # the list of child pids splits on spaces
    queue=("${queue[@]:1}" ${kids[${queue[0]}]:-})
  done
  kill -s TERM "${all[@]}" 2>/dev/null || true
}
kill_chroot_processes() {
  local p sig pids
  for sig in TERM KILL; do
    pids=()
    for p in /proc/[0-9]*; do
      [ "$(readlink "$p/root" 2>/dev/null)" = "$root" ] && pids+=("${p#/proc/}")
    done
    [ ${#pids[@]} -eq 0 ] && return 0
    kill -s "$sig" "${pids[@]}" 2>/dev/null || true
    sleep 2
  done
}
unmount_all() {
  local m
  # deepest first (reverse order of mounting)
  for m in $(mounts_under_root | sort -r); do
    umount "$m" 2>/dev/null || umount -l "$m" || true
  done
}
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  [ -n "${phase_pid:-}" ] && kill_tree "$phase_pid"
  kill_chroot_processes
  unmount_all
  if [ -n "$(mounts_under_root)" ]; then
    say "still mounted under $root, not deleting it:"; mounts_under_root
  elif [ "${FSI_FRESH_KEEP:-0}" = 1 ]; then
    say "kept $work (root/, logs/)"
  elif [ $rc -ne 0 ]; then
    rm -rf --one-file-system "$root"
    say "logs kept in $logs"
  else
    rm -rf --one-file-system "$work"
  fi
  say "total $((SECONDS - t_all)) s, exit code $rc"
  exit $rc
}
trap cleanup EXIT
trap 'say "interrupted (SIGINT)"; exit 130' INT
trap 'say "terminated (SIGTERM)"; exit 143' TERM

# Our own git calls may run as root on a checkout owned by another user (CI through sudo): a private global
# config that trusts it, and nothing from the caller's config.
printf '[safe]\n\tdirectory = *\n' > "$work/gitconfig"
export GIT_CONFIG_GLOBAL="$work/gitconfig" GIT_CONFIG_NOSYSTEM=1

# stamp: prefixes every line with the seconds since the phase began (for the sub-phase times below)
stamp() { local t0=$SECONDS line; while IFS= read -r line; do printf '%5d %s\n' $((SECONDS - t0)) "$line"; done; }
# phase NAME LOG COMMAND...: runs COMMAND with its output in LOG; prints the time or the log's tail
phase() {
  local name=$1 log=$2 t0=$SECONDS rc=0
  shift 2
  say "$name ..."
  # In the background and waited for: a signal to this script runs the cleanup at once (bash defers traps
  # while a foreground command runs), which stops the phase and unmounts before a CI's kill grace ends.
  ( "$@" 2>&1 < /dev/null | stamp > "$log" ) &
  phase_pid=$!
  wait "$phase_pid" || rc=$?
  phase_pid=
  if [ $rc -ne 0 ]; then
    say "$name FAILED (exit code $rc) after $((SECONDS - t0)) s; the end of $log:"
    tail -n 60 "$log"
    exit 1
  fi
  say "$name $((SECONDS - t0)) s"
}
# in_root COMMAND: runs a bash command line in the chroot as root, with a login's clean environment
in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root USER=root LOGNAME=root SHELL=/bin/bash TERM=dumb \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin /bin/bash -c "$1"
}
# as_user COMMAND: the same as the user who runs the README commands (root, or "fsi" with FSI_FRESH_USER=1)
user=root home=/root
if [ "${FSI_FRESH_USER:-0}" = 1 ]; then user=fsi home=/home/fsi; fi
as_user() {
  if [ "$user" = root ]; then in_root "$1"; return; fi
  chroot --userspec="$user:$user" "$root" /usr/bin/env -i HOME="$home" USER="$user" LOGNAME="$user" \
    SHELL=/bin/bash TERM=dumb PATH=/usr/local/bin:/usr/bin:/bin /bin/bash -c "$1"
}

# kernel file systems, mounted as soon as the root exists (apt's terminal log wants /dev/pts): /proc, /sys,
# /dev with its own pts and shm (OpenMPI's shared memory)
mount_kernel_file_systems() {
  mkdir -p "$root/proc" "$root/sys" "$root/dev"
  mount -t proc proc "$root/proc" -o nosuid,noexec,nodev
  mount -t sysfs sys "$root/sys" -o nosuid,noexec,nodev,ro
  if ! mount -t devtmpfs udev "$root/dev" -o mode=0755,nosuid 2>/dev/null; then
    mount --bind /dev "$root/dev"
    mount --make-rslave "$root/dev" # the pts and shm mounts below must not reach this machine's /dev
  fi
  mkdir -p "$root/dev/pts" "$root/dev/shm"
  mount -t devpts devpts "$root/dev/pts" -o newinstance,ptmxmode=0666,mode=0620,gid=5,nosuid,noexec
  mount -t tmpfs shm "$root/dev/shm" -o mode=1777,nosuid,nodev
}

say "repository $repo at $(git -C "$repo" rev-parse --short HEAD); mirror $mirror; scratch root $root"
[ -z "$(git -C "$repo" status --porcelain --untracked-files=no)" ] \
  || say "note: uncommitted changes in $repo are not tested (the check clones HEAD)"

# --- 1-2: the base system -----------------------------------------------------------------------------------
if [ -n "${FSI_FRESH_CACHE:-}" ] && [ -f "$FSI_FRESH_CACHE" ]; then
  phase "unpack cached base root $FSI_FRESH_CACHE" "$logs/cache.log" tar -xpf "$FSI_FRESH_CACHE" -C "$root"
  mount_kernel_file_systems
else
  if ! command -v debootstrap > /dev/null; then
    phase "install debootstrap" "$logs/debootstrap-install.log" \
      bash -c 'export DEBIAN_FRONTEND=noninteractive; apt-get update -qq && apt-get install -y -qq --no-install-recommends debootstrap'
  fi
  # an https mirror needs the CA certificates inside the root for apt's later downloads
  include=()
  case "$mirror" in https:*) include=(--include=ca-certificates) ;; esac
  phase "debootstrap" "$logs/debootstrap.log" \
    debootstrap --variant=minbase "${include[@]}" "$suite" "$root" "$mirror"
  # The root's apt sources are this machine's binary entries (main suite, updates, security), as on an
  # installed Debian 12, in the classic one-line sources.list. No deb-src: adding it is install-openfoam.sh's job.
  # Only Debian's own suites and components (a third-party repository on this machine is not Debian 12).
  awk -v s="$suite" '$2 ~ "^" s "(-updates|-security)?$" {
         c = ""; for (i = 3; i <= NF; i++) if ($i ~ /^(main|contrib|non-free|non-free-firmware)$/) c = c " " $i
         if (c != "") print "deb " $1 " " $2 c }' <<< "$entries" | awk '!seen[$0]++' > "$root/etc/apt/sources.list"
  mount_kernel_file_systems
  phase "base packages (${base_packages[*]})" "$logs/base.log" \
    in_root "export DEBIAN_FRONTEND=noninteractive; apt-get update -qq && apt-get install -y -qq --no-install-recommends ${base_packages[*]}"
  if [ -n "${FSI_FRESH_CACHE:-}" ]; then
    # written aside and renamed, so that an interrupted run leaves no truncated cache behind
    write_cache() {
      tar -cpf "$FSI_FRESH_CACHE.part" --exclude='./proc/*' --exclude='./sys/*' --exclude='./dev/*' -C "$root" . &&
        mv "$FSI_FRESH_CACHE.part" "$FSI_FRESH_CACHE"
    }
    phase "write cache $FSI_FRESH_CACHE" "$logs/cache.log" write_cache
  fi
fi
# debootstrap copies resolv.conf and hostname from this machine but writes no /etc/hosts; the one the Debian
# installer writes on a real machine (localhost and the host name):
if [ ! -s "$root/etc/hosts" ]; then
  printf '127.0.0.1\tlocalhost\n127.0.1.1\t%s\n::1\tlocalhost ip6-localhost ip6-loopback\n' \
    "$(cat "$root/etc/hostname" 2>/dev/null || hostname)" > "$root/etc/hosts"
fi

if [ "$user" != root ]; then
  phase "user $user with sudo" "$logs/user.log" in_root "export DEBIAN_FRONTEND=noninteractive
    apt-get install -y -qq --no-install-recommends sudo && useradd --create-home --shell /bin/bash $user &&
    echo '$user ALL=(ALL) NOPASSWD: ALL' > /etc/sudoers.d/$user && chmod 440 /etc/sudoers.d/$user"
fi

# --- 3: the repository at HEAD, cloned with the root's own git ------------------------------------------------
commit="$(git -C "$repo" rev-parse HEAD)"
clone_repo() {
  git clone -q --bare --no-hardlinks "$repo" "$root/tmp/origin.git"
  in_root "chown -R $user: /tmp/origin.git"
  as_user "git clone -q /tmp/origin.git $home/parachute-fsi && cd $home/parachute-fsi && git checkout -q --detach $commit && git log -1 --format='%h %s'"
  rm -rf "$root/tmp/origin.git"
}
phase "git clone ${commit:0:7}" "$logs/clone.log" clone_repo

# --- 4: the README's commands -------------------------------------------------------------------------------
phase "scripts/main.sh (as $user)" "$logs/main.log" as_user "cd $home/parachute-fsi && scripts/main.sh"
# sub-phases from the stamped log: installs end at install-deps' last line, the build at ninja's last step
awk '/\[install-deps\] (done|all [0-9]+ packages present)/ { inst = $1 }
     $2 ~ /^\[[0-9]+\/[0-9]+\]$/ { split($2, a, /[][\/]/); if (a[2] == a[3]) built = $1 }
     { last = $1 }
     END { printf "[fresh]   inside main.sh: installs %d s, build %d s, main job %d s\n", inst, built - inst, last - built }' \
  "$logs/main.log"
for f in results/ramair-kt/{summary.json,summary.md,log.pimpleFoam} results/ramair-kt/structure/{results.xdmf,results.h5,coupling.csv} results/ramair-kt/plots/{interface_force,iterations,probes,structure}.png; do
  [ -s "$root$home/parachute-fsi/$f" ] || { say "scripts/main.sh wrote no $f"; exit 1; }
done
# ParaView's OpenFOAM reader opens an empty CASE.foam file: it must exist, not have content
[ -e "$root$home/parachute-fsi/results/ramair-kt/ramair-kt.foam" ] || { say "scripts/main.sh wrote no results/ramair-kt/ramair-kt.foam"; exit 1; }

# The whole suite runs here, once (issue 33: not also on the host). fluid.ramair-kt-coupled checks the main
# job's run above instead of running the same case a second time (FSI_MAIN_JOB_RESULTS).
phase "scripts/test.sh (as $user)" "$logs/test.log" as_user \
  "cd $home/parachute-fsi && FSI_MAIN_JOB_RESULTS=$home/parachute-fsi/results/ramair-kt scripts/test.sh"
# The adapter and coupled tests exist only when the OpenFOAM headers were installed: a suite without them
# would pass while missing what this check is for.
for label in adapter coupled; do
  grep -q " $label\.[a-z]" "$logs/test.log" || { say "scripts/test.sh ran no $label.* test"; exit 1; }
done
grep -E "tests passed|Total Test time" "$logs/test.log" | sed 's/^ *[0-9]* /[fresh]   /'
awk '/Label Time Summary/ { on = 1; next } on && NF < 2 { on = 0 } on { $1 = ""; print "[fresh]   " $0 }' "$logs/test.log"
# the ten slowest tests (where CI's time goes): ctest's "N/M Test #K: NAME ....   Passed   S sec" lines.
# awk, not head, takes the first ten: head closing the pipe early makes sort die of SIGPIPE, and pipefail
# turned that into this script's exit code 141 after a suite that passed (CI of 0cdbce4).
awk '$2 ~ /^[0-9]+\/[0-9]+$/ && $3 == "Test" && $(NF) == "sec" { print $(NF - 1), $5 }' "$logs/test.log" |
  sort -rn | awk 'NR <= 10 { printf "[fresh]   slowest: %7.1f s  %s\n", $1, $2 }'
say "PASS: the README's commands work on a fresh minimal Debian 12"
