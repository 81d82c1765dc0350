#!/usr/bin/env bash
# Command-line errors of every subcommand are bad input: exit code 2 and a message (CLI11's own codes, 105
# and up, were returned before); --help still succeeds. Usage: usage_errors.sh FSI
fsi=$1
failed=0 passed=0
expect() {  # expect CODE ARGS...
  local code=$1; shift
  local err
  err=$("$fsi" "$@" 2>&1 >/dev/null)
  local rc=$?
  if [ $rc -eq "$code" ] && { [ "$code" -eq 0 ] || [ -n "$err" ]; }; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1)); echo "FAIL: fsi $*: exit $rc (expected $code), stderr: $err"
  fi
}
expect 2
expect 2 frobnicate
expect 2 run
expect 2 run scene.yaml
expect 2 validate
expect 2 map-check a.msh
expect 2 map-check a.msh b.msh --tolerance
expect 2 plot
expect 2 plot . --color pink
expect 2 plot . --unknown-option
expect 0 --help
expect 0 plot --help
echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
