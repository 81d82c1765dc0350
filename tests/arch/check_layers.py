#!/usr/bin/env python3
"""Include-layer check (ctest `arch.layers`, label `arch`; docs/ARCHITECTURE.md "Layers").

Reads every `#include "<lib>/..."` in structure/, coupling/, adapter/ and apps/ and checks two rules:

  libraries   structure <- coupling <- adapter <- apps and structure <- flight <- apps: a library includes
              only itself and the libraries USES lists for it.
  structure/  the folders of structure/ in the order of STRUCTURE_LAYERS below (lowest first): a folder
              includes only itself and the folders before it.

Every include against a rule is printed as `file:line: includes "path": rule` and the check fails (exit 1),
unless the include is in ALLOWED (known violations, each with its reason, to be removed). An ALLOWED entry
that no longer matches an include fails the check too, so the list only shrinks.

Usage: check_layers.py [SOURCE_DIR]   (default: the repository this script is in)
"""

import os
import re
import sys

LIBRARIES = ["structure", "flight", "coupling", "adapter", "apps"]
# What each library may include besides itself: structure <- coupling <- adapter, structure <- flight; apps
# on top of all.
USES = {
    "structure": [],
    "flight": ["structure"],
    "coupling": ["structure"],
    "adapter": ["structure", "coupling"],
    "apps": ["structure", "flight", "coupling", "adapter"],
}

# The layers inside structure/, lowest first. What each is (docs/ARCHITECTURE.md "Layers"):
STRUCTURE_LAYERS = [
    "model",  # the data (Nodes, MeshData, Model and its blocks), errors, numbers: depends on nothing
    "material",  # constitutive laws and the material types' registry
    "effects",  # Effect (the force-term interface), loads, drag, bending, threaded force evaluation
    "elements",  # the element kinds (ElementKind, its registry) and their kernels
    "integrate",  # central difference, dynamic relaxation, constraints, energy ledger, state snapshots
    "io",  # results writers, state files, mesh readers
    "probes",  # run-time measurements of a model
    "scene",  # the YAML scene: reading, resolving sets, building a Model and its run controls
    "parafoil",  # the `parafoil` generator (a scene generator: registers itself with scene/)
    "roundcanopy",  # the round canopy's constructed shape (the `round_canopy` generator: registers with scene/)
    "run",  # Simulation, the run loops, stop reasons, diagnosis, summaries
]

# Known violations, (including file, included path) -> reason (none left: issue 36 item 2 removed the last).
# The check fails on any violation not listed here, and on an entry that no longer matches an include.
ALLOWED = {
}

INCLUDE = re.compile(r'^\s*#\s*include\s*"((structure|flight|coupling|adapter|apps)/[^"]+)"')
SOURCE_EXT = (".hpp", ".cpp", ".h", ".H", ".C")


def library_of(path):
    top = path.split("/", 1)[0]
    return top if top in LIBRARIES else None


def structure_layer(path):
    parts = path.split("/")
    if len(parts) < 3 or parts[0] != "structure":
        return None
    return parts[1]


def check_include(source, target):
    """The rule `source` including `target` breaks, or None."""
    lib_s, lib_t = library_of(source), library_of(target)
    if lib_t != lib_s and lib_t not in USES[lib_s]:
        return f"library {lib_s}/ may include only {', '.join(USES[lib_s]) or 'itself'}, not {lib_t}/"
    if lib_s == lib_t == "structure":
        a, b = structure_layer(source), structure_layer(target)
        for layer in (a, b):
            if layer not in STRUCTURE_LAYERS:
                return f"structure/{layer}/ is not in STRUCTURE_LAYERS (tests/arch/check_layers.py): place it"
        if STRUCTURE_LAYERS.index(b) > STRUCTURE_LAYERS.index(a):
            return f"structure/{a}/ may not include the higher layer structure/{b}/"
    return None


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    violations, allowed_seen, checked = [], set(), 0
    for lib in LIBRARIES:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, lib)):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith(SOURCE_EXT):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root).replace(os.sep, "/")
                with open(path, encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        checked += 1
                        target = m.group(1)
                        rule = check_include(rel, target)
                        if rule is None:
                            continue
                        if (rel, target) in ALLOWED:
                            allowed_seen.add((rel, target))
                            continue
                        violations.append(f'{rel}:{number}: includes "{target}": {rule}')
    stale = sorted(set(ALLOWED) - allowed_seen)
    for v in violations:
        print(v)
    for source, target in stale:
        print(f'{source}: ALLOWED lists its include of "{target}", which is gone or no longer a violation: '
              "remove the entry from tests/arch/check_layers.py")
    if violations or stale:
        print(f"check_layers: {len(violations)} include(s) against the layers, {len(stale)} stale allow-list "
              f"entr{'y' if len(stale) == 1 else 'ies'}. Libraries: structure <- coupling <- adapter <- apps, structure <- flight <- apps; inside structure/: "
              f"{' <- '.join(STRUCTURE_LAYERS)} (a layer includes only itself and those left of it; "
              "docs/ARCHITECTURE.md \"Layers\")")
        return 1
    print(f"check_layers: {checked} includes follow the layers ({len(ALLOWED)} allow-listed, issue 36 item 2)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
