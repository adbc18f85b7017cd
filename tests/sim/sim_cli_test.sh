#!/usr/bin/env bash
# Black-box tests of `mospec sim`: exit codes, located errors, atomic CSV logs
# and byte-identical reruns. Usage: sim_cli_test.sh MOSPEC_BINARY
source "$(dirname "$0")/../support/cli_lib.sh"
cd "$work"

cat > perturbed.json <<'J'
{ "base": "planar",
  "perturbation": { "arm_q": 0.05, "base_xy": 0.02, "base_yaw": 0.05, "pivot_q": 0.3 } }
J
cat > typo.json <<'J'
{ "base": "planar",
  "initial": { "base_yaw": 0.1, "pivots": [0, 0, 0, 0] } }
J

expect default-run 0 'simulated 0.2 s \(200 ticks, wheeled base, gravity controller\)' -- \
  "$mospec" sim --duration 0.2 --log run.csv
check header-row test "$(head -c 22 run.csv)" = "t,right_q0,right_q1,ri"
check row-count test "$(wc -l < run.csv)" -eq 202
expect planar-zero 0 'planar base, zero controller' -- \
  "$mospec" sim --base planar --controller zero --duration 0.1 --log zero.csv
expect seeded-a 0 '' -- "$mospec" sim perturbed.json --seed 5 --duration 0.3 --log a.csv
expect seeded-b 0 '' -- "$mospec" sim perturbed.json --seed 5 --duration 0.3 --log b.csv
expect seeded-c 0 '' -- "$mospec" sim perturbed.json --seed 6 --duration 0.3 --log c.csv
check same-seed-same-bytes cmp -s a.csv b.csv
check other-seed-other-bytes bash -c '! cmp -s a.csv c.csv'
expect log-to-stdout 0 '' -- "$mospec" sim --base fixed --duration 0.01 --log -
check stdout-csv grep -q '^t,right_q0' stdout.txt
expect mount 0 '' -- "$mospec" sim --base fixed --mount --duration 0.05

expect faults 0 '' -- "$mospec" sim --base fixed --duration 0.02 \
  --fault 'nan:right_arm.q[1]@5+3' --fault 'stale:pivot_q[0]@2' --fault drop@3+2
expect bad-fault-sensor 2 "^mospec: error: no sensor named 'right_arm.q\[9\]'" -- \
  "$mospec" sim --fault 'nan:right_arm.q[9]@5'
expect bad-fault-spec 2 "^mospec: error: --fault 'drop@x': 'x' is not a tick count" -- \
  "$mospec" sim --fault 'drop@x'
expect missing-world 2 "^mospec: error: cannot read 'nope.json'" -- "$mospec" sim nope.json
expect located-typo 2 "^typo.json:2:33: error: initial: unknown key 'pivots'" -- \
  "$mospec" sim typo.json
expect bad-base 2 '^mospec: --base: hover not in' -- "$mospec" sim --base hover
expect bad-controller 2 '^mospec: --controller' -- "$mospec" sim --controller pid
expect negative-duration 2 '^mospec: --duration' -- "$mospec" sim --duration -1
expect full-disk 2 "^mospec: error: cannot write '/dev/full'" -- \
  "$mospec" sim --duration 0.01 --log /dev/full
expect unwritable 2 '^mospec: error: ' -- "$mospec" sim --duration 0.01 --log no/such/dir/x.csv
echo keep > kept.csv
expect failed-run-keeps-log 2 '^typo.json' -- "$mospec" sim typo.json --log kept.csv
check no-partial-output test "$(cat kept.csv)" = keep
check no-temporaries test "$(ls -A | grep -c -v -E '^(perturbed|typo)\.json$|\.csv$|\.txt$')" -eq 0

finish sim_cli_test
