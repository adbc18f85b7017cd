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
# Numbers are range-checked (issue #12): NaN, infinities, zero, negative and
# absurd values are refused with the flag (or file:line:col) and the range.
for d in nan NaN inf -inf 0 -1 1e300 86401 abc; do
  expect "duration $d" 2 "^mospec: --duration: .*(not a finite number|outside the accepted range|not a number); expected|accepted range \(0, 86400\] s" -- \
    "$mospec" sim --duration "$d"
done
expect too-many-ticks 2 '^mospec: error: --duration 20000 s at the world.s control_period of 0.001 s is 20000000 control ticks; at most 10\^7' -- \
  "$mospec" sim --base fixed --duration 20000
expect too-many-rows 2 'at most 10\^6 are kept \(raise --log-every\)' -- \
  "$mospec" sim --base fixed --duration 2000 --log x.csv
check too-long-writes-nothing test ! -e x.csv
for n in 0 -1 nan 1e3 1000001; do
  expect "log-every $n" 2 '^mospec: --log-every' -- "$mospec" sim --log-every "$n"
done
for n in -1 nan 1e3 0x10 9007199254740993 18446744073709551616; do
  expect "seed $n" 2 '^mospec: --seed: .*(expected|accepted range) \[0, 9007199254740992\]' -- "$mospec" sim --seed "$n"
done
expect fault-tick-huge 2 "^mospec: error: --fault 'drop@100000000': tick 100000000 is beyond 10\^7" -- \
  "$mospec" sim --fault 'drop@100000000'
world() { printf '%s\n' "$2" > "$1.json"; }
world period-tiny '{ "control_period": 1e-12 }'
expect control-period-tiny 2 '^period-tiny.json:1:21: error: control_period: 1e-12 is outside the accepted range \[1e-05, 1\] s' -- \
  "$mospec" sim period-tiny.json
world period-zero '{ "control_period": 0 }'
expect control-period-zero 2 '^period-zero.json:1:21: error: control_period: 0 is outside' -- "$mospec" sim period-zero.json
world period-negative '{ "control_period": -0.001 }'
expect control-period-negative 2 'control_period: -0.001 is outside' -- "$mospec" sim period-negative.json
world period-huge '{ "control_period": 1e300 }'
expect control-period-huge 2 'control_period: 1e\+300 is outside' -- "$mospec" sim period-huge.json
world period-inf '{ "control_period": 1e999 }'
expect control-period-inf 2 'control_period' -- "$mospec" sim period-inf.json
world substeps '{ "substeps": 1e9 }'
expect substeps-huge 2 'substeps: expected an integer 1..100' -- "$mospec" sim substeps.json
world substeps0 '{ "substeps": 0 }'
expect substeps-zero 2 'substeps: expected an integer 1..100' -- "$mospec" sim substeps0.json
world delay '{ "command_delay_ticks": 2 }'
expect delay-two 2 'command_delay_ticks: expected 0 or 1' -- "$mospec" sim delay.json
world seed-big '{ "seed": 1e300 }'
expect world-seed-huge 2 'seed: expected an integer 0..2\^53' -- "$mospec" sim seed-big.json
world mass '{ "platform": { "mass": 1e300 } }'
expect mass-huge 2 '^mass.json:1:25: error: mass: 1e\+300 is outside the accepted range \(0, 10000\] kg' -- \
  "$mospec" sim mass.json
world effort '{ "actuation": { "effort_limit": [39, 39, 39, -1, 9, 9, 9] } }'
expect effort-negative 2 'effort_limit\[3\]: -1 is outside the accepted range \(0, 10000\] N·m' -- \
  "$mospec" sim effort.json
world size '{ "platform": { "size": [0.6, 0, 0.25] } }'
expect size-zero 2 'size\[1\]: 0 is outside' -- "$mospec" sim size.json
world yaw '{ "initial": { "base_yaw": -1e200 } }'
expect yaw-huge 2 'base_yaw: -1e\+200 is outside the accepted range \[-6.283185307179586, 6.283185307179586\] rad; a bare number is in radians' -- "$mospec" sim yaw.json
world pert '{ "perturbation": { "base_xy": 50 } }'
expect perturbation-huge 2 'base_xy: 50 is outside the accepted range \[0, 1\] m' -- "$mospec" sim pert.json

# Commands beyond the robot's limits are clamped and reported, exit 1: arms
# whose motors give 0.5 N·m cannot hold themselves against gravity.
world weak '{ "base": "fixed", "actuation": { "effort_limit": [0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5] } }'
expect weak-arms 1 'mospec: warning: commands beyond the robot.s limits were clamped' -- \
  "$mospec" sim weak.json --duration 0.05 --log weak.csv
check weak-arms-names-the-joint grep -Eq '^  right_arm.tau\[1\]: clamped in 50 ticks from tick 0, requested up to [0-9.e+-]+ N·m, limit 0.5 N·m' stderr.txt
check weak-arms-log-written test -s weak.csv
expect default-unclamped 0 '' -- "$mospec" sim --base fixed --duration 0.05
check default-no-clamp-warning bash -c "! grep -q clamped '$work/stderr.txt'"

echo keep > kept.csv
expect failed-run-keeps-log 2 '^typo.json' -- "$mospec" sim typo.json --log kept.csv
check no-partial-output test "$(cat kept.csv)" = keep
check no-temporaries test "$(ls -A | grep -c -v -E '\.json$|\.csv$|\.txt$')" -eq 0

finish sim_cli_test
