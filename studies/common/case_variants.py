"""Helpers of the studies that run a coupled case in several variants and tabulate them
(studies/ramair/ramair_resolutions.py, studies/sail/sail_knobs.py, studies/wing/wing_polar.py,
studies/ramair/trim_study.py): which variants
were asked for, the case's settings and structure.yaml with some values changed, a copy of the case run by its
Allrun, and why a run stopped early."""
import re
import shutil
import subprocess
import sys
import time


def settings_with(text, changes):
    """A settings file's text with `key value` lines replaced (a key not present is appended)."""
    lines = text.splitlines()
    for key, value in changes.items():
        pat = re.compile(rf"^{re.escape(key)}\s")
        hit = [i for i, l in enumerate(lines) if pat.match(l)]
        if hit:
            lines[hit[0]] = f"{key} {value}"
        else:
            lines.append(f"{key} {value}")
    return "\n".join(lines) + "\n"


def structure_with(text, changes, where="structure.yaml"):
    """structure.yaml's text with generator parameters replaced (`name: value` inside the generator's mapping);
    the key "+effect" adds its value as an entry of the scene's effects: mapping."""
    for key, value in changes.items():
        if key == "+effect":
            new, n = re.subn(r"^effects:\n", f"effects:\n  {value}\n", text, flags=re.M)
            if n != 1:
                sys.exit(f"{where}: {n} 'effects:' mappings, expected 1")
            text = new
            continue
        new, n = re.subn(rf"\b{re.escape(key)}: [0-9.e+-]+", f"{key}: {value}", text)
        if n != 1:
            sys.exit(f"{where}: {n} '{key}:' entries, expected 1")
        text = new
    return text


def run_copy(case, d, settings, structure, env, allrun="./Allrun.parallel"):
    """Copies the case folder to d (replacing d), writes d/run.settings (the case's coupled.settings with
    `settings` changed) and d/structure.yaml (with `structure` changed), runs `allrun -settings run.settings`
    with the build's environment `env` sourced, its output in d/Allrun.out (not log.*: Allrun takes those for an
    earlier run), and stores d/wall_seconds and d/exit_code (negative: a signal; stop_reason says so).
    Returns the exit code. The arguments are a list: nothing passes through a shell but the fixed source line."""
    if d.exists():
        shutil.rmtree(d)
    shutil.copytree(case, d)
    (d / "run.settings").write_text(settings_with((case / "coupled.settings").read_text(), settings))
    if structure:
        (d / "structure.yaml").write_text(structure_with((case / "structure.yaml").read_text(), structure,
                                                         str(case / "structure.yaml")))
    t0 = time.monotonic()
    with open(d / "Allrun.out", "w") as log:
        p = subprocess.run(["bash", "-c", f'. "$0" && exec {allrun} -settings run.settings', str(env)], cwd=d,
                           stdout=log, stderr=subprocess.STDOUT)
    (d / "wall_seconds").write_text(f"{time.monotonic() - t0:.1f}\n")
    (d / "exit_code").write_text(f"{p.returncode}\n")
    return p.returncode


def chosen(only, variants, prog):
    """The variant names of a comma-separated --only list, in its order; exits naming the valid ones."""
    names = [n for n in only.split(",") if n]
    for n in names:
        if n not in variants:
            sys.exit(f"{prog}: unknown variant '{n}'; valid: {', '.join(variants)}")
    return names


def stop_reason(d):
    """Why a run in folder d ended early: a signal (the exit code run_variant stored in d/exit_code), Allrun's
    remesh_max stop, or the mesh guard's or OpenFOAM's first fatal line in log.pimpleFoam; with the new meshes
    the run had made by then (Allrun.out's "New mesh" lines, the windows from structure/remesh.N/request)."""
    allrun = d / "Allrun.out"
    allrun_text = allrun.read_text(errors="replace") if allrun.exists() else ""
    code = (d / "exit_code").read_text().strip() if (d / "exit_code").exists() else ""
    capped = re.search(r"Allrun: remesh_max (\d+) reached: .* asks for another at t = ([0-9.e+-]+) s", allrun_text)
    if code.startswith("-"):
        reason = f"stopped by signal {code[1:]}"
    elif capped:
        reason = f"remesh_max {capped.group(1)} reached at t = {float(capped.group(2)):.3f} s"
    else:
        reason = _fluid_stop(d)
    meshes = re.findall(r"^New mesh (\d+) at t = ([0-9.e+-]+) s", allrun_text, re.M)
    if not meshes:
        return reason
    windows = []
    for n, _ in meshes:
        req = d / "structure" / f"remesh.{n}" / "request"
        hit = re.search(r"^window (\d+)", req.read_text(), re.M) if req.exists() else None
        if not hit:  # the request of the mesh being made when the run stopped has not been moved yet
            req = d / "structure" / "remesh" / "request"
            hit = re.search(r"^window (\d+)", req.read_text(), re.M) if req.exists() else None
        windows.append(int(hit.group(1)) if hit else None)
    k, (t0, t1) = len(meshes), (float(meshes[0][1]), float(meshes[-1][1]))
    span = (f"windows {windows[0]}–{windows[-1]}" if k > 1 else f"window {windows[0]}") if None not in windows else ""
    when = f"t = {t0:.3f}–{t1:.3f} s" if k > 1 else f"t = {t0:.3f} s"
    return f"{reason}, after {k} new mesh{'es' if k > 1 else ''} ({', '.join(x for x in (span, when) if x)})"


def _fluid_stop(d):
    """The mesh guard's or OpenFOAM's first fatal line in d/log.pimpleFoam."""
    log = d / "log.pimpleFoam"
    text = log.read_text(errors="replace") if log.exists() else ""
    hit = re.search(r"mesh guard: t = ([0-9.e+-]+) s, window (\d+)", text)
    if hit:
        cell = re.search(r"Worst cell: \d+(?: on rank \d+)? at \(([^)]*)\)", text)
        where = f" next to ({', '.join(f'{float(v):.2f}' for v in cell.group(1).split())})" if cell else ""
        return f"mesh guard stop in window {hit.group(2)} (t = {float(hit.group(1)):.3f} s){where}"
    hit = re.search(r"FOAM FATAL[^\n]*\n([^\n]*)", text)
    if hit:
        return f"failed: {hit.group(1).strip()[:80]}"
    if "sigFpe::sigHandler" in text:
        times = re.findall(r"^Time = ([0-9.e+-]+)", text, re.M)
        return "floating-point exception in the fluid solve" + (f" (t = {float(times[-1]):.3f} s)" if times else "")
    return "failed (see Allrun.out)"
