#!/usr/bin/python3
"""Ctrl-C and SIGTERM at the command line: `fsi run` gets SIGINT at several moments of a run that takes a few
seconds — at once, as soon as the handler exists, during scene loading and set-up, during the step loop, and
during a dynamic relaxation — several times each, so that a race shows; and SIGTERM (kill, a batch system's
time limit) at most of the same moments.

Expected every time: exit code 130 for SIGINT, 143 for SIGTERM (not death by the signal), summary.json with
stop_reason "interrupted" and stop_signal naming the signal, an interrupted_state.h5 with a finite state, and
results.xdmf / results.h5 closed cleanly. The only signals that may kill the process are those sent while the
dynamic loader still maps the shared libraries, before the program's handler exists (read from
/proc/PID/status) and before it allocates anything for the scene (its resident memory is then that of the
libraries, under LOADER_MB). The "loading" moment sends the signal while the scene's model is being built
(resident memory above SCENE_MB, no results file yet).

Then the continuation: a run with an end time stopped by SIGTERM part way and continued with `fsi run SCENE
--out DIR --start-from DIR/interrupted_state.h5` ends as the run that was never stopped — probes and final
positions to 1e-12 relative (measured: bit for bit) — with one results series in DIR.

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


def handler_installed(pid, sig=signal.SIGINT):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) & (1 << (sig - 1)))
    except OSError:
        pass
    return False


def resident_mb(pid):
    try:
        with open(f"/proc/{pid}/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 1e6
    except OSError:
        return 0.0


def run_once(label, args, moment, sig=signal.SIGINT):
    """Starts `fsi run`, sends `sig` at `moment` (seconds after the start, "handler" as soon as the handler is
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
        if t_handler is None and handler_installed(p.pid, sig):
            t_handler = t
        if t_results is None and os.path.exists(os.path.join(out, "results.xdmf")):
            t_results = t
        if moment == "handler":
            due = t_handler is not None
        elif isinstance(moment, tuple):  # ("stepping", s): s seconds after the first frame (the step loop's start)
            due = t_results is not None and t >= t_results + moment[1]
        elif moment == "loading":
            due = resident_mb(p.pid) > SCENE_MB and t_results is None
        else:
            due = t >= moment
        if due and sent_at is None:
            sent_with_handler = handler_installed(p.pid, sig)
            sent_mb = resident_mb(p.pid)
            sent_at = t
            p.send_signal(sig)
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
    name = signal.Signals(sig).name
    what = f"{label}: {name} at {sent_at if sent_at is not None else -1:.3f} s, handler at " + (
        f"{t_handler:.3f} s" if t_handler is not None else "-") + f", exit {rc}"
    if sent_at is None:
        failures.append(f"{what}: the run ended before the signal could be sent (make the run longer)")
        return what, failures, t_handler, t_results
    what += f" ({sent_mb:.0f} MB resident when sent)"
    if rc == -sig:
        if sent_with_handler:
            failures.append(f"{what}: killed by {name} although its handler was installed")
        elif sent_mb > LOADER_MB:
            failures.append(f"{what}: killed by {name} while loading the scene (no handler yet)")
        elif os.path.exists(out):
            failures.append(f"{what}: killed by {name} after it had started writing {out}")
        return what + ": killed, signal sent during the dynamic loader", failures, t_handler, t_results
    if rc != 128 + sig:
        failures.append(f"{what}: exit code {rc}, expected {128 + sig}\n{text[-2000:]}")
        return what, failures, t_handler, t_results
    if f"interrupted ({name}):" not in text:
        failures.append(f"{what}: no 'interrupted ({name}):' message\n{text[-2000:]}")
    try:
        import json

        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        if summary["stop_reason"] != "interrupted":
            failures.append(f"{what}: stop_reason {summary['stop_reason']}")
        if summary.get("stop_signal") != name:
            failures.append(f"{what}: stop_signal {summary.get('stop_signal')}, expected {name}")
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


def continuation():
    """SIGTERM part way through a run with an end time, then --start-from its interrupted_state.h5 into the same
    directory: the same end as a run never stopped. Returns the failures."""
    failures = []
    scene = os.path.join(WORK, "hencky-end.yaml")
    text = open(HENCKY).read()
    text = text.replace("rings: 16", "rings: 60").replace("interval: 0.005", "interval: 0.001")
    text = text.replace("until_static: {tolerance: 1.0e-10, max_time: 0.5}", "end: 0.02")
    with open(scene, "w") as f:
        f.write(text)
    whole, part = os.path.join(WORK, "whole"), os.path.join(WORK, "continued")
    shutil.rmtree(part, ignore_errors=True)
    p = subprocess.run([FSI, "run", scene, "--out", whole, "--quiet"], capture_output=True, text=True)
    if p.returncode != 0:
        return [f"continuation: the uninterrupted run exits {p.returncode}\n{p.stderr[-2000:]}"]
    # 0.3 s into the step loop (a fixed moment after the start missed it on an idle machine: the run had ended)
    what, f, _, _ = run_once("continued", [scene, "--quiet"], ("stepping", 0.3), signal.SIGTERM)
    print(what, flush=True)
    if f or not os.path.exists(os.path.join(part, "interrupted_state.h5")):
        return f or [f"{what}: no interrupted_state.h5 to continue from"]
    p = subprocess.run([FSI, "run", scene, "--out", part, "--start-from", os.path.join(part, "interrupted_state.h5")],
                       capture_output=True, text=True)
    print(f"continued: exit {p.returncode}: {p.stdout.splitlines()[0] if p.stdout else p.stderr.strip()}")
    if p.returncode != 0:
        return [f"continuation: --start-from interrupted_state.h5 exits {p.returncode}\n{p.stderr[-2000:]}"]
    import json

    a, b = (json.load(open(os.path.join(d, "summary.json"))) for d in (whole, part))
    if b.get("start_from", {}).get("kind") != "explicit_state":
        failures.append(f"continuation: summary start_from {b.get('start_from')}")
    for k, v in a["probes"].items():
        if abs(b["probes"][k] - v) > 1e-12 * abs(v):
            failures.append(f"continuation: probe {k} {b['probes'][k]!r}, uninterrupted {v!r} (1e-12)")
    if b["stats"]["steps"] != a["stats"]["steps"]:
        failures.append(f"continuation: {b['stats']['steps']} steps in all, uninterrupted {a['stats']['steps']}")
    with h5py.File(os.path.join(whole, "results.h5"), "r") as fa, h5py.File(os.path.join(part, "results.h5"), "r") as fb:
        ta = [float(fa["steps"][k].attrs["time"]) for k in fa["steps"]]
        tb = [float(fb["steps"][k].attrs["time"]) for k in fb["steps"]]
        if not set(ta) <= set(tb) or tb != sorted(tb):
            failures.append(f"continuation: frames at {tb}, uninterrupted {ta}")
        xa = np.asarray(fa["steps"][sorted(fa["steps"])[-1]]["coordinates"])
        xb = np.asarray(fb["steps"][sorted(fb["steps"])[-1]]["coordinates"])
        dev = float(np.abs(xa - xb).max())
        scale = float(np.abs(np.asarray(fa["steps"][sorted(fa["steps"])[-1]]["displacement"])).max())
        print(f"continued: final positions {dev:.3g} m from the uninterrupted run's (largest displacement "
              f"{scale:.3g} m)")
        if not dev <= 1e-12 * scale:
            failures.append(f"continuation: final positions differ by {dev:.3g} m (1e-12 x {scale:.3g} m)")
    return failures


def main():
    moments = [0.0, "handler", "loading", 0.6, 1.2, 2.0]
    failures, handler_times, results_times = [], [], []
    for r in range(REPEATS):
        for sig, ms in ((signal.SIGINT, moments), (signal.SIGTERM, [0.0, "handler", "loading", 1.2])):
            for m in ms:
                label = f"explicit-{signal.Signals(sig).name}-{m}-{r}"
                what, f, th, tr = run_once(label, EXPLICIT, m, sig)
                print(what, flush=True)
                failures += f
                if th is not None:
                    handler_times.append(th)
                if tr is not None:
                    results_times.append(tr)
        for sig, m in ((signal.SIGINT, 0.5), (signal.SIGINT, 1.0), (signal.SIGTERM, 0.7)):
            what, f, _, _ = run_once(f"relaxation-{signal.Signals(sig).name}-{m}-{r}", RELAXATION, m, sig)
            print(what, flush=True)
            failures += f
    failures += continuation()
    if handler_times and results_times:
        print(f"handler installed at {min(handler_times):.3f}-{max(handler_times):.3f} s, results file created at "
              f"{min(results_times):.3f}-{max(results_times):.3f} s after the start")
    if failures:
        print("\nFAILED:\n" + "\n".join(failures))
        return 1
    print("all interrupts honoured, the continued run ends as the uninterrupted one")
    return 0


if __name__ == "__main__":
    sys.exit(main())
