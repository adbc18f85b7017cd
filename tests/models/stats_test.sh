#!/usr/bin/env bash
# `mospec stats`: Table I of the paper reproduced for the authors' four apps
# (skipped, saying so, when ../shared is absent) and the counting rules on a
# small app of our own. Usage: stats_test.sh MOSPEC_BINARY SHARED_DIR
set -u
mospec=$(realpath "$1")
shared=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

check() {  # check NAME EXPECTED ACTUAL
  if [ "$2" != "$3" ]; then
    echo "FAIL $1"; echo "  expected: $2"; echo "  actual:   $3"; failures=$((failures+1))
  else
    echo "ok   $1"
  fi
}

# Table I (World model, Constraints, Controllers, 3D-1D Maps, Solver specification).
upstream="$shared/upstream/motion-spec-ral"
if [ -d "$upstream/models" ]; then
  cd "$upstream"
  check "Table I single arm" $'35/446\t7/78\t12/138\t7/79\t10/105' \
    "$("$mospec" stats models/sc0a-right-arm.json --format row 2>/dev/null)"
  check "Table I two arms" $'89/1128\t18/200\t24/276\t20/200\t20/210' \
    "$("$mospec" stats models/sc0b-dual-arm.json --format row 2>/dev/null)"
  check "Table I SC1" $'100/1258\t18/200\t34/416\t20/200\t24/248' \
    "$("$mospec" stats models/sc1.json --format row 2>/dev/null)"
  check "Table I SC2" $'100/1258\t18/200\t34/416\t20/200\t26/266' \
    "$("$mospec" stats models/sc2.json --format row 2>/dev/null)"
else
  echo "skip Table I: $upstream is absent"
fi

# Counting rules on our own app.
cd "$work"
mkdir -p m
cat > app.json <<'J'
{ "@context": { "app": "https://comp-rob2b.github.io/metamodels/application/",
    "import": { "@id": "app:import", "@type": "@id" },
    "iri-map": { "@id": "app:iri-map", "@container": "@id" },
    "path": { "@id": "app:path" } },
  "@id": "https://ex.org/app",
  "import": [ "https://ex.org/m/01-world-model.json", "https://ex.org/m/00-misc.json",
              "https://ex.org/m/01-world-model.json", "https://ex.org/m/07-scenario.json",
              "https://ex.org/m/02-map.json" ],
  "iri-map": { "https://ex.org/m/": { "path": "m/" } } }
J
# 2 entities; lines as Python's json.dumps(@graph, indent=4) writes them:
# [, {, "@id", "@type": [, 2 types, ], "p": [], "q": {}, "n": 1.5, "s": "é", }, {, "@id", }, ] = 16
cat > m/01-world-model.json <<'J'
{ "@context": { "@vocab": "https://ex.org/v#" },
  "@graph": [ { "@id": "https://ex.org/a", "@type": ["A", "B"], "p": [], "q": {}, "n": 1.5, "s": "é" },
              { "@id": "https://ex.org/b" } ] }
J
cat > m/00-misc.json <<'J'
{ "@context": { "@vocab": "https://ex.org/v#" }, "@graph": [ { "@id": "https://ex.org/u" } ] }
J
# No @graph: one entity, the object without @context: {, "@id", "x": [, 1, 2, ], } = 7
cat > m/07-scenario.json <<'J'
{ "@context": { "@vocab": "https://ex.org/v#" }, "@id": "https://ex.org/s", "x": [1, 2] }
J
cat > m/02-map.json <<'J'
{ "@context": { "@vocab": "https://ex.org/v#" }, "@graph": [] }
J
check "own app" $'2/16\t0/0\t0/0\t0/1\t1/7' "$("$mospec" stats app.json --format row 2>&1)"
if command -v python3 > /dev/null; then
  py=$(python3 -c 'import json; g=json.load(open("m/01-world-model.json"))["@graph"]; print(len(json.dumps(g, indent=4).split("\n")))')
  check "python agrees on lines" "16" "$py"
else
  echo "SKIP python agrees on lines: python3 is not installed (the cross-check with Python's json.dumps needs it)"
fi
table=$("$mospec" stats app.json --files 2>&1)
check "table row" "world model                    2      16" "$(echo "$table" | grep '^world model')"
check "misc listed, not counted" "1" "$(echo "$table" | grep -c 'not counted.*00-misc.json')"
check "duplicate import counted once" "1" "$(echo "$table" | grep -c '01-world-model.json')"
"$mospec" stats missing.json > /dev/null 2>&1
check "missing app exits 2" "2" "$?"

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
