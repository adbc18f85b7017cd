#!/usr/bin/env bash
# models/examples/payload-inertia: SC0a plus an InertialWrench of a 1 kg
# sphere held at the bracelet (its inertia is the same seen from any frame, so
# a constant seen by the platform is exact). The model validates with zero
# findings (its shapes come with the vocabulary), lowers to one
# inertial-wrench step reading the ten numbers the model states, and runs
# interpreted and generated alike. Variants: a mass of -1 kg is refused by the
# shapes; grams are refused by lowering; a wrench seen by another frame breaks
# a frame rule.
# Usage: payload_inertia_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"
app=models/examples/payload-inertia.json
payload=models/examples/payload-inertia/payload.json

validates_clean "$app"

expect "lowers" 0 "" -- "$mospec" ir "$app"
cp "$work/stdout.txt" "$work/ir.json"
check "one inertial-wrench step" test "$(grep -c '"kind": "inertial-wrench"' "$work/ir.json")" -eq 1
values=$(awk '/"name": "inertia_payload"/{f=1} f&&/"value"/{v=1;next} f&&v&&/\]/{exit} f&&v{gsub(/[ ,]/,""); printf "%s ", $0}' "$work/ir.json")
check "the inertia's ten numbers as stated (got: $values)" \
  test "$values" = "1.0 0.0 0.0 0.0 0.001 0.001 0.001 0.0 0.0 0.0 "

expect "runs (interpreted)" 0 "" -- "$mospec" run "$app" --sim --interpret --duration 1 --log "$work/run.csv"
expect "runs (generated)" 0 "" -- "$mospec" run "$app" --sim --duration 1 --log "$work/gen.csv" \
  --cache "$work/cache"
check "generated and interpreted logs are byte-identical" cmp -s "$work/run.csv" "$work/gen.csv"
check "the generated controller holds the inertia" grep -rq "rigid_body_inertia" "$work/cache"

variant() {  # name, sed expression on the payload file
  rm -rf "$work/tree" && mkdir -p "$work/tree" && cp -r models metamodels robots "$work/tree/"
  sed -i "$2" "$work/tree/$payload"
}
variant negative-mass 's/"mass": 1.0/"mass": -1.0/'
(cd "$work/tree" && "$mospec" validate "$app" > "$work/v.txt" 2>&1)
check "a negative mass is refused by the shapes" grep -q "inertia-payload\|op-payload-inertial-wrench" "$work/v.txt"
check "  ... as a violation" grep -q "^shacl: [1-9]" "$work/v.txt"

variant grams 's/"mass": 1.0,/"mass": 1.0, "unit": "GM",/'
(cd "$work/tree" && "$mospec" ir "$app" > /dev/null 2> "$work/e.txt")
check "grams are refused, not read as kilograms" grep -q "payload.json:[0-9]*:[0-9]*: error: the rigid-body inertia .* states the unit 'GM'" "$work/e.txt"

variant frames 's/^//'
perl -0pi -e 's|("\@id": "wrench-payload-inertial".*?"as-seen-by": ")[^"]*|$1https://mospec.example/robots/kinova-gen3/frame-Bracelet_Link|s' "$work/tree/$payload"
(cd "$work/tree" && "$mospec" ir "$app" > /dev/null 2> "$work/f.txt")
check "a wrench seen by another frame than the inertia is refused" grep -q "wrench.as-seen-by = rigid-body-inertia.as-seen-by" "$work/f.txt"

finish payload_inertia
