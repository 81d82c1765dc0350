# Functions the coupled-case tests share (sourced by run_allrun_test.sh and run_interrupt_test.sh; $src: the
# cases/coupled folder of the source tree).

# last_probe CASE: the reference probe in the last window of structure/coupling*.csv (summarize.py's reader)
last_probe() {
  /usr/bin/python3 - "$1" "$src" <<'PY'
import os, sys, yaml
sys.path.insert(0, sys.argv[2])
import summarize
probe = yaml.safe_load(open(os.path.join(sys.argv[1], "reference.yaml")))["probe"]
rows, t, v = summarize.history(sys.argv[1], probe)
print(repr(v[-1]))
PY
}
# close A B TOL: |A - B| <= TOL * max(|A|, |B|)
close() { /usr/bin/python3 -c "import sys; a, b, t = map(float, sys.argv[1:]); print(f'{a:.9g} vs {b:.9g}: relative difference {abs(a-b)/max(abs(a),abs(b)):.2e} (limit {t:g})'); sys.exit(0 if abs(a-b) <= t*max(abs(a),abs(b)) else 1)" "$@"; }
