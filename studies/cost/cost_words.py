"""Words from numbers for docs/ACCURACY_COST.md (studies/cost/accuracy_cost.py): ratios as the doc prints them,
the "what you buy" sentence of one step, observed convergence orders."""
import math


def times(x):
    """A ratio as the doc prints it: 2 significant digits below 10, whole numbers above."""
    if x >= 999.5:  # 3.1·10⁴ rather than 31417: the digits beyond the second mean nothing
        e = int(f"{x:.1e}".split("e")[1])
        return f"{x / 10 ** e:.1f}·10" + "".join("⁰¹²³⁴⁵⁶⁷⁸⁹"[int(c)] for c in str(e))
    return f"{x:.0f}" if x >= 9.95 else f"{x:.1f}"


def buy(change, e0, e1, t0, t1, floor=0.0, cost="the time"):
    """'change: error 4.0× smaller, 7.9× the time' from the errors and times before (0) and after (1).
    Errors at or below `floor` (the reference's own precision) are not compared."""
    if e1 <= floor and e0 <= floor:
        err = "error below the reference's precision before and after"
    elif e1 <= floor:
        err = f"error from {e0:.2g} to below the reference's precision ({floor:.1g})"
    elif e1 <= e0:
        err = f"error {times(e0 / e1)}× smaller"
    else:
        err = f"error {times(e1 / e0)}× larger"
    if e0 > floor and e1 > floor and max(e0 / e1, e1 / e0) > 30:
        err += f" ({e0:.1e} → {e1:.1e})"
    return f"{change}: {err}, {times(t1 / t0)}× {cost}"


def buy_from_row_above(rows, i, change, key="error", time="wall", **kw):
    """The "what you buy" cell of table row i against row i - 1 ("" for the first row); change(p, r) names the
    step from the row above p to this row r."""
    if i == 0:
        return ""
    p, r = rows[i - 1], rows[i]
    return buy(change(p, r), p[key], r[key], p[time], r[time], **kw)


def order(h, e):
    """Observed convergence orders between successive levels: log(e_i/e_{i+1}) / log(h_i/h_{i+1})."""
    return [math.log(e[i] / e[i + 1]) / math.log(h[i] / h[i + 1]) if e[i] > 0 and e[i + 1] > 0 else float("nan")
            for i in range(len(e) - 1)]


def fmt_orders(p):
    return ", ".join(f"{x:.2f}" for x in p)
