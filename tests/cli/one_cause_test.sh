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

finish one_cause_test
