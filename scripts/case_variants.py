"""Helpers of the scripts that run a coupled case in several variants and tabulate them
(ramair_resolutions.py, sail_knobs.py): which variants were asked for, and why a run stopped early."""
import re
import sys


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
