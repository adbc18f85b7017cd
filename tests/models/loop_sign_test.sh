#!/usr/bin/env bash
# The closed-loop check before a run (issue #33 item 6), at the statement of
# the gain (the controller's node: the loader places a node's statements there),
# before anything runs:
# - a velocity PI whose proportional gain has the wrong sign (it would drive
#   its error away, until torques clamp and joints hit their limits) is
#   refused, naming the quantity, the gain and the sign it must have;
# - so is a slow position loop's (sc0a's elbow-height PD through the elbow
#   force: its error moves nanometres per newton over the probe);
# - a gain of the right sign but too high for the 1 ms tick (the velocity PI's
#   kp 3000: the loop oscillates tick by tick, growing) is refused as an
#   unstable loop, with the scale of the gains that is stable.
# The shipped gains pass.
# Usage: loop_sign_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cp -r "$src/models" "$src/robots" "$src/metamodels" "$work/"
cd "$work"
m=https://mospec.example/models

expect "sc0a's own gains pass the check and run" 0 "verdict: ok" -- \
  "$mospec" run --sim --interpret --duration 0.05 models/sc0a.json

# set_first_gain FROM TO: the shipped controllers, with the first
# proportional-gain FROM set to TO.
handlers=models/right-arm/05-constraint-handler.json
set_first_gain() {
  cp "$src/$handlers" "$handlers"
  sed -i "0,/\"proportional-gain\": \"$1\"/s//\"proportional-gain\": \"$2\"/" "$handlers"
  grep -q "\"$2\"" "$handlers" || fail "the test's edit to $2 did not apply"
}

# ctrl-angvel-rightarm-ee-x: proportional-gain 100 -> -100.
set_first_gain 100.0 -100.0
expect "a wrong-sign gain is refused before the run" 1 \
  "^models/right-arm/05-constraint-handler.json:41:[0-9]+: error: the controller '$m/ctrl-angvel-rightarm-ee-x' drives the error of '$m/angvel-rightarm-ee-x' away from 0: at the start, a larger output '$m/eacc-rightarm-ee-ang-x' makes the error smaller \(-[0-9.e-]+ per unit after 5 ticks\), so its proportional-gain must be >= 0, and it is -100$" \
  -- "$mospec" run --sim --interpret --duration 1 models/sc0a.json --log "$work/run.csv"
check "only that gain" test "$(grep -c ': error: ' "$work/stderr.txt")" = 1
check "nothing was run" bash -c "grep -q 'nothing was run' '$work/stderr.txt' && [ ! -e '$work/run.csv' ]"
expect "... as [loop-sign] (MOSPEC_DIAGNOSTIC_CODES=1)" 1 \
  "^models/right-arm/05-constraint-handler.json:41:[0-9]+: error\[loop-sign\]: the controller '$m/ctrl-angvel-rightarm-ee-x' drives" \
  -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" run --sim --interpret --duration 1 models/sc0a.json

# The elbow-height PD's proportional-gain 200 -> -200.
set_first_gain 200.0 -200.0
expect "a slow loop's wrong-sign gain is refused too" 1 \
  "^models/right-arm/05-constraint-handler.json:20:[0-9]+: error: the controller '$m/ctrl-pos-rightarm-elbow-height' drives the error of '$m/pos-rightarm-elbow-height' away from 0: at the start, a larger output '$m/frc-rightarm-elbow-height' makes the error smaller \(-[0-9.]+e-0[89] per unit after 5 ticks\), so its proportional-gain must be >= 0, and it is -200$" \
  -- "$mospec" run --sim --interpret --duration 1 models/sc0a.json

# The x angular-velocity PI's proportional-gain 100 -> 3000.
set_first_gain 100.0 3000.0
expect "a gain too high for the tick is refused as an unstable loop" 1 \
  "^models/right-arm/05-constraint-handler.json:41:[0-9]+: error: the loop of the controller '$m/ctrl-angvel-rightarm-ee-x' on '$m/angvel-rightarm-ee-x' is unstable at the start: .*its gains \(proportional-gain 3000, integral-gain 2500, derivative-gain 0\) put a pole at \|z\| = 1\.[0-9]+, which grows the error e-fold every [0-9.]+ ms; with every gain scaled by 0\.[0-9]+ or less that pole is inside the unit circle" \
  -- "$mospec" run --sim --interpret --duration 1 models/sc0a.json
check "one loop" test "$(grep -c ': error: ' "$work/stderr.txt")" = 1
expect "... as [unstable-loop] (MOSPEC_DIAGNOSTIC_CODES=1)" 1 \
  "^models/right-arm/05-constraint-handler.json:41:[0-9]+: error\[unstable-loop\]: the loop of the controller '$m/ctrl-angvel-rightarm-ee-x'" \
  -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" run --sim --interpret --duration 1 models/sc0a.json
check "the summary line counts the loops" grep -qE "^mospec: 1 controller loop\(s\) that would diverge; nothing was run \(--run-diverging runs it anyway\)$" "$work/stderr.txt"

finish loop_sign_test
