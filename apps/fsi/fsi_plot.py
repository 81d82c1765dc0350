#!/usr/bin/python3
"""fsi plot: PNG plots of a run's outputs. Called by `fsi plot RUN_DIR [--out DIR] [--color auto|stress|displacement]`
(apps/fsi/main.cpp execs it with Debian's /usr/bin/python3); it can also be run directly.

RUN_DIR is one of
  a structure run  (`fsi run SCENE --out DIR`): DIR/results.h5 with /tables/energy and /tables/probes (or
                   /tables/residual for dynamic relaxation) and the output frames, DIR/summary.json;
  a coupled case   (an OpenFOAM case run with the fsiCoupling function object): CASE/structure/coupling.csv,
                   CASE/structure/results.h5, CASE/structure/timing.json.
Writes into OUT (default RUN_DIR/plots) one PNG per view and index.json, which lists every PNG with its title
and the series it shows with their number of points (what the tests check).

Exit codes: 0 written; 2 bad input (RUN_DIR is neither kind, or a file in it cannot be read; the message
names the file and what is missing); 1 the Python modules are missing.
"""

import argparse
import json
import math
import os
import re
import sys
import textwrap


class InputError(Exception):
    """A problem with the run folder the user can fix; reported with exit code 2."""


def warn(msg):
    print(f"warning: {msg}", file=sys.stderr)


np = matplotlib = plt = h5py = yaml = Line3DCollection = Poly3DCollection = None


def load_modules():
    """Imports numpy, matplotlib (Agg) and h5py: after the cheap checks of the run folder, which then answer
    at once (matplotlib takes seconds to import)."""
    global np, matplotlib, plt, h5py, yaml, Line3DCollection, Poly3DCollection
    try:
        import numpy as np
        import matplotlib

        matplotlib.use("Agg")  # files only, no display
        import matplotlib.pyplot as plt
        from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection
        import h5py
    except ImportError as e:  # depends on the machine
        print(f"error: fsi plot needs numpy, matplotlib and h5py for /usr/bin/python3 ({e}); on Debian: "
              "apt-get install python3-numpy python3-matplotlib python3-h5py", file=sys.stderr)
        sys.exit(1)
    try:
        import yaml  # only for the scene's title and probe units; optional
    except ImportError:
        yaml = None
    # Readable at 100 %: one font size for everything, light grid.
    plt.rcParams.update({"font.size": 10, "axes.grid": True, "grid.alpha": 0.3, "legend.fontsize": 9,
                         "figure.dpi": 110, "savefig.dpi": 110})


PROBE_UNITS = {"displacement": "m", "position": "m", "reaction": "N", "volume": "m³", "stress": "Pa",
               "line_tension": "N", "applied_load": "N", "reaction_moment": "N m", "pitch_angle": "deg",
               "equilibrium_error": "-"}
COUPLING_FIXED = ["time", "iterations", "converged", "residual", "Fx_fluid", "Fy_fluid", "Fz_fluid",
                  "Fx_structure", "Fy_structure", "Fz_structure"]


# ---------------------------------------------------------------------------------------------------------
# Index of what was plotted


class Index:
    def __init__(self, kind, run_dir, out_dir):
        self.data = {"kind": kind, "run_dir": os.path.abspath(run_dir), "plots": []}
        self.out_dir = out_dir

    def save(self, fig, name, title, series, **extra):
        """Writes fig to OUT/name and records it; series: list of (label, number of points)."""
        path = os.path.join(self.out_dir, name)
        make_dir(self.out_dir)
        fig.savefig(path)
        plt.close(fig)
        entry = {"file": name, "title": title, "series": []}
        for s in series:  # (name, points) or (name, points, values <= 0 a log axis could not draw)
            entry["series"].append({"name": s[0], "points": int(s[1])})
            if len(s) > 2 and s[2]:
                entry["series"][-1]["not_drawn_nonpositive"] = int(s[2])
        entry.update(extra)
        self.data["plots"].append(entry)
        print(f"wrote {path}")

    def write(self):
        path = os.path.join(self.out_dir, "index.json")
        with open(path, "w") as f:
            json.dump(self.data, f, indent=2)
            f.write("\n")
        print(f"wrote {path}")


# ---------------------------------------------------------------------------------------------------------
# Helpers


