"""Accuracy versus cost, mesh refinement: the validation cases of fsi_runs.MESH_STUDIES at several mesh sizes,
error against their references and a finer mesh, observed orders; table and plot (studies/cost/accuracy_cost.py)."""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "common"))  # fsi_runs
import fsi_runs  # noqa: E402
from cost_words import buy_from_row_above, fmt_orders, order  # noqa: E402
from fsi_runs import MESH_STUDIES  # noqa: E402


def mesh_study(name, levels, repeats, finest_reference=None):
    """Runs MESH_STUDIES[name] at each level. Error against the study's analytical/published reference and,
    if finest_reference is a level, against that (finer, not tabulated) solution too. Also the observed order
    from successive differences (independent of any reference) and the Richardson extrapolation."""
    st = MESH_STUDIES[name]
    reference = st["reference"]()
    rows = []
    for n in levels:
        s = fsi_runs.run_timed(st["case"], st["sets"](n), repeats=repeats)
        v = s["probes"][st["probe"]]
        rows.append(dict(level=n, h=st["h"](n), elements=s["stats"]["membrane_elements"], value=v,
                         steps=s["stats"]["steps"], wall=s["wall"], wall_runs=s["wall_runs"],
                         error=abs(v / reference - 1)))
    out = dict(name=name, rows=rows, reference=reference,
               reference_text=st["reference_text"].format(reference / st["unit"]),
               floor=st["reference_resolution"] / abs(reference), expected_order=st["expected_order"])
    if finest_reference:
        s = fsi_runs.run(st["case"], st["sets"](finest_reference))
        vf = s["probes"][st["probe"]]
        out["fine"] = dict(level=finest_reference, value=vf, wall=s["stats"]["wall_seconds"],
                           elements=s["stats"]["membrane_elements"])
        for r in rows:
            r["error_fine"] = abs(r["value"] / vf - 1)
    v = [r["value"] for r in rows]
    h = [r["h"] for r in rows]
    if len(v) >= 3:
        d = [abs(v[i] - v[i + 1]) for i in range(len(v) - 1)]
        out["difference_orders"] = order(h[:-1], d)
    if st["expected_order"]:
        out["orders"] = order(h, [r["error"] for r in rows])
        p = out["difference_orders"][-1]
        q = h[-2] / h[-1]
        if st["expected_order"] and p == p and p > 0:
            out["richardson"] = v[-1] + (v[-1] - v[-2]) / (q ** p - 1)
    return out


def mesh_section(studies):
    md = ["## Mesh refinement\n",
          "Each level halves the element size (rings of the Hencky disc, divisions of the sphere octant, squares "
          "per airbag face). Error: relative to the reference named in the heading. *Order from differences*: "
          "log(|v₁−v₂|/|v₂−v₃|)/log 2 over three successive levels, which needs no reference; *Richardson*: the "
          "finest two values extrapolated with that order. Expected: second order (linear triangles, smooth "
          "solution); the airbag's wrinkled band along the seam is not smooth, and its deflection is not "
          "monotone in the mesh.\n",
          "![mesh refinement: error against wall time](img/accuracy_cost_mesh.png)\n"]
    for s in studies:
        st = MESH_STUDIES[s["name"]]
        u, un = st["unit"], st["unit_name"]
        title = {"hencky": "Hencky membrane (`cases/structure/hencky`), centre deflection",
                 "sphere": "Pressurised sphere (`cases/structure/sphere`, E = 3000 MPa, 10 kPa), mean radial "
                           "displacement",
                 "airbag": "Square airbag (`cases/structure/airbag`), centre displacement"}[s["name"]]
        md.append(f"### {title}\n")
        md.append(f"Reference: {s['reference_text']}." + (
            f" Also against the {s['fine']['level']} {st['level_name']} solution ({s['fine']['elements']} "
            f"triangles, {s['fine']['value'] / u:.3f} {un}, {s['fine']['wall']:.1f} s), the finest run: "
            "*error vs finest* leaves out that run's own error." if "fine" in s else "") + "\n")
        fine = "fine" in s
        md.append(f"| {st['level_name']} | triangles | value [{un}] | error | "
                  + ("error vs finest | " if fine else "") + "steps | wall [s] | what you buy (from the row above) |")
        md.append("|---|---|---|---|---|---|---|" + ("---|" if fine else ""))
        for i, r in enumerate(s["rows"]):
            key = "error_fine" if fine else "error"
            words = buy_from_row_above(s["rows"], i,
                                       lambda p, r: f"halving the mesh size ({p['level']} → {r['level']})", key=key,
                                       floor=0.0 if fine else s["floor"])
            err = f"{r['error']:.2e}" + (" (within the reference's precision)" if r["error"] <= s["floor"] else "")
            md.append(f"| {r['level']} | {r['elements']} | {r['value'] / u:.4f} | {err} | "
                      + (f"{r['error_fine']:.2e} | " if fine else "")
                      + f"{r['steps']} | {r['wall']:.3f} | {words} |")
        extra = []
        if "orders" in s:
            extra.append(f"observed order against the reference: {fmt_orders(s['orders'])}")
        if "difference_orders" in s:
            extra.append(f"order from differences: {fmt_orders(s['difference_orders'])}")
        if "richardson" in s:
            extra.append(f"Richardson extrapolation {s['richardson'] / u:.4f} {un} "
                         f"({s['richardson'] / s['reference'] - 1:+.1e} from the reference)")
        if extra:
            md.append("\n" + "; ".join(extra) + ".\n")
        else:
            md.append("")
    return md


def mesh_plot(studies, path):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for s in studies:
        key = "error_fine" if "fine" in s else "error"
        w = [r["wall"] for r in s["rows"]]
        e = [max(r[key], 1e-9) for r in s["rows"]]
        label = s["name"] + (" (vs finest mesh)" if "fine" in s else " (vs reference)")
        ax.loglog(w, e, "o-", label=label)
        for r, x, y in zip(s["rows"], w, e):
            ax.annotate(str(r["level"]), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("relative error")
    ax.set_title("Mesh refinement (labels: rings / divisions / squares per face)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
