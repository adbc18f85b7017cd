#!/usr/bin/env bash
# Shapes come with the vocabulary: an app whose vocabulary resolves to mospec's
# metamodels gets mospec's shapes for every term it uses, whatever its
# `constraints` list says (metamodels/mospec/shape-files.txt). Apps that lists
# no shape file, or only some, still get the unit, threshold-order and
# reference checks; an app that resolves the vocabulary elsewhere keeps exactly
# its own list (tests/cli/validate_test.sh: the authors' verdicts).
# Usage: vocabulary_shapes_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cp -r "$src/models" "$src/metamodels" "$src/robots" "$work/"
cd "$work"

# An app's shape list, emptied (an app that names no shape file at all).
no_constraints() { sed -i '/"constraints": \[/,/\],/d' "$1"; }

for app in sc0a sc1; do
  no_constraints models/$app.json
  grep -q '"constraints": \[' models/$app.json && fail "$app: constraints list not removed"
  expect "$app without a shape list validates with zero findings (--strict)" 0 "" -- \
    "$mospec" validate --strict models/$app.json
done

# Gravity in newtons: refused although no listed file has the gravity shape.
sed -i 's/"M-PER-SEC2"/"N"/' models/platform/01-world-model.json
expect "wrong gravity unit refused without a shape list" 1 "" -- "$mospec" validate models/sc0a.json
check "... by the gravity shape" grep -q 'gravity is an acceleration' "$work/stdout.txt"
cp "$src/models/platform/01-world-model.json" models/platform/

# SC1's distance tube upside down: the threshold-order check of task/constraint.ttl.
sed -i 's/"0.72"/"0.60"/' models/sc1/00-misc.json
expect "lower > upper refused without a shape list" 1 "" -- "$mospec" validate models/sc1.json
check "... twice, by the threshold-order shape" \
  test "$(grep -c 'lower threshold must be less than the upper threshold' "$work/stdout.txt")" -eq 2
cp "$src/models/sc1/00-misc.json" models/sc1/

# A reference in N-M for a force in N (SC0a's contact force), with the app
# listing only an unrelated shape file: the unit check still applies.
cp "$src/models/sc0a.json" models/sc0a.json
sed -i '/"constraints": \[/,/\],/c\            "constraints": [ "https://comp-rob2b.github.io/metamodels/mospec/time.ttl" ],' models/sc0a.json
grep -n '"frc-rightarm-ee-contact-ref"' -A8 models/sc0a/00-misc.json | grep -q '"unit": "N"' ||
  fail "sc0a's contact force reference is not in N any more; adapt this test"
sed -i '/"frc-rightarm-ee-contact-ref"/,/"unit"/ s/"unit": "N"/"unit": "N-M"/' models/sc0a/00-misc.json
expect "reference in N-M for a force in N refused with a partial shape list" 1 "" -- \
  "$mospec" validate models/sc0a.json
check "... by the reference-unit shape" \
  grep -q 'reference value or threshold has a unit the constrained quantity does not have' "$work/stdout.txt"

finish vocabulary_shapes
