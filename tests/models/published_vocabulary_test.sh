#!/usr/bin/env bash
# The paper's group's published extension vocabulary (issue #33 item 7):
# contexts under https://secorolab.github.io/metamodels/ resolve to mospec's own
# (metamodels/secorolab/); one mospec has none of is refused where the model
# names it. Joint limits are the published kc-ext:JointLimit and a
# constraint's tolerance the published cstr-ext:tolerance: models still using
# mospec's retired terms (mos-jnt:JointEffortLimit & co., mos-grd:tolerance)
# are refused by validation, lowering and the chain reader, each message
# naming the published term.
# Usage: published_vocabulary_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$work" || exit 2
cp -r "$src/models" "$src/metamodels" "$src/robots" .

# --- an unknown secorolab context: refused at the reference, naming the URL ---
cat > fsm.json <<'JSON'
{
    "@context": [
        "https://secorolab.github.io/metamodels/behaviour/fsm.json"
    ],
    "@id": "https://ex.org/fsm",
    "@type": "FiniteStateMachine"
}
JSON
expect "an unknown secorolab context is refused at the reference" 2 \
  '^fsm\.json:3:[0-9]+: error: .*https://secorolab\.github\.io/metamodels/behaviour/fsm\.json' -- \
  "$mospec" rdf fsm.json

# --- the published contexts load unchanged --------------------------------
expect "the lift (kc-ext:JointLimit, published context URL) validates" 0 "" -- \
  "$mospec" validate models/examples/lift.json --strict
stdout_has "... with no finding" '^shacl: 0 violations, 0 warnings, 0 infos'

# --- retired joint-limit classes ---------------------------------------------
python3 - robots/lift.jsonld <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
for i, n in enumerate(doc["@graph"]):
    if n["@id"] == "effort-limit-lift":
        doc["@graph"][i] = {"@id": "effort-limit-lift", "@type": "JointEffortLimit",
                            "of-joint": "joint-lift", "unit": "N", "limit": 300}
json.dump(doc, open(sys.argv[1], "w"), indent=4)
PY
expect "validation refuses mos-jnt:JointEffortLimit, naming kc-ext:JointLimit" 1 "" -- \
  "$mospec" validate models/examples/lift.json
stdout_has "... at the node, naming the published term" \
  'lift\.jsonld:[0-9]+:[0-9]+: error: <https://mospec\.example/robots/lift/effort-limit-lift>: mos-jnt:JointPositionLimits, JointVelocityLimit and JointEffortLimit are retired: a joint limit is the published kc-ext:JointLimit \(context https://secorolab\.github\.io/metamodels/kinematic-chain/structural-entities-extension\.json\)'
expect "mospec ir refuses it (validation first), naming kc-ext:JointLimit" 1 \
  'lift\.jsonld:[0-9]+:[0-9]+: error: .*JointEffortLimit are retired: a joint limit is the published kc-ext:JointLimit' -- \
  "$mospec" ir models/examples/lift.json -o ir.json
# Reading the chain without validation (the world's arm) refuses it too.
expect "reading the chain for the world refuses it, naming kc-ext:JointLimit" 2 \
  'effort-limit-lift: JointEffortLimit \(mos-jnt\) is retired; a joint limit is the published kc-ext:JointLimit' -- \
  "$mospec" sim models/examples/lift.world.json --duration 0.01

# --- the retired mos-grd:tolerance -------------------------------------------
sed -i 's|"https://secorolab.github.io/metamodels/task/constraint-extension.json"|"https://comp-rob2b.github.io/metamodels/mospec/guards.json"|' \
  models/sc1/03-constraints.json
expect "validation refuses mos-grd:tolerance, naming cstr-ext:tolerance" 1 "" -- \
  "$mospec" validate models/sc1.json
stdout_has "... at the constraint" \
  '03-constraints\.json:[0-9]+:[0-9]+: error: <[^>]*>: mos-grd:tolerance is retired: a constraint.s tolerance is the published cstr-ext:tolerance; list the context https://secorolab\.github\.io/metamodels/task/constraint-extension\.json'
expect "mospec ir refuses it (validation first; lowering too: diagnostic case retired-tolerance)" 1 \
  '03-constraints\.json:[0-9]+:[0-9]+: error: .*mos-grd:tolerance is retired' -- \
  "$mospec" ir models/sc1.json -o ir.json

finish published_vocabulary
