#!/usr/bin/env bash
# `mospec run --sim`: the generated controller (generated, built, loaded) and
# the interpreter write byte-identical logs for the same model and seed — on a
# small synthetic model, on sc0a and on SC1's task on another base. The second run of a model reuses the
# cached build.
SRC="$2"
source "$SRC/tests/support/cli_lib.sh"
cd "$SRC" || exit 1
cache="$work/cache"

D="$SRC/tests/ir/data"
expect "tiny, generated" 0 "" -- "$mospec" run --root "$D" "$D/tiny.json" --sim --duration 2.5 \
  --log "$work/tiny-gen.csv" --cache "$cache"
expect "tiny, interpreted" 0 "" -- "$mospec" run --root "$D" "$D/tiny.json" --sim --duration 2.5 \
  --log "$work/tiny-int.csv" --interpret
check "tiny: identical logs" cmp -s "$work/tiny-gen.csv" "$work/tiny-int.csv"
check "tiny: the log has rows" test "$(wc -l < "$work/tiny-gen.csv")" -gt 100

expect "sc0a, generated" 0 "" -- "$mospec" run models/sc0a.json --sim --duration 2 --seed 3 \
  --log "$work/sc0a-gen.csv" --summary "$work/sc0a-gen.json" --cache "$cache"
expect "sc0a, interpreted" 0 "" -- "$mospec" run models/sc0a.json --sim --duration 2 --seed 3 \
  --log "$work/sc0a-int.csv" --interpret
check "sc0a: identical logs" cmp -s "$work/sc0a-gen.csv" "$work/sc0a-int.csv"
expect "sc0a again: the cached build is reused" 0 "" -- "$mospec" run models/sc0a.json --sim \
  --duration 0.1 --log "$work/sc0a-again.csv" --cache "$cache"
check "no rebuild on the second run" bash -c "! grep -q 'generated and built' '$work/stderr.txt'"

# SC1's task on another base (tests/ir/data/diamond-base): both controllers
# and the simulated base run with the numbers lowering read from the model.
expect "diamond base: validates under --strict" 0 "" -- "$mospec" validate --strict \
  tests/ir/data/diamond-base/app.json
expect "diamond base, generated" 0 "" -- "$mospec" run tests/ir/data/diamond-base/app.json --sim \
  --duration 1 --log "$work/diamond-gen.csv" --cache "$cache"
expect "diamond base, interpreted" 0 "" -- "$mospec" run tests/ir/data/diamond-base/app.json \
  --sim --duration 1 --log "$work/diamond-int.csv" --interpret
check "diamond base: identical logs" cmp -s "$work/diamond-gen.csv" "$work/diamond-int.csv"
check "diamond base: the log differs from SC1's on the paper's base" bash -c \
  "'$mospec' run models/sc1.json --sim --duration 1 --interpret --log '$work/sc1-int.csv' 2>/dev/null && ! cmp -s '$work/sc1-int.csv' '$work/diamond-int.csv'"

# Three drives (tests/ir/data/tri-base): the controllers, the robot interface
# and the simulated base are sized by the base's drive count (six wheels).
expect "three-drive base: validates under --strict" 0 "" -- "$mospec" validate --strict \
  tests/ir/data/tri-base/app.json
expect "three-drive base, generated" 0 "" -- "$mospec" run tests/ir/data/tri-base/app.json --sim \
  --duration 1 --log "$work/tri-gen.csv" --cache "$cache"
expect "three-drive base, interpreted" 0 "" -- "$mospec" run tests/ir/data/tri-base/app.json \
  --sim --duration 1 --log "$work/tri-int.csv" --interpret
check "three-drive base: identical logs" cmp -s "$work/tri-gen.csv" "$work/tri-int.csv"
expect "three-drive base: the fourth pivot is no sensor" 2 "no sensor named 'pivot_q\\[3\\]'.*pivot_q\\[0\\.\\.2\\]" \
  -- "$mospec" run tests/ir/data/tri-base/app.json --sim --interpret --duration 0.1 \
  --fault 'nan:pivot_q[3]@5'

finish run-equivalence
