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

# The ceiling example imports the right arm's shared controllers but replaces
# the vertical constraint with its own: the right arm's vertical-velocity PID
# then drives nothing, which lowering says at the controller; --strict refuses.
expect "a controller whose output nothing reads is reported at it" 0 \
  "05-constraint-handler.json:125:[0-9]+: warning: the controller '[^']*ctrl-linvel-rightarm-ee-vertical' drives '[^']*eacc-rightarm-ee-lin-z', which reaches no solver" \
  -- "$mospec" ir models/examples/ceiling.json -o "$work/ceiling.json"
check "... and the program is lowered all the same" test -s "$work/ceiling.json"
expect "... --strict refuses it" 1 "1 finding\(s\) under --strict; nothing was generated" \
  -- "$mospec" ir --strict models/examples/ceiling.json -o "$work/ceiling-strict.json"
check "... and writes nothing" test ! -e "$work/ceiling-strict.json"
expect "sc1's controllers all drive something" 0 "" -- "$mospec" ir models/sc1.json -o "$work/sc1.4.json"
check "... so it warns about none" test ! -s "$work/stderr.txt"

D="$SRC/tests/ir/data"
expect "tiny lowers" 0 "" -- "$mospec" ir --root "$D" "$D/tiny.json" -o "$work/tiny.json"
order=$(grep -o '"kind": "[a-z-]*"' "$work/tiny.json" | sed 's/"kind": //; s/"//g' | tr '\n' ' ')
# The edge monitor the handler lists reports while the motion runs: it follows
# the motion's step; the level monitor no handler lists does not wait for it.
check "tiny schedule: clock, evaluators, monitor, motion, its monitor, controller" \
  test "$order" = "read-clock evaluate evaluate evaluate level-monitor guarded-motion edge-monitor pid "

# The damping and impedance controllers of the published vocabulary lower to
# steps of their registry kinds, with the parameters the model states.
expect "controllers lower" 0 "" -- "$mospec" ir --root "$D" "$D/controllers.json" -o "$work/controllers.json"
order=$(grep -o '"kind": "[a-z-]*"' "$work/controllers.json" | sed 's/"kind": //; s/"//g' | tr '\n' ' ')
check "controllers schedule: clock, evaluators, two motions, two dampers, an impedance" \
  test "$order" = "read-clock evaluate evaluate evaluate evaluate guarded-motion guarded-motion damping damping impedance "
check "... the damper's limits and the spring's stiffness and damping in the IR" \
  grep -Pzq '"damping": \{\n *"maximum-velocity": 0.2,\n *"maximum-force": 10.0\n *\}(.|\n)*"impedance": \{\n *"stiffness": 300.0,\n *"damping": 20.0' "$work/controllers.json"

# A controller two motions' handlers list runs while either motion runs: its
# gate is an any-of step over both running flags (it was gated by the handler
# read last only).
mkdir -p "$work/shared/controllers" && cp "$D/controllers.json" "$work/shared/"
sed 's|^        { "@id": "handler", "@type": "ConstraintHandler", "motion": "motion",|        { "@id": "motion-2", "@type": "GuardedMotion", "when": ["cstr-done"], "while": [], "until": [] },\n        { "@id": "handler-2", "@type": "ConstraintHandler", "motion": "motion-2",\n          "evaluators": ["eval-done"], "controllers": ["damper"] },\n&|' \
  "$D/controllers/model.json" > "$work/shared/controllers/model.json"
expect "a controller shared by two motions lowers" 0 "" -- \
  "$mospec" ir --root "$work/shared" "$work/shared/controllers.json" -o "$work/shared.json"
order=$(grep -o '"kind": "[a-z-]*"' "$work/shared.json" | sed 's/"kind": //; s/"//g' | tr '\n' ' ')
check "... two motions, one any-of, then the damper it gates (got: $order)" \
  test "$order" = "read-clock evaluate evaluate evaluate evaluate guarded-motion guarded-motion guarded-motion any-of damping damping impedance "

