#!/usr/bin/python3
"""Ctrl-C at the command line: `fsi run` gets SIGINT at several moments of a run that takes a few seconds —
at once, as soon as the handler exists, during scene loading and set-up, during the step loop, and during a
dynamic relaxation — several times each, so that a race shows.

Expected every time: exit code 130 (not death by the signal), summary.json with stop_reason "interrupted",
an interrupted_state.h5 with a finite state, and results.xdmf / results.h5 closed cleanly. The only signals
that may kill the process are those sent while the dynamic loader still maps the shared libraries, before the
program's handler exists (read from /proc/PID/status) and before it allocates anything for the scene (its
resident memory is then that of the libraries, under LOADER_MB). The "loading" moment sends the signal while
the scene's model is being built (resident memory above SCENE_MB, no results file yet).

Usage: interrupt_test.py FSI_BINARY WORK_DIR [REPEATS]
"""
import os
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import h5py
import numpy as np

FSI, WORK = sys.argv[1], sys.argv[2]
REPEATS = int(sys.argv[3]) if len(sys.argv) > 3 else 3
SOURCE = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
HENCKY = os.path.join(SOURCE, "cases/structure/hencky/scene.yaml")
CUSHION = os.path.join(SOURCE, "cases/structure/cushion-circular/scene.yaml")

# Hencky's membrane with 300 rings (270k nodes): loading and set-up take a few tenths of a second, a step
# tens of milliseconds, and it never becomes static in the time the test gives it.
EXPLICIT = [HENCKY, "--set", "meshes.disc.generator.rings=300", "--set", "time.until_static.max_time=1000"]
RELAXATION = [CUSHION, "--set", "solver.tolerance=1.0e-12"]
LOADER_MB = 60  # the libraries alone: about 36 MB resident when the handler gets installed
SCENE_MB = 100  # the 300-ring model grows the process to about 190 MB before the results file appears


def handler_installed(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) & (1 << (signal.SIGINT - 1)))
    except OSError:
        pass
    return False


def resident_mb(pid):
    try:
        with open(f"/proc/{pid}/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 1e6
    except OSError:
        return 0.0


def run_once(label, args, moment):
    """Starts `fsi run`, sends SIGINT at `moment` (seconds after the start, "handler" as soon as the handler is
    installed, "loading" while the scene is built), returns a description of the outcome and the failures."""
    out = os.path.join(WORK, label)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(WORK, exist_ok=True)
    log = open(out + ".log", "w")
    t0 = time.monotonic()
    p = subprocess.Popen([FSI, "run", args[0], "--out", out] + args[1:], stdout=log, stderr=subprocess.STDOUT)
    t_handler = t_results = None
    sent_with_handler = None
    sent_at = None
    sent_mb = 0.0
    while p.poll() is None:
        t = time.monotonic() - t0
        if t_handler is None and handler_installed(p.pid):
            t_handler = t
        if t_results is None and os.path.exists(os.path.join(out, "results.xdmf")):
            t_results = t
        if moment == "handler":
            due = t_handler is not None
        elif moment == "loading":
            due = resident_mb(p.pid) > SCENE_MB and t_results is None
        else:
            due = t >= moment
        if due and sent_at is None:
            sent_with_handler = handler_installed(p.pid)
            sent_mb = resident_mb(p.pid)
            sent_at = t
            p.send_signal(signal.SIGINT)
        if sent_at is not None:
            break
        time.sleep(0.0005)
    # Keep watching the set-up times while the process finishes.
    while p.poll() is None:
        t = time.monotonic() - t0
        if t_results is None and os.path.exists(os.path.join(out, "results.xdmf")):
            t_results = t
        if t > (sent_at or 0) + 120:
            p.kill()
            break
        time.sleep(0.002)
    rc = p.wait()
    log.close()
    text = open(out + ".log").read()
    failures = []
    what = f"{label}: SIGINT at {sent_at if sent_at is not None else -1:.3f} s, handler at " + (
        f"{t_handler:.3f} s" if t_handler is not None else "-") + f", exit {rc}"
    if sent_at is None:
        failures.append(f"{what}: the run ended before the signal could be sent (make the run longer)")
        return what, failures, t_handler, t_results
    what += f" ({sent_mb:.0f} MB resident when sent)"
    if rc == -signal.SIGINT:
        if sent_with_handler:
            failures.append(f"{what}: killed by SIGINT although its handler was installed")
        elif sent_mb > LOADER_MB:
            failures.append(f"{what}: killed by SIGINT while loading the scene (no handler yet)")
        elif os.path.exists(out):
            failures.append(f"{what}: killed by SIGINT after it had started writing {out}")
        return what + ": killed, signal sent during the dynamic loader", failures, t_handler, t_results
    if rc != 130:
        failures.append(f"{what}: exit code {rc}, expected 130\n{text[-2000:]}")
        return what, failures, t_handler, t_results
    if "interrupted:" not in text:
        failures.append(f"{what}: no 'interrupted:' message\n{text[-2000:]}")
    try:
        import json

        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        if summary["stop_reason"] != "interrupted":
            failures.append(f"{what}: stop_reason {summary['stop_reason']}")
        if summary.get("state_file") != "interrupted_state.h5":
            failures.append(f"{what}: summary names no state file")
        with h5py.File(os.path.join(out, "interrupted_state.h5"), "r") as f:
            x = np.asarray(f["x"])
            if x.size == 0 or not np.all(np.isfinite(x)) or not np.all(np.isfinite(np.asarray(f["v"]))):
                failures.append(f"{what}: interrupted_state.h5 holds no finite state")
            step = int(f.attrs["step"])
        steps = summary["stats"].get("steps", summary["stats"].get("iterations"))
        if step != steps:
            failures.append(f"{what}: state at step {step}, summary says {steps}")
        what += f", state at step {step}"
        ET.parse(os.path.join(out, "results.xdmf"))
        with h5py.File(os.path.join(out, "results.h5"), "r"):
            pass
    except Exception as e:  # a missing or unreadable file
        failures.append(f"{what}: {type(e).__name__}: {e}")
    return what, failures, t_handler, t_results


def main():
    moments = [0.0, "handler", "loading", 0.6, 1.2, 2.0]
    failures, handler_times, results_times = [], [], []
    for r in range(REPEATS):
        for m in moments:
            label = f"explicit-{m}-{r}"
            what, f, th, tr = run_once(label, EXPLICIT, m)
            print(what, flush=True)
            failures += f
            if th is not None:
                handler_times.append(th)
            if tr is not None:
                results_times.append(tr)
        for m in [0.5, 1.0]:
            what, f, _, _ = run_once(f"relaxation-{m}-{r}", RELAXATION, m)
            print(what, flush=True)
            failures += f
    if handler_times and results_times:
        print(f"handler installed at {min(handler_times):.3f}-{max(handler_times):.3f} s, results file created at "
              f"{min(results_times):.3f}-{max(results_times):.3f} s after the start")
    if failures:
        print("\nFAILED:\n" + "\n".join(failures))
        return 1
    print("all interrupts honoured")
    return 0


if __name__ == "__main__":
    sys.exit(main())
