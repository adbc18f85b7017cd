#!/usr/bin/env bash
# `validate --strict` reports a class of mospec's metamodels that types a node
# and that no shape covers, or a property of theirs that the model uses and no
# shape's sh:path names ("unshaped-term"), unless
# metamodels/mospec/unshaped-terms.txt lists it; every term that list names is
# defined by some context of the metamodels (no stale entries).
# Usage: unshaped_terms_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cp -r "$src/models" "$src/metamodels" "$src/robots" "$work/"
cd "$work"
list=metamodels/mospec/unshaped-terms.txt
mm=https://comp-rob2b.github.io/metamodels/

expect "sc0a: zero findings under --strict" 0 "" -- "$mospec" validate --strict models/sc0a.json
check "... no unshaped-term" bash -c "! grep -q unshaped-term '$work/stderr.txt'"

# A structural class taken off the list: each use of it is a located finding.
grep -q '^geom-ent:Frame ' "$list" || fail "geom-ent:Frame is not listed any more; adapt this test"
sed -i '/^geom-ent:Frame /d' "$list"
expect "Frame unlisted: without --strict exit 0" 0 "" -- "$mospec" validate models/sc0a.json
check "... and no unshaped-term" bash -c "! grep -q unshaped-term '$work/stderr.txt'"
expect "Frame unlisted: --strict exit 1, located at the first node's @type" 1 \
  "^robots/kinova-gen3.jsonld:[0-9]+:[0-9]+: warning: type <${mm}geometry/structural-entities#Frame> of <https://mospec.example/robots/kinova-gen3/frame-base_link> is covered by no shape \([0-9]+ nodes typed so\): add a shape that targets it, or list it as structural in metamodels/mospec/unshaped-terms.txt" -- \
  "$mospec" validate --strict models/sc0a.json
check "... once" test "$(grep -c unshaped-term "$work/stderr.txt")" -eq 1
expect "... as [unshaped-term] (MOSPEC_DIAGNOSTIC_CODES=1)" 1 \
  "^robots/kinova-gen3.jsonld:[0-9]+:[0-9]+: warning\[unshaped-term\]: type <" -- \
  env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" validate --strict models/sc0a.json
cp "$src/$list" "$list"

# A property taken off the list: its first statement is the finding's place.
grep -q '^slv:solver ' "$list" || fail "slv:solver is not listed any more; adapt this test"
sed -i '/^slv:solver /d' "$list"
expect "slv:solver unlisted: --strict exit 1, located at its statement" 1 \
  "^models/[^:]+:[0-9]+:[0-9]+: warning: property <${mm}task/solver-specification#solver> of <https://mospec.example/models/[^>]+> is constrained by no shape's sh:path \([0-9]+ uses?\): add a shape whose path names it, or list it as structural in metamodels/mospec/unshaped-terms.txt" -- \
  "$mospec" validate --strict models/sc0a.json
expect "... without --strict exit 0" 0 "" -- "$mospec" validate models/sc0a.json
cp "$src/$list" "$list"

# A kind tag taken off the list is reported; declared a subclass of a shaped
# class (rdfs:subClassOf in the shapes graph), it is covered by that class's
# targets.
sed -i '/^cstr:EqualityConstraint /d' "$list"
expect "EqualityConstraint unlisted: --strict finding" 1 \
  "warning: type <${mm}task/constraint#EqualityConstraint> of <[^>]+> is covered by no shape" -- \
  "$mospec" validate --strict models/sc0a.json
printf '@prefix rdfs: <http://www.w3.org/2000/01/rdf-schema#> .\ncstr:EqualityConstraint rdfs:subClassOf cstr:Constraint .\n' \
  >> metamodels/task/constraint.ttl
expect "... a subclass of cstr:Constraint: covered" 0 "" -- "$mospec" validate --strict models/sc0a.json
cp "$src/$list" "$list"
cp "$src/metamodels/task/constraint.ttl" metamodels/task/