variant() {  # NAME SED-EXPRESSION: a copy of the tiny model with one edit
  rm -rf "$work/$1"; mkdir -p "$work/$1/tiny"; cp "$D/tiny.json" "$work/$1/"
  sed "$2" "$D/tiny/model.json" > "$work/$1/tiny/model.json"
}

variant cycle 's/"quantity": "time", "reference-value"/"quantity": "effort", "reference-value"/'
expect "a dependency cycle is refused, located" 1 \
  'tiny/model.json:[0-9]+:[0-9]+: error: .*eval-track.*dependency cycle' -- \
  "$mospec" ir --root "$work/cycle" "$work/cycle/tiny.json" -o "$work/cycle.json"
check "no IR written for a refused model" test ! -e "$work/cycle.json"
# Each lowering error is a line of its own that starts with its location, as
# an editor's error parser reads it (the first used to follow "mospec: error: ").
check "every lowering error line starts with its file:line:col" \
  grep -Eq "^[^ ]*tiny/model.json:[0-9]+:[0-9]+: error: " "$work/stderr.txt"
check "... and none is behind a prefix" \
  bash -c "! grep -Eq '^mospec: error: .*: error: ' '$work/stderr.txt'"

variant unproduced 's/"quantity": "time", "reference-value"/"quantity": "orphan", "reference-value"/; s/{ "@id": "effort"/{ "@id": "orphan", "@type": ["Quantity", "Time"], "quantity-kind": "Time", "unit": "SEC" },\n        { "@id": "effort"/'
expect "an unproduced quantity is refused, named and located" 1 \
  "tiny/model.json:[0-9]+:[0-9]+: error: nothing produces 'https://mospec.example/tests/tiny/orphan'" -- \
  "$mospec" ir --root "$work/unproduced" "$work/unproduced/tiny.json"

variant constant 's/"control-signal": "effort"/"control-signal": "time-ref"/'
expect "writing a model constant is refused" 1 "time-ref' has a fixed value in the model" -- \
  "$mospec" ir --root "$work/constant" "$work/constant/tiny.json"

# Numbers by XSD's lexical rules (issue #12): a gain written "+100.0" is a
# valid xsd:double; so are ".5", "1." and exponent forms; INF and NaN are
# valid lexical forms but not finite gains, and are refused, located.
variant plus 's/"proportional-gain": "2.0"/"proportional-gain": "+100.0"/; s/"integral-gain": "0.5"/"integral-gain": ".5"/; s/"derivative-gain": "0.1"/"derivative-gain": "-1.5E-1"/'
expect "a gain written +100.0 (and .5, -1.5E-1) is a number" 0 "" -- \
  "$mospec" ir --root "$work/plus" "$work/plus/tiny.json" -o "$work/plus.json"
check "... read as 100, 0.5 and -0.15" \
  grep -q '"kp": 100' "$work/plus.json"
for bad in INF -INF NaN; do
  variant "gain$bad" "s/\"proportional-gain\": \"2.0\"/\"proportional-gain\": \"$bad\"/"
  expect "a gain of $bad is refused, located" 1 \
    "tiny/model.json:[0-9]+:[0-9]+: error: the controller 'https://mospec.example/tests/tiny/ctrl-track' has proportional-gain \"$bad\"\\^\\^xsd:double, which is not a finite number" -- \
    "$mospec" ir --root "$work/gain$bad" "$work/gain$bad/tiny.json" -o "$work/gain$bad.json"
done
variant gainhex 's/"proportional-gain": "2.0"/"proportional-gain": "0x10"/'
expect "a gain XSD does not read (0x10) is refused" 1 "proportional-gain|0x10" -- \
  "$mospec" ir --root "$work/gainhex" "$work/gainhex/tiny.json" -o "$work/gainhex.json"

# qudt:value is an xsd:decimal: "2.5" is one, a JSON number 2.5 becomes JSON-LD's
# canonical "2.5E0" and is read too; "2.5e0" written as a string is not a
# decimal, and is refused, located at the value.
variant decimal 's/"value": "2.0"/"value": 2.5/'
expect "a JSON number under the decimal coercion is read" 0 "" -- \
  "$mospec" ir --root "$work/decimal" "$work/decimal/tiny.json" -o "$work/decimal.json"
