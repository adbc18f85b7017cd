#!/usr/bin/env bash
# One cause, one error (issue #33 item 9): a misspelt reference in a model is
# one error, at the reference, with the nearest IRI a file defines; what SHACL
# reports because of it (the reference is not a controller; the motion's guard
# has no controller acting on it) are notes naming that error.
# Usage: one_cause_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cp -r "$src/models" "$src/robots" "$src/metamodels" "$work/"
cd "$work"
m=https://mospec.example/models

# The handler lists ctrl-angvel-rightarm-ee-xx instead of ...-x.
sed -i 's/"ctrl-angvel-rightarm-ee-x",/"ctrl-angvel-rightarm-ee-xx",/' models/sc0a/05-constraint-handler.json
expect "a misspelt controller is refused" 1 "" -- "$mospec" validate models/sc0a.json
check "one error" test "$(grep -c ': error: ' "$work/stdout.txt")" = 1
stdout_has "the error is at the reference, with the nearest defined IRI" \
  "^models/sc0a/05-constraint-handler.json:[0-9]+:[0-9]+: error: <$m/cstr-hdl-rightarm>: names <$m/ctrl-angvel-rightarm-ee-xx>, which no loaded file defines: .*; did you mean <$m/ctrl-angvel-rightarm-ee-x>\?"
stdout_has "the handler's other result about it is a note" \
  "^models/sc0a/05-constraint-handler.json:[0-9]+:[0-9]+: note: <$m/cstr-hdl-rightarm>: a handler's controllers are controllers .*\(likely a consequence of the error at models/sc0a/05-constraint-handler.json:[0-9]+:[0-9]+, about <$m/ctrl-angvel-rightarm-ee-xx>: fix that first\)"
stdout_has "the motion's guard without a controller is a note" \
  "^models/sc0a/04-motion-specification.json:[0-9]+:[0-9]+: note: <$m/motion-rightarm>: <$m/cstr-angvel-rightarm-ee-x> is a per-condition .*likely a consequence of the error at models/sc0a/05-constraint-handler.json"
stdout_has "the summary counts them" \
  '^shacl: 3 violations, 0 warnings, 0 infos \(2 of them likely consequences of another, as noted\)$'

# A constraint's quantity misspelt: one error, with the nearest quantity.
cp "$src/models/sc0a/05-constraint-handler.json" models/sc0a/
sed -i 's/"quantity": "pos-rightarm-ee-x"/"quantity": "pos-rightarm-ee-xz"/' models/sc0a/03-constraints.json
grep -q 'pos-rightarm-ee-xz' models/sc0a/03-constraints.json || fail "the test's edit did not apply"
expect "a misspelt quantity is refused" 1 "" -- "$mospec" validate models/sc0a.json
check "one error for the misspelt quantity" test "$(grep -c ': error: ' "$work/stdout.txt")" = 1
stdout_has "with the nearest quantity" "names <$m/pos-rightarm-ee-xz>, which no loaded file defines: .*; did you mean <$m/pos-rightarm-ee-x>\?"

# A misspelt joint of a solver's chain (a joint quantity's, a joint force's):
# one error each, at the node that names it, listing the chain's joints
# (sorted); nothing else follows from it.
r=https://mospec.example/robots/kinova-gen3
sed -i '0,/joint-Actuator4"/s//joint-Actuatr4"/' models/examples/joint-limit/00-misc.json
sed -i 's/"attached-to": "https:\/\/mospec.example\/robots\/kinova-gen3\/joint-Actuator4"/"attached-to": "https:\/\/mospec.example\/robots\/kinova-gen3\/joint-Actuator44"/' \
  models/examples/joint-limit/06-solver-specification.json
grep -q 'joint-Actuatr4' models/examples/joint-limit/00-misc.json &&
  grep -q 'joint-Actuator44' models/examples/joint-limit/06-solver-specification.json ||
  fail "the test's edits did not apply"
expect "misspelt joints are refused by validation" 1 "" -- "$mospec" validate models/examples/joint-limit.json
check "one error per misspelt joint" test "$(grep -c ': error: ' "$work/stdout.txt")" = 2
joints="$r/joint-Actuator1, $r/joint-Actuator2, $r/joint-Actuator3, $r/joint-Actuator4, $r/joint-Actuator5, $r/joint-Actuator6, $r/joint-Actuator7"
stdout_has "the joint quantity's, with the chain's joints" \
  "^models/examples/joint-limit/00-misc.json:[0-9]+:[0-9]+: error: <https://mospec.example/models/examples/joint-limit/q-rightarm-j4>: no joint <$r/joint-Actuatr4> in the chain <$r/chain> \(the chain of the solver that outputs it\); its joints are $joints "
stdout_has "the joint force's, with the chain's joints" \
  "^models/examples/joint-limit/06-solver-specification.json:[0-9]+:[0-9]+: error: <[^>]*>: no joint <$r/joint-Actuator44> in the chain <$r/chain> \(the chain of the solver whose drivers list it\); its joints are $joints "
stdout_has "no other finding" '^shacl: 2 violations, 0 warnings, 0 infos$'

finish one_cause_test
