#!/usr/bin/env python3
"""What accuracy costs: for each dynamic-relaxation method and tolerance ε = 1e-2 ... 1e-6, the error in the
centre displacement and in the maximum principal stress against a tight-tolerance solution (ε = 1e-10),
versus iterations and wall time, on the 25x25 square cushion. Writes a table into
docs/DYNAMIC_RELAXATION.md and the plot docs/img/dr_accuracy_cost.png. studies/cost/accuracy_cost.py calls
measure() and plot() for its own summary of all the knobs.
Usage: studies/relaxation/dr_accuracy_cost.py   (needs build/bin/fsi and python3-matplotlib; about 1 minute)"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from dr_common import METHODS, ROOT, replace_block, run  # noqa: E402

CASE = "cushion-square-25"
EPS = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6]


def measure(methods=tuple(METHODS), eps=EPS, repeats=1):
    """Runs the reference (KDR, ε = 1e-10) and every method at every ε; returns (reference summary, rows).
    Wall times are medians of `repeats` runs."""
    ref = run(CASE, ["solver.tolerance=1.0e-10"])
    w_ref = ref["probes"]["center_displacement"]
    s_ref = ref["probes"]["max_principal_stress"]
    rows = []
    for method in methods:
        for e in eps:
            s = run(CASE, METHODS[method] + [f"solver.tolerance={e}"], repeats=repeats)
            st = s["stats"]
            rows.append(dict(method=method, eps=e, converged=st["converged"], it=st["iterations"],
                             wall=s["wall"],
                             ew=abs(s["probes"]["center_displacement"] / w_ref - 1),
                             es=abs(s["probes"]["max_principal_stress"] / s_ref - 1)))
    return ref, rows


def table(ref, rows):
    w_ref = ref["probes"]["center_displacement"]
    s_ref = ref["probes"]["max_principal_stress"]
    lines = [f"Reference (KDR, ε = 1e-10, {ref['stats']['iterations']} iterations): centre displacement "
             f"{w_ref * 1000:.4f} mm, max principal stress {s_ref / 1e6:.4f} MPa.\n",
             "| method | ε | iterations | wall [ms] | error centre displacement | error max principal stress |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        it = f"{r['it']}" if r["converged"] else f"{r['it']} (not converged)"
        lines.append(f"| {r['method']} | {r['eps']:.0e} | {it} | {r['wall'] * 1000:.1f} | {r['ew']:.2e} | "
                     f"{r['es']:.2e} |")
    return "\n".join(lines)


def plot(rows, path, title):
    methods = list(dict.fromkeys(r["method"] for r in rows))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for method in methods:
        rs = [r for r in rows if r["method"] == method and r["converged"]]
        for ax, key, scale in ((axes[0], "it", 1), (axes[1], "wall", 1000)):
            line, = ax.loglog([r[key] * scale for r in rs], [max(r["ew"], 1e-12) for r in rs], "o-",
                              label=f"{method} displacement")
            ax.loglog([r[key] * scale for r in rs], [max(r["es"], 1e-12) for r in rs], "s--",
                      color=line.get_color(), label=f"{method} max stress")
    axes[0].set_xlabel("iterations")
    axes[1].set_xlabel("wall time [ms]")
    for ax in axes:
        ax.set_ylabel("relative error vs ε = 1e-10 solution")
        ax.grid(True, which="both", alpha=0.3)
    axes[1].legend(fontsize=7, ncol=2)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    ref, rows = measure()
    text = table(ref, rows)
    replace_block("accuracy-cost", text)
    print(text)
    plot(rows, ROOT / "docs/img/dr_accuracy_cost.png",
         "Square cushion 25x25 (2028 dof): error against cost for ε = 1e-2 ... 1e-6")
