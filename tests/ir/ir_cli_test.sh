#!/usr/bin/env bash
# `mospec ir`: the project's scenarios lower, deterministically; a tiny
# synthetic model lowers to the expected schedule; broken variants of it are
# refused with located errors (cycle, unproduced quantity, written constant)
# and no output.
SRC="$2"
source "$SRC/tests/support/cli_lib.sh"
cd "$SRC" || exit 1

for app in sc0a sc0b sc1 sc2; do
  expect "$app lowers" 0 "" -- "$mospec" ir "models/$app.json" -o "$work/$app.1.json"
  "$mospec" ir "models/$app.json" -o "$work/$app.2.json" 2>/dev/null
  check "$app IR is deterministic" cmp -s "$work/$app.1.json" "$work/$app.2.json"
done

expect "an app named without .json (models/sc0a) is models/sc0a.json" 0 "" -- \
  "$mospec" ir models/sc0a -o "$work/sc0a.3.json"
check "... and lowers to the same IR" cmp -s "$work/sc0a.1.json" "$work/sc0a.3.json"

check "sc1 composes the platform twist and logs it" grep -q '"name": "base-velocity-composition.vy"' "$work/sc1.1.json"
# The base step reads the platform wrench (1 driver) and, after it, the running
# flags of the motions that drive it: with none running the base holds.
base_step=$(sed -n '/"kind": "base-force-distribution"/,/"where"/p' "$work/sc1.1.json")
check "sc1's force distribution has one driver" grep -q '"drivers": 1' <<< "$base_step"
check "sc1's force distribution is gated by both whisker motions" \
  test "$(grep -cE '^ +[0-9]+,?$' <<< "$base_step")" -eq 3

D="$SRC/tests/ir/data"
expect "tiny lowers" 0 "" -- "$mospec" ir --root "$D" "$D/tiny.json" -o "$work/tiny.json"
order=$(grep -o '"kind": "[a-z-]*"' "$work/tiny.json" | sed 's/"kind": //; s/"//g' | tr '\n' ' ')
check "tiny schedule: clock, evaluators, monitors, motion, controller" \
  test "$order" = "read-clock evaluate evaluate evaluate level-monitor edge-monitor guarded-motion pid "

variant() {  # NAME SED-EXPRESSION: a copy of the tiny model with one edit
  rm -rf "$work/$1"; mkdir -p "$work/$1/tiny"; cp "$D/tiny.json" "$work/$1/"
  sed "$2" "$D/tiny/model.json" > "$work/$1/tiny/model.json"
}

variant cycle 's/"quantity": "time", "reference-value"/"quantity": "effort", "reference-value"/'
expect "a dependency cycle is refused, located" 1 \
  'tiny/model.json:[0-9]+:[0-9]+: error: .*eval-track.*dependency cycle' -- \
  "$mospec" ir --root "$work/cycle" "$work/cycle/tiny.json" -o "$work/cycle.json"
check "no IR written for a refused model" test ! -e "$work/cycle.json"

variant unproduced 's/"quantity": "time", "reference-value"/"quantity": "orphan", "reference-value"/; s/{ "@id": "effort"/{ "@id": "orphan", "@type": ["Quantity", "Time"], "quantity-kind": "Time", "unit": "SEC" },\n        { "@id": "effort"/'
expect "an unproduced quantity is refused, named and located" 1 \
  "tiny/model.json:[0-9]+:[0-9]+: error: nothing produces 'https://mospec.example/tests/tiny/orphan'" -- \
  "$mospec" ir --root "$work/unproduced" "$work/unproduced/tiny.json"

variant constant 's/"control-signal": "effort"/"control-signal": "time-ref"/'
expect "writing a model constant is refused" 1 "time-ref' has a fixed value in the model" -- \
  "$mospec" ir --root "$work/constant" "$work/constant/tiny.json"

finish ir-cli
