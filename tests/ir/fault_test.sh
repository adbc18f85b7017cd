#!/usr/bin/env bash
# A NaN from a sensor in the middle of a run: the controller never commands a
# non-finite value, holds the arm on the last valid sample while the fault
# lasts, and the task recovers (sc0a's contact force is back within 10 % of
# 20 N at the end). A malformed fault spec is a usage error naming it.
SRC="$2"
source "$SRC/tests/support/cli_lib.sh"
cd "$SRC" || exit 1

for mode in --interpret ""; do
  name=${mode:-generated}
  expect "sc0a with right_arm.q[1] NaN for 100 ticks ($name)" 0 "" -- \
    "$mospec" run models/sc0a --sim $mode --duration 3 --cache "$work/cache" \
    --fault 'nan:right_arm.q[1]@1000+100' --fault 'nan:right_arm.qd[3]@2000+5' \
    --summary "$work/$name.json"
  check "$name: no non-finite command" grep -q '"non_finite": false' "$work/$name.json"
  check "$name: torques within Kinova's limits" grep -q '"torque_limit_exceeded": false' "$work/$name.json"
  fn=$(grep -o '"right_fn": [-0-9.e+]*' "$work/$name.json" | awk '{print $2}')
  check "$name: contact force back to 20 N ± 10 % (got $fn)" \
    awk -v f="$fn" 'BEGIN { exit !(f >= 18 && f <= 22) }'
done

expect "a malformed fault spec is refused" 2 "--fault 'nan:right_arm.q\[1\]': no @TICK" -- \
  "$mospec" run models/sc0a --sim --interpret --duration 0.1 --fault 'nan:right_arm.q[1]'

finish run-faults
