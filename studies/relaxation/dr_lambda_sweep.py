#!/usr/bin/env python3
"""λ sweep of the dynamic-relaxation methods on the cushion cases (iterations to ε = 1e-3, one load step),
in the layout of the reference thesis. Writes the table into docs/DYNAMIC_RELAXATION.md.
Usage: studies/relaxation/dr_lambda_sweep.py   (needs build/bin/fsi; about 5 minutes on 2 cores)"""
from concurrent.futures import ThreadPoolExecutor

from dr_common import METHODS, replace_block, run

CASES = {"cushion-square-25": "TL1 (2028 dof)", "cushion-square-50": "TL2 (7803 dof)",
         "cushion-circular": "circular (17823 dof)"}
LAMBDAS = [0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 2.0]
LAMBDAS_KDR1 = [5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15]


def cell(summary):
    s = summary["stats"]
    if not s.get("converged"):
        return "div"
    mark = "*" if s.get("restarts", 0) > 0 else ""
    return f"{s['iterations']}{mark}"


jobs = []
for case in CASES:
    for method, sets in METHODS.items():
        for lam in (LAMBDAS_KDR1 if method == "KDR1" else LAMBDAS):
            jobs.append((case, method, lam, sets + [f"solver.lambda={lam}"]))
    for lam in LAMBDAS:  # evidence: the same default method without the wrinkling model
        jobs.append((case, "KDR, no wrinkling", lam,
                     METHODS["KDR"] + [f"solver.lambda={lam}", "materials.fabric.wrinkling=false"]))

with ThreadPoolExecutor(max_workers=2) as pool:
    results = list(pool.map(lambda j: cell(run(j[0], j[3])), jobs))

lines = []
for case, title in CASES.items():
    lines.append(f"\n**{title}** — columns are λ ({', '.join(map(str, LAMBDAS))}; KDR1: "
                 f"{', '.join(map(str, LAMBDAS_KDR1))})\n")
    lines.append("| method | " + " | ".join(f"c{i + 1}" for i in range(len(LAMBDAS))) + " |")
    lines.append("|---|" + "---|" * len(LAMBDAS))
    for method in list(METHODS) + ["KDR, no wrinkling"]:
        row = [r for j, r in zip(jobs, results) if j[0] == case and j[1] == method]
        row += [""] * (len(LAMBDAS) - len(row))
        lines.append(f"| {method} | " + " | ".join(row) + " |")
replace_block("lambda-sweep", "\n".join(lines))
print("\n".join(lines))
