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
    """Why a run ended early: the mesh guard's or OpenFOAM's first fatal line in log.pimpleFoam."""
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