check "... as 2.5" grep -q '2.5' "$work/decimal.json"
variant notdecimal 's/"value": "2.0"/"value": "2.5e0"/'
expect "an exponent in an xsd:decimal string is refused, located" 1 \
  "tiny/model.json:16:[0-9]+: error: .*time-end.* has the value \"2.5e0\"\\^\\^xsd:decimal, which is not a finite number of its datatype" -- \
  "$mospec" ir --root "$work/notdecimal" "$work/notdecimal/tiny.json" -o "$work/notdecimal.json"

# A timeout (a threshold on the clock's time) must be > 0 s: a negative or
# zero one is decided before the first tick. mospec/time.ttl's Timeout shape
# refuses it at validation (located at the constraint); lowering refuses it
# too (located at the threshold's value) when the shape is not applied (the app
# does not list it, and --listed-shapes-only leaves out the vocabulary's shapes).
for t in -0.5 0 0.0 NaN; do
  variant "timeout$t" "s/\"value\": \"0.5\"/\"value\": \"$t\"/"
  expect "a timeout of $t s is a violation of mospec/time.ttl's Timeout shape" 1 \
    "tiny/model.json:22:[0-9]+: error: <https://mospec.example/tests/tiny/cstr-started>: a timeout \(a threshold on a clock's time\) must be a number of seconds > 0 \[" -- \
    "$mospec" ir --root "$work/timeout$t" "$work/timeout$t/tiny.json" -o "$work/timeout$t.json"
  check "no IR written for a timeout of $t" test ! -e "$work/timeout$t.json"
  # The same model, the app without mospec/time.ttl: lowering refuses it.
  sed -i 's|metamodels/mospec/time.ttl|metamodels/task/monitors.ttl|' "$work/timeout$t/tiny.json"
  if [ "$t" = NaN ]; then
    pattern="tiny/model.json:15:[0-9]+: error: the threshold '.*time-start' of '.*cstr-started' has the value \"NaN\"\\^\\^xsd:decimal, which is not a finite number"
  else
    pattern="tiny/model.json:15:[0-9]+: error: the timeout 'https://mospec.example/tests/tiny/time-start' of 'https://mospec.example/tests/tiny/cstr-started' is -?0(\\.5)? s; a threshold on the clock's time 'https://mospec.example/tests/tiny/time' must be > 0 s"
  fi
  expect "without the shape, lowering refuses a timeout of $t s, located" 1 "$pattern" -- \
    "$mospec" ir --listed-shapes-only --root "$work/timeout$t" "$work/timeout$t/tiny.json" -o "$work/timeout$t.json"
  check "no IR written for a timeout of $t (lowering)" test ! -e "$work/timeout$t.json"
done

# --dump-after PASS: the program after one lowering pass (each pass is
# verified); after the last it is the finished program; an unknown pass is a
# usage error that lists the passes.
expect "--dump-after operators" 0 "" -- \
  "$mospec" ir --root "$D" "$D/tiny.json" --dump-after operators -o "$work/after-operators.json"
check "... is JSON of the IR with its slots" grep -q '"mospec-ir": 1' "$work/after-operators.json"
check "... has no log yet (the log pass comes last)" grep -q '"log": \[\]' "$work/after-operators.json"
expect "--dump-after log" 0 "" -- \
  "$mospec" ir --root "$D" "$D/tiny.json" --dump-after log -o "$work/after-log.json"
check "... is the finished program" cmp -s "$work/after-log.json" "$work/tiny.json"
expect "an unknown pass is refused, naming the passes" 2 \
  "--dump-after: no lowering pass 'lowering'; the passes are properties, clocks, arm-solvers, operators, .*, schedule, unlisted-controllers, log" -- \
  "$mospec" ir --root "$D" "$D/tiny.json" --dump-after lowering

finish ir-cli
