#!/usr/bin/env python3
"""Draws the house and its layers (docs/img/architecture.png, docs/ARCHITECTURE.md "Layers") from the tree.

Every box is a folder (a library, or a layer of structure/ in check_layers.STRUCTURE_LAYERS order, lowest at
the bottom) with its file and line counts; every arrow is the number of `#include "lib/..."` lines from one
box into another (the includer points at what it uses). Arrows only point down or left when the layers hold,
which ctest `arch.layers` checks; an arrow against them is drawn red.

Usage: /usr/bin/python3 tests/arch/draw_architecture.py [OUT.png]   (default docs/img/architecture.png)
"""

import collections
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches as patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_layers  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ROLES = {
    "model": "Nodes, MeshData, Model blocks, errors",
    "material": "constitutive laws, material registry",
    "effects": "Effect: loads, drag, bending, threads",
    "elements": "element kinds and their kernels",
    "integrate": "central difference, relaxation, constraints",
    "io": "results (HDF5+XDMF), state files, mesh readers",
    "probes": "run-time measurements",
    "scene": "YAML scene -> Model + run controls",
    "parafoil": "the parafoil generator",
    "roundcanopy": "the round canopy's constructed shape",
    "run": "Simulation, run loops, stop, summaries",
    "coupling": "interface, mapping, schemes, accelerations",
    "adapter": "OpenFOAM function object (libfsiFoam)",
    "apps": "the fsi command line",
    "flight": "parafoil-payload flight: 6 DOF, tables, wind",
}


def unit_of(rel):
    """The box a source path belongs to: a structure/ layer or a library."""
    parts = rel.split("/")
    if parts[0] == "structure" and len(parts) > 2:
        return parts[1]
    return parts[0]


def scan():
    files, lines, edges = collections.Counter(), collections.Counter(), collections.Counter()
    for lib in check_layers.LIBRARIES:
        for dirpath, dirnames, filenames in os.walk(os.path.join(ROOT, lib)):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith(check_layers.SOURCE_EXT):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, name), ROOT).replace(os.sep, "/")
                src = unit_of(rel)
                files[src] += 1
                with open(os.path.join(dirpath, name), encoding="utf-8", errors="replace") as f:
                    for line in f:
                        lines[src] += 1
                        m = check_layers.INCLUDE.match(line)
                        if m and unit_of(m.group(1)) != src:
                            edges[(src, unit_of(m.group(1)), check_layers.check_include(rel, m.group(1)) is None)] += 1
    return files, lines, edges


def main(argv):
    out = argv[1] if len(argv) > 1 else os.path.join(ROOT, "docs", "img", "architecture.png")
    files, lines, edges = scan()
    layers = check_layers.STRUCTURE_LAYERS
    box_w, box_h, gap = 4.3, 0.62, 0.18
    pos = {}
    for i, layer in enumerate(layers):  # structure/: a column, lowest layer at the bottom
        pos[layer] = (0.0, i * (box_h + gap))
    top = (len(layers) - 1) * (box_h + gap)
    for j, lib in enumerate(["coupling", "adapter", "apps"]):  # the libraries above structure, to its right
        pos[lib] = (box_w + 1.8 + j * (box_w + 0.9), top * (0.12 + 0.36 * j))
    pos["flight"] = (box_w + 1.8, top * 0.86)  # beside coupling: uses structure only
    fig, ax = plt.subplots(figsize=(16, 8.5))
    ax.add_patch(patches.FancyBboxPatch((-0.25, -0.3), box_w + 0.5, top + box_h + 0.75, boxstyle="round,pad=0.02",
                                        fc="#f4f6fa", ec="#5a6b8c", lw=1.5))
    ax.text(box_w / 2, top + box_h + 0.22, "structure/  (fsi_structure)", ha="center", fontsize=12, weight="bold")
    for unit, (x, y) in pos.items():
        lib = unit in check_layers.LIBRARIES
        ax.add_patch(patches.FancyBboxPatch((x, y), box_w, box_h, boxstyle="round,pad=0.02",
                                            fc="#dde7f7" if lib else "white", ec="#34495e", lw=1.2))
        title = f"{unit}/" if lib else f"structure/{unit}/"
        ax.text(x + 0.08, y + box_h - 0.2, f"{title}   {files[unit]} files, {lines[unit]:,} lines", fontsize=9,
                weight="bold", va="center")
        ax.text(x + 0.08, y + 0.18, ROLES.get(unit, ""), fontsize=8.5, va="center", color="#333")

    def anchor(unit, toward):
        x, y = pos[unit]
        tx, ty = pos[toward]
        if unit in layers and toward in layers:  # inside the column: arrows on the right edge, bowed
            return (x + box_w, y + box_h / 2)
        return (x + (box_w if tx > x else 0.0), y + box_h / 2) if tx != x else (x + box_w / 2, y)

    # library-to-library edges: structure layers collapse into "structure"
    lib_edges = collections.Counter()
    for (src, dst, ok), n in edges.items():
        s = "structure" if src in layers else src
        d = "structure" if dst in layers else dst
        if s != d:
            lib_edges[(s, d, ok)] += n
        elif s == "structure":
            i, j = layers.index(src), layers.index(dst)
            xa, ya = anchor(src, dst)
            xb, yb = anchor(dst, src)
            ax.annotate("", xy=(xb, yb), xytext=(xa, ya),
                        arrowprops=dict(arrowstyle="->", color="#27ae60" if ok else "#c0392b",
                                        lw=0.6 + 0.12 * min(n, 20), alpha=0.75,
                                        connectionstyle=f"arc3,rad={-0.12 - 0.04 * abs(i - j)}"))
    structure_mid = (box_w, top / 2 + box_h / 2)
    for (s, d, ok), n in sorted(lib_edges.items()):
        xa, ya = (pos[s][0], pos[s][1] + box_h / 2) if s != "structure" else structure_mid
        if d == "structure":
            xb, yb = structure_mid
        else:
            xb, yb = pos[d][0] + (box_w if pos[d][0] < xa else 0), pos[d][1] + box_h / 2
        ax.annotate("", xy=(xb, yb), xytext=(xa, ya),
                    arrowprops=dict(arrowstyle="->", color="#27ae60" if ok else "#c0392b",
                                    lw=0.8 + 0.05 * min(n, 60), alpha=0.8, connectionstyle="arc3,rad=0.08"))
        ax.text(0.35 * xa + 0.65 * xb, 0.35 * ya + 0.65 * yb + 0.12, str(n), fontsize=8, color="#1e6b3a" if ok else "#c0392b",
                ha="center")
    against = sum(n for (_, _, ok), n in edges.items() if not ok)
    ax.text(pos["coupling"][0], -0.2,
            "arrow: #include lines from a folder into another (the includer points at what it uses)\n"
            "green: with the layers (a folder uses only itself and those below / to its left); "
            f"red: against them ({against} now, allow-listed in tests/arch/check_layers.py)\n"
            "libraries: structure <- coupling <- adapter <- apps, structure <- flight <- apps;  checked by ctest arch.layers",
            fontsize=8.5, va="bottom")
    ax.set_xlim(-0.5, pos["apps"][0] + box_w + 0.3)
    ax.set_ylim(-0.5, top + box_h + 0.7)
    ax.axis("off")
    ax.set_title("The house: libraries and the layers of structure/ (generated by tests/arch/draw_architecture.py)",
                 fontsize=12)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=110)
    print(f"draw_architecture: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