# A shape file taken away (off the vocabulary's list and the app's): the class
# its shapes target is no longer covered.
sed -i '\|^task/map.ttl$|d' metamodels/mospec/shape-files.txt
sed -i '\|metamodels/task/map.ttl|d' models/sc0a.json
expect "map.ttl gone: map:View is unshaped under --strict" 1 \
  "^models/[^:]+:[0-9]+:[0-9]+: warning: type <${mm}task/map#View> of <[^>]+> is covered by no shape" -- \
  "$mospec" validate --strict models/sc0a.json
expect "... without --strict exit 0" 0 "" -- "$mospec" validate models/sc0a.json
cp "$src/metamodels/mospec/shape-files.txt" metamodels/mospec/
cp "$src/models/sc0a.json" models/

# A malformed list is a located error.
printf 'geom:Frame  # undeclared prefix\n' > "$list"
expect "undeclared prefix in the list: located error" 2 \
  "unshaped-terms.txt:1:1: error: prefix 'geom' of 'geom:Frame' is not declared" -- \
  "$mospec" validate --strict models/sc0a.json
expect "... as [unshaped-terms] (MOSPEC_DIAGNOSTIC_CODES=1)" 2 \
  "unshaped-terms.txt:1:1: error\[unshaped-terms\]: prefix 'geom'" -- \
  env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" validate --strict models/sc0a.json
cp "$src/$list" "$list"

# No stale entries: a model typing one node with each listed term (as a full
# IRI; "defined" is by IRI, so properties are checked too), whose files use every context of the metamodels, has no undefined-type
# finding. A misspelt entry is caught.
iris() {
  awk '{ sub(/(^|[ \t])#.*/, "") } NF == 0 { next }
       $1 == "@prefix" { p = $2; sub(/:$/, "", p); i = $3; gsub(/[<>]/, "", i); pre[p] = i; next }
       /^</ { gsub(/[<>]/, "", $1); print $1; next }
       { c = index($1, ":"); print pre[substr($1, 1, c - 1)] substr($1, c + 1) }' "$1"
}
stale_model() {
  mkdir -p t
  local imports="" n=0 f
  {
    echo '{ "@context": "'"${mm}"'qudt.json", "@graph": ['
    local sep=""
    while read -r iri; do
      n=$((n+1)); echo "$sep"'{ "@id": "https://mospec.example/t/n'"$n"'", "@type": "'"$iri"'" }'; sep=","
    done < <(iris "$1")
    echo '] }'
  } > t/types.json
  imports='"https://mospec.example/t/types.json"'
  n=0
  for f in $(cd metamodels && find . -name '*.json' | sed 's|^\./||' | sort); do
    n=$((n+1))
    echo '{ "@context": "'"${mm}${f}"'", "@id": "https://mospec.example/t/c'"$n"'" }' > t/c$n.json
    imports="$imports, \"https://mospec.example/t/c$n.json\""
  done
  cat > t/app.json <<APP
{ "@context": { "app": "${mm}application/",
    "import": { "@id": "app:import", "@type": "@id" },
    "iri-map": { "@id": "app:iri-map", "@container": "@id" },
    "path": { "@id": "app:path", "@type": "http://www.w3.org/2001/XMLSchema#string" } },
  "@id": "https://mospec.example/t/app",
  "import": [ $imports ],
  "iri-map": { "${mm}": { "path": "metamodels/" }, "https://mospec.example/t/": { "path": "t/" } } }
APP
  : > t/empty.ttl
}
check "the list names classes" test "$(iris "$list" | grep -c "^${mm}")" -ge 10
stale_model "$list"
expect "every listed class is defined by a metamodels context" 0 "" -- \
  "$mospec" validate --strict --listed-shapes-only --shapes t/empty.ttl t/app.json
printf 'geom-ent:Frmae  # misspelt\n' >> "$list"
stale_model "$list"
expect "... a misspelt entry is an undefined type" 1 "warning: type <${mm}geometry/structural-entities#Frmae> is defined by no loaded JSON-LD context" -- \
  "$mospec" validate --strict --listed-shapes-only --shapes t/empty.ttl t/app.json
cp "$src/$list" "$list"

finish unshaped_terms
