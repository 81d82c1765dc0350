#!/usr/bin/python3
"""Issue 39's comparison of the interface mapping with a plain nearest projection (NP): runs the harness's
table (tests/unit/test_mapping_vs_nearest.cpp, MappingVsNearest.DISABLED_Table: sphere, torus and wing-skin
pairs, both directions, random-phase fields), stores every ratio in docs/data/mapping_vs_nearest.json and
plots docs/img/mapping_vs_nearest.png (error / NP's error per settings and direction; 1 = NP).
Usage (from the source root, after scripts/build.sh): studies/mapping/mapping_vs_nearest.py [--tests BIN]"""
import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tests", default=str(ROOT / "build/bin/fsi_unit_tests"))
    ap.add_argument("--json", default=str(ROOT / "docs/data/mapping_vs_nearest.json"))
    ap.add_argument("--png", default=str(ROOT / "docs/img/mapping_vs_nearest.png"))
    a = ap.parse_args(argv)
    env = dict(os.environ, FSI_MAPPING_TABLE_JSON=a.json)
    out = subprocess.run([a.tests, "--gtest_also_run_disabled_tests", "--gtest_filter=MappingVsNearest.DISABLED_Table"],
                         env=env, check=True, capture_output=True, text=True).stdout
    print("\n".join(line for line in out.splitlines() if line.startswith("|")))
    rows = json.load(open(a.json))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    settings = list(dict.fromkeys(r["settings"] for r in rows))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for ax, direction in zip(axes, ("fine to coarse", "coarse to fine")):
        for i, s in enumerate(settings):
            for k, key in enumerate(("max_ratio", "rms_ratio")):
                y = [r[key] for r in rows if r["settings"] == s and r["direction"] == direction]
                x = [i + (k - 0.5) * 0.3] * len(y)
                ax.scatter(x, y, s=12, alpha=0.6, color="C0" if k == 0 else "C1",
                           label=("max" if k == 0 else "RMS") if i == 0 else None)
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_yscale("log")
        ax.set_xticks(range(len(settings)))
        ax.set_xticklabels(settings, rotation=30, ha="right", fontsize=8)
        ax.set_title(f"{direction}: error / nearest projection's")
        ax.grid(True, which="both", axis="y", alpha=0.3)
    axes[0].set_ylabel("nodal error / NP's (24 cases per setting)")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print(f"wrote {a.json} and {a.png}")


if __name__ == "__main__":
    main(sys.argv[1:])
