#!/usr/bin/env bash
# The numeric flags of `mospec run` and `mospec trials` (issue #12): NaN,
# infinities, zero, negative and absurd values are refused before anything is
# built or simulated, naming the flag and the accepted range; a run too long to
# simulate (ticks, log rows) is refused naming --duration, the world's
# control_period and --log-every. Usage: run_flags_test.sh MOSPEC SOURCE_DIR
SRC="$2"
source "$SRC/tests/support/cli_lib.sh"
cd "$SRC" || exit 1

run() { "$mospec" run models/sc0a --sim --interpret --cache "$work/cache" "$@"; }
for d in nan -nan inf -inf 0 -0.5 1e300 86401 ten; do
  expect "run --duration $d" 2 \
    "^mospec: --duration: .*(not a finite number|outside the accepted range|not a number).*\(0, 86400\] s" -- \
    run --duration "$d"
done
expect "run: 20000 s at 1 ms is beyond 10^7 ticks" 2 \
  "^mospec: error: --duration 20000 s at the world's control_period of 0.001 s is 20000000 control ticks; at most 10\^7" -- \
  run --duration 20000 --log "$work/never.csv"
check "run: nothing written" test ! -e "$work/never.csv"
expect "... as [invalid-duration] (MOSPEC_DIAGNOSTIC_CODES=1)" 2 \
  "^mospec: error\[invalid-duration\]: --duration 20000 s" -- \
  env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" run models/sc0a --sim --interpret --cache "$work/cache" --duration 20000
expect "run: 10^7 ticks logged every tick is beyond 10^6 rows" 2 \
  "logging every 1 would keep 10000000 rows in memory, at most 10\^6 are kept \(raise --log-every\)" -- \
  run --duration 10000 --log-every 1
for s in -1 nan 1e3 0x10 9007199254740993; do
  expect "run --seed $s" 2 "^mospec: --seed: .*\[0, 9007199254740992\]" -- run --seed "$s"
done
for n in 0 -3 nan 2000000; do
  expect "run --log-every $n" 2 "^mospec: --log-every" -- run --log-every "$n"
done
expect "run --fault at tick 10^8" 2 "tick 100000000 is beyond 10\^7" -- \
  run --duration 0.01 --fault 'drop@100000000'

trials() { "$mospec" trials models/sc0a --sim --interpret -o "$work/trials" "$@"; }
for n in 0 -1 nan 100001 1e3; do
  expect "trials -n $n" 2 "^mospec: -n" -- trials -n "$n"
done
for j in 0 -2 nan 4097; do
  expect "trials --jobs $j" 2 "^mospec: --jobs" -- trials -n 1 --jobs "$j"
done
for d in nan inf 0 -1 1e9; do
  expect "trials --duration $d" 2 "^mospec: --duration: .*\(0, 86400\] s" -- trials -n 1 --duration "$d"
done
expect "trials --seed-base nan" 2 "^mospec: --seed-base: .*\[0, 9007199254740992\]" -- \
  trials -n 1 --seed-base nan
expect "trials --seed-base -1" 2 "^mospec: --seed-base" -- trials -n 1 --seed-base -1
expect "trials: the last seed beyond 2^53" 2 \
  "^mospec: error: --seed-base 9007199254740991 with -n 3: the last trial's seed would exceed 2\^53" -- \
  trials -n 3 --seed-base 9007199254740991
check "trials: nothing started" test ! -e "$work/trials"
for n in 0 nan; do
  expect "trials --log-every $n" 2 "^mospec: --log-every" -- trials -n 1 --log-every "$n"
done

finish run-flags
