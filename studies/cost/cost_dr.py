"""Accuracy versus cost, dynamic relaxation: studies/relaxation/dr_accuracy_cost.py's measurement (method and tolerance
on the 25x25 cushion) with a "what you buy" per step (studies/cost/accuracy_cost.py)."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "relaxation"))  # dr_accuracy_cost
import dr_accuracy_cost  # noqa: E402
from cost_words import buy  # noqa: E402


def dr_study(methods, eps, repeats):
    ref, rows = dr_accuracy_cost.measure(methods, eps, repeats)
    return dict(reference=dict(iterations=ref["stats"]["iterations"], value=ref["probes"]["center_displacement"]),
                rows=rows)


def dr_section(dr):
    md = ["## Static answers by dynamic relaxation: method and tolerance\n",
          "The 25×25 square cushion (`cases/structure/cushion-square-25`, 2028 dof), measured by "
          "`studies/relaxation/dr_accuracy_cost.py`'s `measure()`; error of the centre displacement against the "
          f"KDR solution at ε = 1e-10 ({dr['reference']['iterations']} iterations, "
          f"{dr['reference']['value'] * 1e3:.4f} mm). Methods: docs/DYNAMIC_RELAXATION.md.\n",
          "![dynamic relaxation: error against iterations and wall time](img/accuracy_cost_dr.png)\n",
          "| method | ε | iterations | wall [ms] | error | what you buy (from the row above) |",
          "|---|---|---|---|---|---|"]
    prev = None
    for r in dr["rows"]:
        words = ""
        conv = "" if r["converged"] else " (not converged)"
        if prev is not None and prev["method"] == r["method"] and prev["converged"] and r["converged"]:
            words = buy(f"ε {prev['eps']:.0e} → {r['eps']:.0e}", prev["ew"], r["ew"], prev["wall"], r["wall"])
        md.append(f"| {r['method']} | {r['eps']:.0e} | {r['it']}{conv} | {r['wall'] * 1e3:.1f} | {r['ew']:.2e} | "
                  f"{words} |")
        prev = r
    kdr = {r["eps"]: r for r in dr["rows"] if r["method"] == "KDR"}
    lines = []
    for r in dr["rows"]:
        k = kdr.get(r["eps"])
        if r["method"] != "KDR" and k and r["converged"] and k["converged"]:
            lines.append("* " + buy(f"{r['method']} instead of KDR at ε = {r['eps']:.0e}", k["ew"], r["ew"],
                                    k["wall"], r["wall"]))
    if lines:
        md += ["", "Other methods against the default (KDR) at the same ε:\n"] + lines
    md.append("")
    return md


def dr_plot(dr, path):
    dr_accuracy_cost.plot(dr["rows"], path, "Dynamic relaxation, 25×25 cushion: error against cost")
