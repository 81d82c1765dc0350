#!/bin/bash
# The whole rung-1 study (docs/AERODYNAMICS.md), serial, one point at a time (about 100 min on one core of a
# shared 2-core machine). Every finished point is appended to OUT/section_runs.json; at the end
# `section_polar.py report` writes docs/data/section_polar.json and the four figures in docs/img/.
# Usage: studies/section/run_study.sh [OUT]   (default studies-out/section, untracked)
set -e
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-$root/studies-out/section}
py=/usr/bin/python3
run() { "$py" "$here/section_polar.py" run --out "$out" "$@" || echo "section_polar: some points failed: $*"; }
# the polars' other angles (4 and 8 deg come from the convergence runs), 2000 iterations at most
sweep=-4,0,6,10,12,14,16
# 1. convergence, three levels, LS(1)-0417 at 4 and 8 deg, both wall treatments, far field at 100 chords
run --section ls0417 --alpha 4,8 --level coarse,medium,fine --wall functions,layers --farfield 100
# 2. NACA 4415 (the 3D canopy's section): the same
run --section naca4415 --alpha 4,8 --level coarse,medium,fine --wall functions,layers --farfield 100
# 3. resolved wall (y+ ~ 1), LS(1)-0417: convergence
run --section ls0417 --alpha 4,8 --level coarse,medium,fine --wall resolved --farfield 100
# 4. the 3D case's own far field (8/16/8 chords) and its one-chord background
run --section ls0417 --alpha 4,8 --level coarse --wall functions
run --section ls0417 --alpha 4,8 --level fine --wall layers
run --section ls0417 --alpha 4 --level coarse --wall functions --background 1
# 5. the 3D case's pseudo-transient pimpleFoam (Courant 4, 300 steps, 1000 at 4 deg; CL at step 100 recorded too)
run --section ls0417 --alpha 8 --level coarse --wall functions --farfield 100 --solver pimple
run --section ls0417 --alpha 4 --level coarse --wall functions --farfield 100 --solver pimple --steps 1000
run --section ls0417 --alpha 4 --level fine --wall layers --farfield 100 --solver pimple
run --section ls0417 --alpha 4 --level medium --wall layers --farfield 100 --solver pimple --steps 1500
# 6. the polars: the 3D case's coarse wall-function mesh and the fine mesh with wall-function layers
run --section ls0417 --alpha=$sweep --level coarse --wall functions --farfield 100 --iterations 2000
run --section ls0417 --alpha=$sweep --level fine --wall layers --farfield 100 --iterations 2000
run --section naca4415 --alpha=$sweep --level coarse --wall functions --farfield 100 --iterations 2000
run --section naca4415 --alpha=$sweep --level fine --wall layers --farfield 100 --iterations 2000
# 7. the resolved wall's polar on the fine mesh (4 and 8 deg from the convergence runs)
run --section ls0417 --alpha=0,10,12,14 --level fine --wall resolved --farfield 100 --iterations 2000
run --section ls0417 --alpha=-4,6,16 --level fine --wall resolved --farfield 100 --iterations 2000
"$py" "$here/section_polar.py" report --runs "$out" --json "$root/docs/data/section_polar.json" --img "$root/docs/img"
