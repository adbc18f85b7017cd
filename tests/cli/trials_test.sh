#!/usr/bin/env bash
# `mospec trials`: two short seeded runs of the tiny IR model (its iri-map is
# relative: --root is passed through to `mospec run`), the manifest written
# last; failing trials give a non-zero exit and are recorded as such.
# Usage: trials_test.sh MOSPEC SOURCE_DIR
. "$(dirname "$0")/../support/cli_lib.sh"
src=$2
cd "$src" || exit 1

expect "two trials" 0 "trials: 2/2 exited 0" -- \
  "$mospec" trials tests/ir/data/tiny.json --sim -n 2 --jobs 2 --duration 0.2 --interpret \
  --root tests/ir/data --seed-base 7 -o "$work/tiny"
check "manifest" test -f "$work/tiny/trials.json"
check "two entries" test "$(grep -c '"seed":' "$work/tiny/trials.json")" -eq 2
check "seeds K+i" grep -q '"seed": 8' "$work/tiny/trials.json"
check "totals" grep -Eq '"passed": 2' "$work/tiny/trials.json"
for i in 0 1; do
  check "trial $i log" test -s "$work/tiny/trial-$i.csv"
  check "trial $i summary" grep -q '"ticks"' "$work/tiny/trial-$i.json"
done
# The tiny model has no distance columns: plot draws its constraints' values
# and its controllers' outputs (the units from the trials' summaries).
expect "plot the tiny trials" 0 "2 trials" -- "$mospec" plot "$work/tiny" -o "$work/default.svg"
check "the default plot draws the tracked constraint" grep -q 'cstr-track.value' "$work/default.svg"
check "and its controller's output" grep -q 'ctrl-track.output' "$work/default.svg"
expect "plot chosen columns" 0 "2 trials" -- \
  "$mospec" plot "$work/tiny" -o "$work/tiny.svg" --distance cstr-track.value --force ctrl-track.output

# Failing trials (no such app): recorded, the first one's messages shown, exit 2;
# a rerun into the same directory first removes the old manifest and trials.
expect "failing trials" 2 "trial 0 \(seed 0\) exited 2" -- \
  "$mospec" trials tests/ir/data/absent.json --sim -n 2 --interpret -o "$work/tiny"
check "failing trials line" grep -q "trials: 0/2 exited 0" "$work/stderr.txt"
check "failures recorded" grep -q '"failed": 2' "$work/tiny/trials.json"
check "no stale log" test ! -e "$work/tiny/trial-0.csv"
expect "bad -n" 2 "" -- "$mospec" trials tests/ir/data/tiny.json --sim -n 0 -o "$work/zero"
expect "unwritable dir" 2 "cannot create the trials directory" -- \
  "$mospec" trials tests/ir/data/tiny.json --sim -n 1 -o /proc/mospec-trials

finish trials_test