def scaled_unit(values, unit):
    """(factor, label) so that values*factor reads in k/M/G of unit when they are large."""
    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    peak = float(np.max(np.abs(finite))) if finite.size else 0.0
    for factor, prefix in ((1e-9, "G"), (1e-6, "M"), (1e-3, "k")):
        if peak >= 1.0 / factor:
            return factor, prefix + unit
    return 1.0, unit


def make_dir(path):
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as e:
        raise InputError(f"{path}: cannot create ({e})")


def heading(what, title):
    """`what` and the run's title, wrapped so that a long scene title stays inside the figure."""
    return "\n".join([what] + textwrap.wrap(title, 80))


def marker_for(n):
    return "o" if n <= 40 else None


def log_panel(ax, t, v, color, when_empty):
    """v > 0 against t on a log axis; the number of values it could not draw (<= 0). Without any positive
    value the panel says `when_empty` instead."""
    ok = v > 0
    if ok.all():
        ax.semilogy(t, v, color=color, marker=marker_for(len(t)), markersize=3)
    elif ok.any():  # points only: a line would suggest values across the gaps
        ax.semilogy(t[ok], v[ok], ".", color=color, markersize=4)
    else:
        ax.set_yticks([])
        ax.text(0.5, 0.5, when_empty, transform=ax.transAxes, ha="center", va="center")
    return int((~ok).sum())


def mark_restarts(ax, restarts, label=True):
    for i, (t, text) in enumerate(restarts):
        ax.axvline(t, color="tab:red", linestyle=":", linewidth=1.2,
                   label=(f"restart (t = {t:g} s)" if label and i == 0 else None))


def read_h5(path):
    try:
        return h5py.File(path, "r")
    except OSError as e:
        raise InputError(f"{path}: cannot be read as HDF5 ({e})")


def read_table(h5, name, path):
    """Columns of /tables/<name> as {column: array}, or None when the table is absent."""
    group = h5.get(f"tables/{name}")
    if group is None:
        return None
    cols = {k: np.asarray(group[k][()], dtype=float) for k in group.keys()}
    lengths = {len(v) for v in cols.values()}
    if len(lengths) > 1:
        raise InputError(f"{path}: /tables/{name} has columns of different lengths {sorted(lengths)}")
    return cols


def scene_info(scene_path):
    """(title, {probe: unit}) from the scene file; ('', {}) when it cannot be read (best effort: it only
    costs the title and the units)."""
    if yaml is None or not scene_path or not os.path.isfile(scene_path):
        return "", {}
    try:
        with open(scene_path) as f:
            scene = yaml.safe_load(f)
        probes = scene.get("probes", {}) or {}
        units = {name: PROBE_UNITS.get((p or {}).get("type"), "") for name, p in probes.items()}
        return str(scene.get("title", "") or ""), units
    except Exception:
        return "", {}


# ---------------------------------------------------------------------------------------------------------
# Time series


def plot_energy(index, energy, title):
    t = energy["time"]
    n = len(t)
    # D = α-damping dissipation + viscous dissipation (internal work not stored as strain energy).
    dissipation = energy["mass_damping"] + energy["internal_work"] - energy["strain"]
    lines = [("kinetic", energy["kinetic"], "kinetic energy"),
             ("strain", energy["strain"], "strain energy"),
             ("external_work", energy["external_work"], "external work"),
             ("internal_work", energy["internal_work"], "internal work"),
             ("dissipation", dissipation, "dissipation (damping + viscous)")]
    factor, unit = scaled_unit(np.concatenate([v for _, v, _ in lines]), "J")
    fig, (ax, axe) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, height_ratios=[3, 1.4],
                                  layout="constrained")
    for (_, v, label), style in zip(lines, ["-", "-", "--", "-.", ":"]):
        ax.plot(t, v * factor, style, marker=marker_for(n), markersize=3, label=label)
    ax.set_ylabel(f"energy [{unit}]")
    ax.set_title(heading("Energies", title))
    top = max(float(np.nanmax(np.concatenate([v for _, v, _ in lines]))) * factor, 1e-30)
    ax.set_ylim(top=top * 1.3)  # room for the legend above the curves
    ax.legend(loc="upper center", ncol=3)
    skipped = log_panel(axe, t, energy["balance_error"], "tab:purple", "0 at every check")
    axe.set_ylabel("balance error [–]")
    axe.set_xlabel("time [s]")
    axe.set_title("|W_ext + KE₀ − KE − W_int − D| / largest energy", fontsize=9)
    series = [(name, n) for name, _, _ in lines] + [("balance_error", n, skipped)]
    index.save(fig, "energy.png", "energies vs time", series)


