#!/usr/bin/env bash
# An app drops (mospec/app#drop) what it does not want of the shared files it
# imports, and replaces a shared controller, without forking a file (issue #33
# item 8). The app here is sc0a's, in a scratch directory: it leaves out the
# right arm's vertical-velocity constraint (the constraint, its evaluator, its
# controller and the acceleration constraint that applies it) and swaps the
# elbow-height controller for one with other gains (the user's file adds it to
# sc0a's handler: statements about one IRI from several files merge). A drop that names nothing,
# that would cut an item out of an ordered list, or that names a class, is
# refused at the app's line.
# Usage: drop_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
# A user's tree: the shipped models, robots and the user's own files.
cp -r "$src/models" "$src/robots" "$src/metamodels" "$work/"
mkdir -p "$work/models/mine"
cd "$work"

m=https://mospec.example/models
# APP FILE DROPS...: an app importing sc0a's files and $work/mine.json, dropping
# the given IRIs (a JSON array's items).
write_app() {
  local file=$1 drops=$2
  python3 - "$src/models/sc0a.json" "$file" "$drops" "$work" <<'PY'
import json, sys
app = json.load(open(sys.argv[1]))
app["@context"] = ["https://comp-rob2b.github.io/metamodels/mospec/app.json", app["@context"]]
node = app["@graph"][0]
node["import"].append("https://mospec.example/mine/mine.json")
node["iri-map"]["https://mospec.example/mine/"] = {"path": "models/mine/"}
node["drop"] = json.loads(sys.argv[3])
json.dump(app, open(sys.argv[2], "w"), indent=4)
PY
}
cat > models/mine/mine.json <<'JSON'
{
    "@context": [
        "https://comp-rob2b.github.io/metamodels/task/constraint-handler.json",
        { "@base": "https://mospec.example/models/" }
    ],
    "@graph": [
        {
            "@id": "https://mospec.example/mine/ctrl-elbow-soft",
            "@type": ["Controller", "ProportionalIntegralDerivative"],
            "error-signal": "pos-rightarm-elbow-height-err",
            "control-signal": "frc-rightarm-elbow-height",
            "proportional-gain": "100.0",
            "integral-gain": "0.0",
            "derivative-gain": "20.0"
        },
        {
            "@id": "cstr-hdl-rightarm",
            "@type": "ConstraintHandler",
            "controllers": ["https://mospec.example/mine/ctrl-elbow-soft"]
        }
    ]
}
JSON

write_app models/app.json "[\"$m/cstr-linvel-rightarm-ee-vertical\", \"$m/eval-linvel-rightarm-ee-vertical\",
  \"$m/ctrl-linvel-rightarm-ee-vertical\", \"$m/acc-cstr-rightarm-ee-lin-z\", \"$m/ctrl-pos-rightarm-elbow-height\"]"
cp models/sc0a.world.json models/app.world.json

expect "validates with the drops" 0 "note: dropped '$m/acc-cstr-rightarm-ee-lin-z': 5 statement\(s\) about it \(models/right-arm/06-solver-specification.json:51:[0-9]+\), 1 reference\(s\) to it \(models/right-arm/06-solver-specification.json:61:[0-9]+\)" \
  -- "$mospec" validate --strict models/app.json
stdout_has "validates with zero findings" '^shacl: 0 violations, 0 warnings, 0 infos'
check "each drop is noted at the app's line" \
  test "$(grep -cE "^models/app.json:[0-9]+:[0-9]+: note: dropped" "$work/stderr.txt")" = 5

expect "lowers" 0 "" -- "$mospec" ir models/app.json -o "$work/ir.json"
# The codes (docs/diagnostics.md), as MOSPEC_DIAGNOSTIC_CODES=1 writes them.
expect "a drop is noted as [dropped]" 0 "^models/app.json:[0-9]+:[0-9]+: note\[dropped\]: dropped '" \
  -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" validate --strict models/app.json
check "the dropped controller is not in the program" \
  bash -c "! grep -q 'ctrl-linvel-rightarm-ee-vertical\|acc-cstr-rightarm-ee-lin-z' '$work/ir.json'"
check "the replacement controller is" grep -q 'mine/ctrl-elbow-soft' "$work/ir.json"
check "with its own gain" grep -q '100' "$work/ir.json"

expect "runs" 0 "verdict: ok" -- "$mospec" run --sim --interpret --duration 1 \
  models/app.json --log "$work/run.csv"
check "the replacement's output is logged, the dropped one's is not" \
  bash -c "head -1 '$work/run.csv' | grep -q ctrl-elbow-soft.output && ! head -1 '$work/run.csv' | grep -q 'linvel-rightarm-ee-vertical\|ctrl-pos-rightarm-elbow-height'"

write_app models/typo.json "[\"$m/ctrl-linvel-rightarm-ee-verticle\"]"
expect "a drop that names nothing is refused, with the nearest entity" 2 \
  "^models/typo.json:[0-9]+:[0-9]+: error: the app drops '$m/ctrl-linvel-rightarm-ee-verticle', which no loaded file mentions; did you mean '$m/ctrl-linvel-rightarm-ee-vertical'\?" \
  -- "$mospec" validate models/typo.json
expect "a drop that names nothing is [invalid-drop]" 2 \
  "^models/typo.json:[0-9]+:[0-9]+: error\[invalid-drop\]: the app drops '" \
  -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" validate models/typo.json

write_app models/list.json "[\"$m/prio-rightarm\"]"
expect "a drop that would cut an item out of an ordered list is refused" 2 \
  "^models/list.json:[0-9]+:[0-9]+: error: the app drops '$m/prio-rightarm', but models/sc0a/06-solver-specification.json:[0-9]+:[0-9]+ lists it in an ordered list, which cannot lose one item; drop the entity that holds the list" \
  -- "$mospec" validate models/list.json

write_app models/class.json "[\"https://comp-rob2b.github.io/metamodels/task/constraint-handler#ConstraintHandler\"]"
expect "a drop that names a class is refused" 2 "gives it as a class; only entities can be dropped" \
  -- "$mospec" validate models/class.json

finish drop_test
