#!/usr/bin/env bash
# The closed-loop sign check before a run (issue #33 item 6): a velocity PI
# whose proportional gain has the wrong sign (it would drive its error away,
# until torques clamp and joints hit their limits) is refused before anything
# runs, at the controller, naming the quantity, the gain and the sign it must
# have. The shipped gains pass. A loop too weak to be judged over the probe
# (sc0a's elbow-height PD through the elbow force) is not judged.
# Usage: loop_sign_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cp -r "$src/models" "$src/robots" "$src/metamodels" "$work/"
cd "$work"
m=https://mospec.example/models

expect "sc0a's own gains pass the check and run" 0 "verdict: ok" -- \
  "$mospec" run --sim --interpret --duration 0.05 models/sc0a.json

# ctrl-angvel-rightarm-ee-x: proportional-gain 100 -> -100.
sed -i '0,/"proportional-gain": "100.0"/s//"proportional-gain": "-100.0"/' models/right-arm/05-constraint-handler.json
grep -q '"-100.0"' models/right-arm/05-constraint-handler.json || fail "the test's edit did not apply"
expect "a wrong-sign gain is refused before the run" 1 \
  "^models/right-arm/05-constraint-handler.json:[0-9]+:[0-9]+: error: the controller '$m/ctrl-angvel-rightarm-ee-x' drives the error of '$m/angvel-rightarm-ee-x' away from 0: at the start, a larger output '$m/eacc-rightarm-ee-ang-x' makes the error smaller \(-[0-9.e-]+ per unit over 20 ticks\), so its proportional-gain must be >= 0, and it is -100$" \
  -- "$mospec" run --sim --interpret --duration 1 models/sc0a.json --log "$work/run.csv"
check "only that gain" test "$(grep -c ': error: ' "$work/stderr.txt")" = 1
check "nothing was run" bash -c "grep -q 'nothing was run' '$work/stderr.txt' && [ ! -e '$work/run.csv' ]"

finish loop_sign_test