def plot_probe_panels(index, t, probes, units, title, restarts=(), file="probes.png"):
    """One panel per probe against time; probes: {name: values}."""
    names = list(probes)
    ncol = 1 if len(names) <= 4 else 2
    nrow = math.ceil(len(names) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(8 if ncol == 1 else 12, 1.2 + 2.2 * nrow), sharex=True,
                             squeeze=False, layout="constrained")
    for k, name in enumerate(names):
        ax = axes[k // ncol][k % ncol]
        v = probes[name]
        unit = units.get(name, "")
        factor, unit = scaled_unit(v, unit) if unit in ("Pa", "N") else (1.0, unit)
        ax.plot(t, v * factor, marker=marker_for(len(t)), markersize=3, color=f"C{k % 10}")
        ax.set_title(name)
        ax.set_ylabel(f"{name} [{unit}]" if unit else name)
        mark_restarts(ax, restarts, label=(k == 0))
        if restarts and k == 0:
            ax.legend(loc="best")
    for k in range(len(names), nrow * ncol):
        axes[k // ncol][k % ncol].set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    fig.suptitle(heading("Probes", title))
    index.save(fig, file, "probe histories", [(name, len(probes[name])) for name in names])


def plot_relaxation(index, residual, title):
    it = residual["iteration"]
    n = len(it)
    fig, ax = plt.subplots(figsize=(8, 5), layout="constrained")
    skipped = {}
    for key, label in (("residual_ratio", "residual ratio |R| / |F_ext|"), ("energy_ratio", "KE / U")):
        v = residual[key]
        ok = v > 0
        skipped[key] = int((~ok).sum())
        ax.semilogy(it[ok], v[ok], marker=marker_for(n), markersize=3, label=label)
    ax.set_xlabel("iteration [–]")
    ax.set_ylabel("ratio [–]")
    ax.set_title(heading("Dynamic relaxation convergence", title))
    ax.legend(loc="best")
    index.save(fig, "relaxation.png", "dynamic relaxation convergence",
               [("residual_ratio", n, skipped["residual_ratio"]), ("energy_ratio", n, skipped["energy_ratio"])])


# ---------------------------------------------------------------------------------------------------------
# The structure's last frame


def last_frame(h5, path):
    steps = h5.get("steps")
    if steps is None or len(steps) == 0:
        return None
    name = sorted(steps.keys())[-1]
    g = steps[name]
    if "coordinates" not in g:
        raise InputError(f"{path}: /steps/{name} has no coordinates")
    return name, g, sorted(steps.keys())[0]


def plot_structure(index, h5, path, title, color):
    frame = last_frame(h5, path)
    if frame is None:
        warn(f"{path}: no output frame (/steps is empty): no structure picture")
        return
    name, g, first = frame
    x = np.asarray(g["coordinates"][()], dtype=float)
    x0 = np.asarray(h5["steps"][first]["coordinates"][()], dtype=float)
    tris = np.asarray(h5["mesh/triangles"][()], dtype=int).reshape(-1, 3) if "mesh/triangles" in h5 else \
        np.zeros((0, 3), int)
    lines = np.asarray(h5["mesh/lines"][()], dtype=int).reshape(-1, 2) if "mesh/lines" in h5 else \
        np.zeros((0, 2), int)
    time = float(g.attrs.get("time", float("nan")))
    step = int(g.attrs.get("step", -1))

    # Colour of the triangles: major principal stress [Pa] or displacement magnitude [m] (node values averaged).
    values, label = None, None
    if color in ("auto", "stress") and "principal_stress_major" in g:
        values, label, unit = np.asarray(g["principal_stress_major"][()], float).ravel(), \
            "major principal stress", "Pa"
    elif color == "stress":
        warn(f"{path}: /steps/{name} has no principal_stress_major (add principal_stress to the scene's "
             "output fields); colouring by displacement")
    if values is None and len(tris):
        if "displacement" in g:
            u = np.asarray(g["displacement"][()], float).reshape(-1, 3)
        else:  # displacement not written: relative to the first frame
            u = x - x0
        mag = np.linalg.norm(u, axis=1)
        values, label, unit = mag[tris].mean(axis=1), "displacement magnitude", "m"
    fig = plt.figure(figsize=(9, 7), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    pts = [x]
    if len(tris):
        edges = np.unique(np.sort(np.vstack([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1), axis=0)
        ax.add_collection3d(Line3DCollection(x0[edges], colors=[(0.5, 0.5, 0.5, 0.3)], linewidth=0.4))
        factor, unit_label = scaled_unit(values, unit) if unit == "Pa" else (1.0, unit)
        if unit == "m" and values.size and np.nanmax(values) < 0.1:
            factor, unit_label = 1e3, "mm"
        cmap = plt.get_cmap("viridis")
        v = values * factor
        # The colour range covers the 2nd to 98th percentile of the triangles: a few elements at a line
        # attachment or a rib (a point load's singular stress) would otherwise set the scale and leave the rest
        # of the skin one colour; the colour bar's arrows and its label give what lies beyond.
        lo, hi = (float(np.nanpercentile(v, 2)), float(np.nanpercentile(v, 98))) if v.size else (0.0, 1.0)
        vmin, vmax = (float(np.nanmin(v)), float(np.nanmax(v))) if v.size else (lo, hi)
        if not hi > lo:
            lo, hi = vmin, vmax if vmax > vmin else vmin + 1.0
        clipped = vmin < lo or vmax > hi
        extend = {(True, True): "both", (True, False): "min", (False, True): "max"}.get((vmin < lo, vmax > hi),
                                                                                        "neither")
        norm = matplotlib.colors.Normalize(lo, hi)
        surf = Poly3DCollection(x[tris], facecolors=cmap(norm(v)),
                                edgecolor=(0, 0, 0, 0.25) if len(tris) <= 4000 else "none", linewidth=0.3)
        ax.add_collection3d(surf)
        sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
        # colour bars on the right: below the axes they hid the x axis' label
        fig.colorbar(sm, ax=ax, location="right", shrink=0.6, pad=0.02, aspect=30, extend=extend,
                     label=f"{label} [{unit_label}]" + (f"\n(2nd-98th percentile; {vmin:.3g} to {vmax:.3g} in all)"
                                                         if clipped else ""))
    if len(lines):
        if "cable_force" in g:
            f = np.asarray(g["cable_force"][()], float).ravel()
            cfac, cunit = scaled_unit(f, "N")
            cnorm = matplotlib.colors.Normalize(float(np.min(f * cfac)), float(max(np.max(f * cfac),
                                                                                 np.min(f * cfac) + 1e-30)))
            cables = Line3DCollection(x[lines], cmap="inferno", norm=cnorm, linewidth=1.8)
            cables.set_array(f * cfac)
            ax.add_collection3d(cables)
            fig.colorbar(cables, ax=ax, location="right", shrink=0.5, pad=0.02, aspect=30,
                         label=f"cable force [{cunit}]")
        else:
            ax.add_collection3d(Line3DCollection(x[lines], colors="black", linewidth=1.5))
    # Equal scaling on the three axes: the same length per unit everywhere (a flat direction keeps a
    # sliver of 2 % of the largest extent so the box does not collapse).
    allp = np.vstack(pts + [x0])
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    span = hi - lo
    span = np.maximum(span, 0.02 * max(float(span.max()), 1e-12))
    mid = 0.5 * (lo + hi)
    for set_lim, c, s in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid, span):
        set_lim(c - 0.5 * s, c + 0.5 * s)
    ax.set_box_aspect(tuple(span), zoom=0.85)  # room for the tick and axis labels inside the figure
    # A thin direction (a 2-D case's depth, a flat sheet's normal) would smear its tick labels into the
    # neighbour axis: its extent goes into the axis label instead, and the view looks more along a thin x or y.
    thin = span < 0.15 * span.max()
    extents = []
    for axis, letter, is_thin, a, b in zip((ax.xaxis, ax.yaxis, ax.zaxis), "xyz", thin, lo, hi):
        if is_thin:
            axis.set_ticklabels([])
            axis.set_label_text("")
            extents.append(f"{letter} from {a:.3g} to {b:.3g} m")
        else:
            axis.set_label_text(f"{letter} [m]")
    ax.view_init(elev=20 if thin[1] or thin[0] else 28, azim=-80 if thin[1] else (-10 if thin[0] else -60))
    what = f"Last frame: t = {time:.6g} s, step {step} (grey: first frame)"
    if extents:
        what += "; " + ", ".join(extents)
    ax.set_title(heading(what, title))
    series = [("triangles", len(tris)), ("cables", len(lines))]
    index.save(fig, "structure.png", "structure, last frame", series, frame=name, time=time,
               color=label or "none")


# ---------------------------------------------------------------------------------------------------------
# A structure run


def plot_structure_run(run_dir, out_dir, color):
    h5_path = os.path.join(run_dir, "results.h5")
    summary_path = os.path.join(run_dir, "summary.json")
    title = os.path.basename(os.path.abspath(run_dir))
    units = {}
    if os.path.isfile(summary_path):
        try:
            with open(summary_path) as f:
                summary = json.load(f)
        except (OSError, ValueError) as e:
            raise InputError(f"{summary_path}: {e}")
        title = summary.get("title") or title
        units = scene_info(summary.get("scene"))[1]
    else:
        warn(f"{summary_path} not found (the run did not finish?): no title or probe units")
    index = Index("structure", run_dir, out_dir)
    with read_h5(h5_path) as h5:
        energy = read_table(h5, "energy", h5_path)
        probes = read_table(h5, "probes", h5_path)
        residual = read_table(h5, "residual", h5_path)
        if energy is None and residual is None:
            warn(f"{h5_path} has no /tables/energy (tables are written at the end of a run; was it killed?)")
        if energy is not None:
            missing = [c for c in ("time", "kinetic", "strain", "external_work", "internal_work", "mass_damping",
                                   "balance_error") if c not in energy]
            if missing:
                raise InputError(f"{h5_path}: /tables/energy has no column(s) {', '.join(missing)}")
            plot_energy(index, energy, title)
        if probes is not None and len(probes) > 1:
            if "time" not in probes:
                raise InputError(f"{h5_path}: /tables/probes has no column 'time'")
            names = [c for c in probes if c != "time"]
            plot_probe_panels(index, probes["time"], {c: probes[c] for c in names}, units, title)
        if residual is not None:
            plot_relaxation(index, residual, title)
        plot_structure(index, h5, h5_path, title, color)
    return index


# ---------------------------------------------------------------------------------------------------------
# A coupled case


def read_coupling_csv(path):
    """Header, rows (float array) and restarts [(time, note)] of coupling.csv.

    Lines starting with '#' are comments; one that mentions "restart" marks a restart (at the time it states,
    else at the last row before it). A repeated header line is skipped. When the times stop
    increasing (a restart from an earlier time directory), the rows from that time on are replaced by the
    new ones, so each window appears once, as last computed.
    """
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise InputError(f"{path}: {e}")
    lines = text.split("\n")
    header, rows, restarts, pending = None, [], [], None
    for lineno, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            if "restart" in line.lower():
                pending = line.lstrip("#").strip()
            continue
        fields = [s.strip() for s in line.split(",")]
        if header is None:
            header = fields
            if header[:len(COUPLING_FIXED)] != COUPLING_FIXED:
                raise InputError(f"{path}:{lineno}: header is not the coupling log's "
                                 f"({','.join(COUPLING_FIXED)},<probes>): {line}")
            continue
        if fields == header:
            continue
        last_line = lineno == len(lines) or (lineno == len(lines) - 1 and lines[-1] == "")
        if len(fields) != len(header):
            if last_line and not text.endswith("\n"):  # cut short by a killed run
                warn(f"{path}:{lineno}: incomplete last line skipped")
                continue
            raise InputError(f"{path}:{lineno}: {len(fields)} values, the header has {len(header)}")
        try:
            row = [float(s) for s in fields]
        except ValueError:
            bad = next(i for i, s in enumerate(fields) if not _is_float(s))
            raise InputError(f"{path}:{lineno}: column '{header[bad]}': '{fields[bad]}' is not a number")
        t = row[0]
        if pending is not None or (rows and t <= rows[-1][0]):
            while rows and rows[-1][0] >= t * (1 - 1e-12) - 1e-300:
                rows.pop()  # superseded by the restarted run
            if pending is not None:
                restarts.append((_note_time(pending, rows[-1][0] if rows else t), pending))
                pending = None
        rows.append(row)
    if header is None:
        raise InputError(f"{path}: empty (no header line)")
    return header, np.array(rows, dtype=float).reshape(-1, len(header)), restarts


def _is_float(s):
    try:
        float(s)
        return True
    except ValueError:
        return False


def _note_time(note, fallback):
    """The restart time a note states ('t = 0.6', 'time 0.6', 'at 0.6', 'from 0.6'), else the fallback."""
    m = re.search(r"(?:\bt\b|\btime\b|\bat\b|\bfrom\b)\s*[=:]?\s*([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)", note)
    return float(m.group(1)) if m else fallback


def scene_of_case(case_dir):
    """The structure scene named in system/controlDict (`scene "structure.yaml";`), or ''."""
    try:
        with open(os.path.join(case_dir, "system", "controlDict")) as f:
            m = re.search(r'\bscene\s+"([^"]+)"\s*;', f.read())
    except OSError:
        return ""
    if not m:
        return ""
    p = m.group(1)
    return p if os.path.isabs(p) else os.path.join(case_dir, p)


def plot_forces(index, t, cols, title, restarts):
    fig, axes = plt.subplots(4, 1, figsize=(8, 9.5), sharex=True, height_ratios=[1, 1, 1, 0.9],
                             layout="constrained")
    all_f = np.concatenate([cols[f"F{c}_{s}"] for c in "xyz" for s in ("fluid", "structure")])
    factor, unit = scaled_unit(all_f, "N")
    n = len(t)
    for ax, c in zip(axes, "xyz"):
        ax.plot(t, cols[f"F{c}_fluid"] * factor, "-", color="tab:blue", label="fluid side",
                marker=marker_for(n), markersize=3)
        ax.plot(t, cols[f"F{c}_structure"] * factor, "--", color="tab:orange", label="structure side")
        ax.set_ylabel(f"F{c} [{unit}]")
        mark_restarts(ax, restarts, label=(c == "x"))
        if c == "x":
            ax.legend(loc="best")
    ff = np.stack([cols[f"F{c}_fluid"] for c in "xyz"], axis=1)
    fs = np.stack([cols[f"F{c}_structure"] for c in "xyz"], axis=1)
    scale = np.maximum(np.linalg.norm(ff, axis=1), 1e-300)
    rel = np.linalg.norm(ff - fs, axis=1) / scale
    skipped = log_panel(axes[3], t, rel, "tab:green", "fluid and structure forces identical")
    axes[3].set_ylabel("|F_f − F_s| / |F_f| [–]")
    axes[3].set_xlabel("time [s]")
    mark_restarts(axes[3], restarts, label=False)
    axes[0].set_title(heading("Interface force (fluid side and structure side)", title))
    series = [(f"F{c}_{s}", n) for c in "xyz" for s in ("fluid", "structure")] + [("relative_difference", n, skipped)]
    index.save(fig, "interface_force.png", "interface force vs time", series)


def plot_iterations(index, t, cols, title, restarts, timing):
    n = len(t)
    it = cols["iterations"]
    conv = cols["converged"] > 0.5
    res = cols["residual"]
    fig, (ax, axr) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, layout="constrained")
    ax.plot(t, it, drawstyle="steps-mid", color="tab:blue", label="iterations")
    if (~conv).any():
        ax.plot(t[~conv], it[~conv], "x", color="tab:red", markersize=7, label="not converged")
    ax.set_ylabel("iterations per window [–]")
    ax.set_ylim(0, max(2.0, float(it.max()) * 1.1) if n else 2.0)
    what = "Coupling iterations per window"
    if timing:
        what += (f" ({timing.get('windows', '?')} windows, {timing.get('mean_iterations', float('nan')):.3g} "
                 f"iterations on average, wall {timing.get('wall_seconds', float('nan')):.4g} s)")
    ax.set_title(heading(what, title))
    mark_restarts(ax, restarts)
    ax.legend(loc="best")
    skipped = log_panel(axr, t, res, "tab:purple", "no residual (staggered coupling: one pass per window)")
    axr.set_ylabel("relative residual [–]")
    axr.set_xlabel("time [s]")
    mark_restarts(axr, restarts, label=False)
    index.save(fig, "iterations.png", "coupling iterations and residual per window",
               [("iterations", n), ("residual", n, skipped)])


def plot_coupled_case(case_dir, out_dir, color):
    sdir = os.path.join(case_dir, "structure")
    csv_path = os.path.join(sdir, "coupling.csv")
    if not os.path.isfile(csv_path):
        raise InputError(f"{csv_path} not found: {case_dir} has a structure/ folder but no coupling log "
                         "(did the coupled run start?)")
    header, data, restarts = read_coupling_csv(csv_path)
    cols = {h: data[:, i] for i, h in enumerate(header)}
    scene_title, units = scene_info(scene_of_case(case_dir))
    title = os.path.basename(os.path.abspath(case_dir)) + (f": {scene_title}" if scene_title else "")
    timing = None
    timing_path = os.path.join(sdir, "timing.json")
    if os.path.isfile(timing_path):
        try:
            with open(timing_path) as f:
                timing = json.load(f)
        except (OSError, ValueError) as e:
            raise InputError(f"{timing_path}: {e}")
    index = Index("coupled", case_dir, out_dir)
    index.data["restarts"] = [{"time": t, "note": note} for t, note in restarts]
    if len(data) == 0:
        warn(f"{csv_path}: no window logged yet: no time series")
    else:
        t = cols["time"]
        plot_forces(index, t, cols, title, restarts)
        plot_iterations(index, t, cols, title, restarts, timing)
        probe_names = header[len(COUPLING_FIXED):]
        if probe_names:
            plot_probe_panels(index, t, {p: cols[p] for p in probe_names}, units, title, restarts)
    h5_path = os.path.join(sdir, "results.h5")
    if os.path.isfile(h5_path):
        with read_h5(h5_path) as h5:
            plot_structure(index, h5, h5_path, title, color)
    else:
        warn(f"{h5_path} not found: no structure picture")
    return index


def main(argv):
    ap = argparse.ArgumentParser(prog="fsi plot", description="PNG plots of a structure run or a coupled case")
    ap.add_argument("run_dir", help="output folder of `fsi run` or `fsi fly`, or a coupled OpenFOAM case folder")
    ap.add_argument("--out", help="folder for the PNGs and index.json (default RUN_DIR/plots)")
    ap.add_argument("--color", choices=["auto", "stress", "displacement"], default="auto",
                    help="colour of the structure picture (auto: major principal stress when written)")
    args = ap.parse_args(argv)
    run_dir = args.run_dir
    if not os.path.isdir(run_dir):
        raise InputError(f"{run_dir}: no such folder")
    if os.path.isfile(os.path.join(run_dir, "trajectory.csv")):  # a flight (fsi fly)
        load_modules()
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import fsi_plot_flight  # noqa: E402 (beside this script: share/fsi or apps/fsi)
        index = fsi_plot_flight.plot_flight(run_dir, args.out or os.path.join(run_dir, "plots"), Index, plt, np,
                                            InputError)
        index.write()
        return 0
    structure_run = os.path.isfile(os.path.join(run_dir, "results.h5"))
    coupled = os.path.isdir(os.path.join(run_dir, "structure")) and (
        os.path.isfile(os.path.join(run_dir, "structure", "coupling.csv"))
        or os.path.isfile(os.path.join(run_dir, "structure", "results.h5")))
    if not structure_run and not coupled:
        raise InputError(
            f"{run_dir} is neither a structure run (no {os.path.join(run_dir, 'results.h5')}, written by "
            f"`fsi run SCENE --out DIR`) nor a coupled case (no {os.path.join(run_dir, 'structure', 'coupling.csv')}, "
            "written by the fsiCoupling function object)")
    out_dir = args.out or os.path.join(run_dir, "plots")
    load_modules()
    index = plot_coupled_case(run_dir, out_dir, args.color) if coupled else \
        plot_structure_run(run_dir, out_dir, args.color)
    if not index.data["plots"]:
        raise InputError(f"{run_dir}: nothing to plot (see the warnings above)")
    index.write()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except InputError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(2)
    except KeyError as e:  # an h5 dataset the layout promises is absent
        print(f"error: {sys.argv[1] if len(sys.argv) > 1 else ''}: missing {e}", file=sys.stderr)
        sys.exit(2)
