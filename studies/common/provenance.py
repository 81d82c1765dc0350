"""Where and from what a study's numbers were measured, as the stored results state it: the machine line and
the commit. Shared by the studies that store rows with their provenance (studies/cost/accuracy_cost.py,
studies/sail/sail_knobs.py, studies/ramair/ramair_resolutions.py, studies/ramair/trim_study.py), so that none
of them imports another study for it."""
import os
import platform
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def machine():
    cpu = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    osname = platform.system()
    try:
        for line in Path("/etc/os-release").read_text().splitlines():
            if line.startswith("PRETTY_NAME="):
                osname = line.split("=", 1)[1].strip('"')
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores ({osname}, Python {platform.python_version()})"


def git_commit():
    try:
        c = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                           check=True).stdout.strip()
        # accuracy_cost.py's own outputs do not count as changes to what was measured.
        dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no", "--", ".",
                                ":!docs/ACCURACY_COST.md", ":!docs/img/accuracy_cost_*.png"],
                               capture_output=True, text=True).stdout.strip()
        return c + (" with local changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
