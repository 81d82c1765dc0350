"""Accuracy versus cost, projection between non-matching meshes: `fsi map-check` on generated curved Gmsh
patches, per variant and mesh size, and per quadrature level with a much finer source; tables and plot
(studies/cost/accuracy_cost.py)."""
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))  # fsi_runs
import fsi_runs  # noqa: E402
from cost_words import buy, buy_from_row_above, fmt_orders, order  # noqa: E402

ARC = math.radians(70.0)  # a cylinder patch, radius 1 m, length 1 m: curved like a canopy panel


def write_cylinder_msh(path, n, quads, seed):
    """A Gmsh MSH 2.2 ASCII patch of the cylinder r = 1, 0 ≤ θ ≤ 70°, 0 ≤ z ≤ 1: n×n cells, interior nodes
    moved at random by up to ±0.2 cell (seeded), cells split into two triangles or kept as quads. The two
    meshes of a check differ in n, element kind and perturbation: non-matching everywhere."""
    rng = np.random.default_rng(seed)
    u = np.linspace(0.0, 1.0, n + 1)
    uu, vv = np.meshgrid(u, u, indexing="ij")
    inner = (uu > 0) & (uu < 1) & (vv > 0) & (vv < 1)
    uu = uu + inner * rng.uniform(-0.2, 0.2, uu.shape) / n
    vv = vv + inner * rng.uniform(-0.2, 0.2, vv.shape) / n
    nodes = [(math.cos(ARC * a), math.sin(ARC * a), b) for a, b in zip(uu.ravel(), vv.ravel())]
    idx = lambda i, j: i * (n + 1) + j + 1  # noqa: E731
    cells = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            cells += [(3, (a, b, c, d))] if quads else [(2, (a, b, c)), (2, (a, c, d))]
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", str(len(nodes))]
    lines += [f"{k + 1} {x:.17g} {y:.17g} {z:.17g}" for k, (x, y, z) in enumerate(nodes)]
    lines += ["$EndNodes", "$Elements", str(len(cells))]
    lines += [f"{k + 1} {t} 2 1 1 " + " ".join(map(str, c)) for k, (t, c) in enumerate(cells)]
    lines += ["$EndElements", ""]
    Path(path).write_text("\n".join(lines))


# The L2 projection with every correction, as map-check's defaults were when these tables were made (since
# issue 39 map-check starts from the coupled run's settings, whose displacement is pointwise; this study is
# about the L2 projection's variants and quadrature, docs/PROJECTION.md "Against nearest projection").
L2_ALL_CORRECTIONS = ["--evaluation", "l2", "--gap-correction", "yes", "--defect-correction", "auto",
                      "--keep-side", "yes"]


