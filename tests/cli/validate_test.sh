#!/usr/bin/env bash
# Black-box tests of `mospec validate`: verdicts, exit codes, located one-line
# errors for bad shapes, report formats, --strict, and no partial outputs.
# Usage: validate_test.sh MOSPEC_BINARY
# Run from ../shared/upstream/motion-spec-ral (ctest sets WORKING_DIRECTORY) for
# the authors' scenario verdicts; elsewhere those are skipped with a message.
source "$(dirname "$0")/../support/cli_lib.sh"
upstream=$PWD



# ---- the authors' scenarios --------------------------------------------------
if [ -f models/sc1.json ] && [ -d comp-rob2b/metamodels ]; then
  dcm='<https://comp-rob2b.github.io/metamodels/geometry/coordinates#DirectionCosineXYZ>'
  for case in sc0a-right-arm:1 sc0b-dual-arm:2 sc1:2 sc2:2; do
    app=${case%%:*}; n=${case##*:}
    expect "upstream-$app" 1 '' -- "$mospec" validate "models/$app.json"
    results=$(grep -c ': error: ' "$work/stdout.txt")
    xone=$(grep -A1 ": error: <https://secorolab.github.io/models/demo/pose-[a-z]*-platform-shoulder>: .*\[sh:XoneConstraintComponent" "$work/stdout.txt" | grep -c "note: the shape that fired: $dcm")
    [ "$results" -eq "$n" ] && [ "$xone" -eq "$n" ] || fail "upstream-$app: $results results, $xone Xone on DirectionCosineXYZ; expected $n"
    stdout_has "upstream-$app" "^shacl: $n violations?, 0 warnings, 0 infos$"
  done
  expect upstream-sc1-location 1 '' -- "$mospec" validate models/sc1.json
  stdout_has upstream-sc1-location '^models/01-right-arm/00-misc\.json:59:20: error: <https://secorolab\.github\.io/models/demo/pose-rightarm-platform-shoulder>: '
  stdout_has upstream-sc1-location '^models/02-left-arm/00-misc\.json:59:20: error: <https://secorolab\.github\.io/models/demo/pose-leftarm-platform-shoulder>: '
  cp "$work/stdout.txt" "$work/sc1-first.txt"
  expect upstream-sc1-deterministic 1 '' -- "$mospec" validate models/sc1.json
  cmp -s "$work/stdout.txt" "$work/sc1-first.txt" || fail "upstream-sc1-deterministic: two runs differ"
  # One SPARQL budget for the whole command (#32): each of sc1's SPARQL
  # evaluations takes a few steps, all of them together more than 100.
  expect upstream-sc1-sparql-budget 2 '^comp-rob2b/metamodels/.*\.ttl:[0-9]+:[0-9]+: error: SPARQL constraint <[^>]*> of shape <[^>]*> on focus node <[^>]*>: SPARQL evaluation stopped after 100 steps \(the command.s step limit' -- "$mospec" validate models/sc1.json --sparql-steps 100
  if [ -s "$work/stdout.txt" ]; then fail "upstream-sc1-sparql-budget: a report was written"; fi
  expect upstream-sc1-turtle 1 '' -- "$mospec" validate models/sc1.json --format turtle
  [ "$(grep -c 'sh:sourceConstraintComponent sh:XoneConstraintComponent' "$work/stdout.txt")" -eq 2 ] || fail "upstream-sc1-turtle: expected 2 Xone results"
  stdout_has upstream-sc1-turtle 'sh:conforms false'
  expect upstream-sc1-jsonld 1 '' -- "$mospec" validate models/sc1.json --format jsonld -o "$work/report.jsonld"
  # The JSON-LD report is JSON-LD: mospec's own loader reads it back.
  expect upstream-sc1-jsonld-reads 0 '' -- "$mospec" rdf --format ntriples "$work/report.jsonld"
  [ "$(grep -c '<http://www.w3.org/ns/shacl#sourceConstraintComponent> <http://www.w3.org/ns/shacl#XoneConstraintComponent>' "$work/stdout.txt")" -eq 2 ] || fail "upstream-sc1-jsonld: expected 2 Xone results in its RDF"
  stdout_has upstream-sc1-jsonld-reads '<http://www.w3.org/ns/shacl#conforms> "false"\^\^<http://www.w3.org/2001/XMLSchema#boolean>'
  expect upstream-sc1-strict 1 'models/03-scenarios/01-world-model\.json:[0-9]+:[0-9]+: warning: type <https://secorolab\.github\.io/models/demo/Direction> is defined by no loaded JSON-LD context or shape' -- "$mospec" validate --strict models/sc1.json
  grep -Eq 'task/constraint-handler\.ttl:[0-9]+:[0-9]+: warning: shape <https://comp-rob2b\.github\.io/metamodels/task/constraint-handler#Monitor> has targets but selects no focus node' "$work/stderr.txt" || fail "upstream-sc1-strict: unused shape not reported"
  grep -Eq 'finding\(s\) under --strict' "$work/stderr.txt" || fail "upstream-sc1-strict: no summary"
  # --root: the same verdict from elsewhere.
  (cd "$work" && "$mospec" validate --root "$upstream" "$upstream/models/sc0a-right-arm.json" > root.txt 2>/dev/null; echo $? > root.rc)
  [ "$(cat "$work/root.rc")" -eq 1 ] && grep -q '^shacl: 1 violation,' "$work/root.txt" || fail "upstream-root: --root did not give sc0a's verdict"
else
  echo "validate_test: skipping the authors' scenarios: run from ../shared/upstream/motion-spec-ral (cwd is $PWD)"
fi

# ---- small models written here -------------------------------------------------
cd "$work"
mkdir -p shapes
cat > model.json <<'J'
{ "@context": { "ex": "http://example.org/", "name": "ex:name", "Person": "ex:Person" },
  "@graph": [
    { "@id": "ex:alice", "@type": "Person", "name": "Alice" },
    { "@id": "ex:bob", "@type": "Person" }
  ] }
J
cat > good-model.json <<'J'
{ "@context": { "ex": "http://example.org/", "name": "ex:name", "Person": "ex:Person" },
  "@id": "ex:alice", "@type": "Person", "name": "Alice" }
J
cat > undefined-type.json <<'J'
{ "@context": { "ex": "http://example.org/", "name": "ex:name" },
  "@id": "ex:carol", "@type": "ex:Robot", "name": "Carol" }
J
cat > shapes/person.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ; sh:targetClass ex:Person ;
  sh:property [ sh:path ex:name ; sh:minCount 1 ] .
T
cat > shapes/person.jsonld <<'J'
{ "@context": { "sh": "http://www.w3.org/ns/shacl#", "ex": "http://example.org/" },
  "@id": "ex:PersonShape", "@type": "sh:NodeShape",
  "sh:targetClass": { "@id": "ex:Person" },
  "sh:property": { "sh:path": { "@id": "ex:name" },
                   "sh:minCount": { "@value": "1", "@type": "http://www.w3.org/2001/XMLSchema#integer" } } }
J
cat > shapes/warning.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:NameWarning a sh:NodeShape ; sh:targetClass ex:Person ;
  sh:property [ sh:path ex:name ; sh:minCount 1 ; sh:severity sh:Warning ] .
T
cat > shapes/unused.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:RobotShape a sh:NodeShape ; sh:targetClass ex:Drone ;
  sh:property [ sh:path ex:name ; sh:minCount 1 ] .
T
cat > shapes/empty.ttl <<'T'
# no shapes at all
T
cat > app.json <<'J'
{ "@context": { "app": "https://comp-rob2b.github.io/metamodels/application/",
    "import": { "@id": "app:import", "@type": "@id" },
    "constraints": { "@id": "app:constraints", "@type": "@id", "@container": "@set" },
    "iri-map": { "@id": "app:iri-map", "@container": "@id" },
    "path": { "@id": "app:path", "@type": "http://www.w3.org/2001/XMLSchema#string" } },
  "@id": "https://models.example/app",
  "import": [ "https://models.example/model.json" ],
  "constraints": [ "https://shapes.example/person.ttl" ],
  "iri-map": { "https://models.example/": { "path": "./" },
               "https://shapes.example/": { "path": "shapes/" } } }
J
sed 's#shapes.example/person.ttl#shapes.example/missing.ttl#' app.json > app-missing.json
sed 's#https://shapes.example/person.ttl#https://elsewhere.example/person.ttl#' app.json > app-unmapped.json
cat > bad-syntax.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ;
  sh:targetClass ex:Person
  sh:property [ sh:path ex:name ] .
T
cat > bad-string.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ;
  sh:message "never closed ;
  sh:targetClass ex:Person .
T
cat > bad-sparql.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ;
  sh:targetClass ex:Person ;
  sh:sparql [
    sh:select """
      SELECT $this
      WHERE {
        $this <http://example.org/name> ?n .
        FILTER(?n = )
      }
    """ ] .
T
cat > unsupported-sparql.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ;
  sh:targetClass ex:Person ;
  sh:sparql [ sh:select "SELECT ?x WHERE { ?x ?p ?o }" ] .
T
cat > bad-path.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ;
  sh:targetClass ex:Person ;
  sh:property [ sh:path [ ex:strangePath ex:name ] ; sh:minCount 1 ] .
T
cat > bad-path-literal.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ;
  sh:targetClass ex:Person ;
  sh:property [ sh:path "name" ; sh:minCount 1 ] .
T
cat > bad-count.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <http://example.org/> .
ex:PersonShape a sh:NodeShape ;
  sh:targetClass ex:Person ;
  sh:property [ sh:path ex:name ;
                sh:minCount "one" ] .
T
cat > bad-json.jsonld <<'J'
{ "@context": { "sh": "http://www.w3.org/ns/shacl#" },
  "@id": "http://example.org/S"
  "@type": "sh:NodeShape" }
J
printf '\x00\xff\xfe garbage \x01 <<<' > garbage.ttl

expect help 0 '' -- "$mospec" validate --help
expect no-input 2 'mospec:' -- "$mospec" validate
expect bad-format 2 'mospec:' -- "$mospec" validate --format xml model.json --shapes shapes/person.ttl
expect no-shapes 2 '^mospec: error: no shapes to validate against' -- "$mospec" validate model.json
expect conforms 0 '' -- "$mospec" validate good-model.json --shapes shapes/person.ttl
stdout_has conforms '^shacl: 0 violations, 0 warnings, 0 infos$'
expect violation 1 '' -- "$mospec" validate model.json --shapes shapes/person.ttl
stdout_has violation '^model\.json:4:[0-9]+: error: <http://example\.org/bob>: .*\[sh:MinCountConstraintComponent, path <http://example\.org/name>\]$'
stdout_has violation '^shapes/person\.ttl:4:[0-9]+: note: the shape that fired: \[\]$'
stdout_has violation '^shacl: 1 violation, 0 warnings, 0 infos$'
expect jsonld-shapes 1 '' -- "$mospec" validate model.json --shapes shapes/person.jsonld
stdout_has jsonld-shapes '^model\.json:4:[0-9]+: error: <http://example\.org/bob>: .*sh:MinCountConstraintComponent'
expect two-shape-files 1 '' -- "$mospec" validate model.json --shapes shapes/person.ttl --shapes shapes/warning.ttl
stdout_has two-shape-files '^shacl: 1 violation, 1 warning, 0 infos$'
expect warning-only 0 '' -- "$mospec" validate model.json --shapes shapes/warning.ttl
stdout_has warning-only '^model\.json:4:[0-9]+: warning: <http://example\.org/bob>'
expect warning-strict 1 'under --strict' -- "$mospec" validate --strict model.json --shapes shapes/warning.ttl
expect empty-shapes 0 '' -- "$mospec" validate model.json --shapes shapes/empty.ttl
expect unused-not-strict 0 '' -- "$mospec" validate good-model.json --shapes shapes/unused.ttl
expect unused-strict 1 '^shapes/unused\.ttl:3:[0-9]+: warning: shape <http://example\.org/RobotShape> has targets but selects no focus node' -- "$mospec" validate --strict good-model.json --shapes shapes/unused.ttl
expect unused-strict-code 1 '^shapes/unused\.ttl:3:[0-9]+: warning\[shape-unused\]: shape <' -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" validate --strict good-model.json --shapes shapes/unused.ttl
expect undefined-type-strict 1 '^undefined-type\.json:2:[0-9]+: warning: type <http://example\.org/Robot> is defined by no loaded JSON-LD context or shape' -- "$mospec" validate --strict undefined-type.json --shapes shapes/person.ttl
expect defined-by-shape-strict 0 '' -- "$mospec" validate --strict good-model.json --shapes shapes/person.ttl
expect app 1 '' -- "$mospec" validate app.json
stdout_has app '^\./model\.json:4:[0-9]+: error: <http://example\.org/bob>|^model\.json:4:[0-9]+: error: <http://example\.org/bob>'
expect app-missing-shape-file 2 "^app-missing\.json:[0-9]+:[0-9]+: error: cannot read shape file 'shapes/missing\.ttl'.*No such file" -- "$mospec" validate app-missing.json
expect app-unmapped-shape-file 2 '^app-unmapped\.json:[0-9]+:[0-9]+: error: shape file <https://elsewhere\.example/person\.ttl> is not mapped to a local path' -- "$mospec" validate app-unmapped.json
expect app-map-flag 1 '' -- "$mospec" validate app-unmapped.json --map https://elsewhere.example/=shapes
expect missing-shapes 2 "^mospec: error: cannot read shape file 'missing\.ttl': No such file" -- "$mospec" validate model.json --shapes missing.ttl -o out1.txt
[ ! -e out1.txt ] || fail "missing-shapes: output written"
expect directory-shapes 2 "^mospec: error: cannot read shape file 'shapes'" -- "$mospec" validate model.json --shapes shapes
expect turtle-syntax 2 '^bad-syntax\.ttl:5:[0-9]+: error: ' -- "$mospec" validate model.json --shapes bad-syntax.ttl -o out2.txt
[ ! -e out2.txt ] || fail "turtle-syntax: output written"
expect turtle-string 2 '^bad-string\.ttl:[4-6]:[0-9]+: error: ' -- "$mospec" validate model.json --shapes bad-string.ttl
expect sparql-syntax 2 '^bad-sparql\.ttl:10:21: error: shape <http://example\.org/PersonShape>: .*line 5, column 21 of the query \(sh:select ending at bad-sparql\.ttl:12:[0-9]+\): expected an expression' -- "$mospec" validate model.json --shapes bad-sparql.ttl
expect sparql-no-this 2 '^unsupported-sparql\.ttl:5:[0-9]+: error: shape <http://example\.org/PersonShape>: .*\$this' -- "$mospec" validate model.json --shapes unsupported-sparql.ttl
expect unknown-path 2 '^bad-path\.ttl:5:[0-9]+: error: shape .*path node .* is neither a list nor has sh:alternativePath' -- "$mospec" validate model.json --shapes bad-path.ttl
expect literal-path 2 '^bad-path-literal\.ttl:5:[0-9]+: error: shape .*sh:path value "name" is not a path' -- "$mospec" validate model.json --shapes bad-path-literal.ttl
expect ill-formed-count 2 '^bad-count\.ttl:6:[0-9]+: error: shape .*sh:minCount must be a non-negative xsd:integer' -- "$mospec" validate model.json --shapes bad-count.ttl
expect json-syntax 2 '^bad-json\.jsonld:3:[0-9]+: error: ' -- "$mospec" validate model.json --shapes bad-json.jsonld
expect garbage 2 '^garbage\.ttl:1:[0-9]+: error: ' -- "$mospec" validate model.json --shapes garbage.ttl
for f in bad-syntax bad-string bad-sparql unsupported-sparql bad-path bad-path-literal bad-count garbage; do
  "$mospec" validate model.json --shapes $f.ttl > /dev/null 2> one-line.txt
  [ "$(wc -l < one-line.txt)" -eq 1 ] || fail "one-line-$f: $(wc -l < one-line.txt) lines on stderr"
done
expect output-file 1 '' -- "$mospec" validate model.json --shapes shapes/person.ttl -o report.txt
grep -q '^shacl: 1 violation' report.txt || fail "output-file: content"
[ -s stdout.txt ] && fail "output-file: report also on stdout"
expect turtle-format 1 '' -- "$mospec" validate model.json --shapes shapes/person.ttl --format turtle
stdout_has turtle-format 'sh:focusNode <http://example\.org/bob>'
stdout_has turtle-format 'sh:resultPath <http://example\.org/name>'
expect jsonld-format 0 '' -- "$mospec" validate good-model.json --shapes shapes/person.ttl --format jsonld
stdout_has jsonld-format '"sh:conforms": true'
if [ -w /dev/full ]; then
  expect dev-full 2 "cannot write '/dev/full'" -- "$mospec" validate model.json --shapes shapes/person.ttl -o /dev/full
fi
ls | grep -q '\.tmp\.' && fail "temporary file left behind"

finish validate