def map_check_timed(a, b, args, repeats):
    """One map-check, repeated `repeats` times for the setup time (median), errors from the first."""
    reports = [fsi_runs.map_check(a, b, L2_ALL_CORRECTIONS + list(args)) for _ in range(max(1, repeats))]
    d = reports[0]["directions"][0]
    setups = sorted(r["directions"][0]["setup_seconds"] for r in reports)
    applies = sorted(r["directions"][0]["apply_seconds_vector"] for r in reports)
    return dict(error=d["quadratic_error"]["rms"], error_max=d["quadratic_error"]["max"],
                linear=d["linear_error"]["max"], source_nodes=d["source_nodes"], target_nodes=d["target_nodes"],
                setup=setups[len(setups) // 2], apply=applies[len(applies) // 2],
                unmapped=d["unmapped_quadrature_points"], force=d["conservative_force_error"])


def projection_study(sizes, levels, repeats, work):
    """Variant × mesh: structure-like triangles (n×n cells) → fluid-like quads 1.38× finer, the displacement
    direction; error of the quadratic test field. Quadrature level: a fine source (80×80 cells) mapped onto a
    10× coarser target (8×8 quads), where the level matters (docs/PROJECTION.md, "Quadrature")."""
    rows = []
    for n in sizes:
        src, dst = work / f"tri-{n}.msh", work / f"quad-{n}.msh"
        write_cylinder_msh(src, n, False, 1000 + n)
        write_cylinder_msh(dst, round(1.38 * n), True, 2000 + n)
        for variant in ("consistent", "dual", "lumped"):
            r = map_check_timed(src, dst, ["--variant", variant], repeats)
            rows.append(dict(n=n, h=1.0 / n, variant=variant, **r))
    fine, coarse = work / "tri-fine.msh", work / "quad-coarse.msh"
    write_cylinder_msh(fine, 80, False, 3000)
    write_cylinder_msh(coarse, 8, True, 3001)
    qrows = []
    for level in levels:
        r = map_check_timed(fine, coarse, ["--variant", "auto", "--quadrature-level", str(level)], repeats)
        qrows.append(dict(level=level, **r))
    orders = {v: order([r["h"] for r in rows if r["variant"] == v], [r["error"] for r in rows if r["variant"] == v])
              for v in ("consistent", "dual", "lumped")}
    return dict(rows=rows, orders=orders, quadrature=qrows)


def projection_section(pr):
    md = ["## Projection between non-matching meshes: variant, mesh and quadrature level\n",
          "`fsi map-check SRC DST --json` on a curved patch (cylinder r = 1 m, 70° arc, 1 m long; both meshes "
          "perturbed at random by ±0.2 cell): source n×n cells of triangles (the structure), target 1.38n×1.38n "
          "quads (the fluid); direction source → target (displacements). Error: RMS nodal error of map-check's "
          "quadratic test field relative to its range. Cost: the setup (search, assembly, factorisation), done "
          "once per run; the apply (one 3-component transfer) is listed too: it is paid every coupling "
          "iteration.\n",
          "![projection: error against setup time](img/accuracy_cost_projection.png)\n",
          "| n | source / target nodes | variant | error (RMS) | linear field max error | setup [ms] | apply [µs] | "
          "what you buy |",
          "|---|---|---|---|---|---|---|---|"]
    by = {(r["variant"], r["n"]): r for r in pr["rows"]}
    sizes = sorted({r["n"] for r in pr["rows"]})
    for r in pr["rows"]:
        words = []
        i = sizes.index(r["n"])
        if i > 0:
            p = by[(r["variant"], sizes[i - 1])]
            words.append(buy(f"halving the mesh size ({p['n']} → {r['n']})", p["error"], r["error"], p["setup"],
                             r["setup"], cost="the setup time"))
        if r["variant"] != "consistent":
            c = by[("consistent", r["n"])]
            words.append(buy(f"{r['variant']} instead of consistent", c["error"], r["error"], c["setup"], r["setup"],
                             cost="the setup time"))
        md.append(f"| {r['n']} | {r['source_nodes']} / {r['target_nodes']} | {r['variant']} | {r['error']:.2e} | "
                  f"{r['linear']:.1e} | {r['setup'] * 1e3:.2f} | {r['apply'] * 1e6:.1f} | {'; '.join(words)} |")
    md.append("\nObserved orders (RMS error, successive halvings): "
              + "; ".join(f"{v} {fmt_orders(p)}" for v, p in pr["orders"].items())
              + " (expected 2 for consistent and dual; lumped is first order on irregular meshes).\n")
    q = pr["quadrature"]
    md += [f"**Quadrature level** (consistent): a fine source ({q[0]['source_nodes']} nodes, 80×80 cells) onto a "
           f"10× coarser target ({q[0]['target_nodes']} nodes, 8×8 quads), the case where one 3-point rule per "
           "target triangle samples only a few source nodes (docs/PROJECTION.md names it for a higher level).\n",
           "| `--quadrature-level` | error (RMS) | max error | setup [ms] | what you buy (from the row above) |",
           "|---|---|---|---|---|"]
    for i, r in enumerate(q):
        words = buy_from_row_above(q, i, lambda p, r: f"level {p['level']} → {r['level']}", time="setup",
                                   cost="the setup time")
        md.append(f"| {r['level']} | {r['error']:.2e} | {r['error_max']:.2e} | {r['setup'] * 1e3:.2f} | {words} |")
    md.append("\nThe error measured here is that of a smooth field carried from the fine source to the coarse "
              "target, where the 3-point rule per target triangle already integrates well. What the level is for "
              "is the other direction of the same operator: Hᵀ hands a coarse target's forces only to the source "
              "nodes near its quadrature points (docs/PROJECTION.md, \"Quadrature\"), which map-check's field "
              "errors do not measure.\n")
    return md


def projection_plot(pr, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3))
    ax = axes[0]
    for v in ("consistent", "dual", "lumped"):
        rs = [r for r in pr["rows"] if r["variant"] == v]
        ax.loglog([r["setup"] * 1e3 for r in rs], [r["error"] for r in rs], "o-", label=v)
        for r in rs:
            ax.annotate(str(r["n"]), (r["setup"] * 1e3, r["error"]), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
    ax.set_xlabel("setup time [ms]")
    ax.set_ylabel("RMS error, quadratic field (rel. to range)")
    ax.set_title("Variant and mesh (labels: n)")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax = axes[1]
    q = pr["quadrature"]
    ax.loglog([r["setup"] * 1e3 for r in q], [r["error"] for r in q], "o-")
    for r in q:
        ax.annotate(f"L={r['level']}", (r["setup"] * 1e3, r["error"]), textcoords="offset points", xytext=(4, 4),
                    fontsize=7)
    ax.set_xlabel("setup time [ms]")
    ax.set_ylabel("RMS error, quadratic field (rel. to range)")
    ax.set_title("Quadrature level, source 10× finer than target")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
