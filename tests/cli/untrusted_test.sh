#!/usr/bin/env bash
# Untrusted model trees (issue #12): every input file is a regular file of
# bounded size, references stay inside the model tree, nothing outside it reaches
# stdout, stderr or the RDF output, and malformed @id values are reported.
# Usage: untrusted_test.sh MOSPEC_BINARY
source "$(dirname "$0")/../support/cli_lib.sh"
cd "$work"
t() { timeout 10 "$@"; }  # a hang fails the test (exit 124) instead of stalling it

# ---- files that are not regular files of bounded size ------------------------
mkdir -p tree/dir
mkfifo tree/fifo.json tree/fifo.ttl
ln -s /dev/urandom tree/urandom.json
ln -s /dev/zero tree/zero.json
truncate -s 100M tree/huge.json  # sparse: no blocks written
cat > good.json <<'J'
{ "@context": { "ex": "https://ex.org/" }, "@id": "https://ex.org/a", "ex:name": "A" }
J
declare -A reason=([fifo.json]='not a regular file \(a FIFO\)'
                   [urandom.json]='not a regular file \(a character device\)'
                   [zero.json]='not a regular file \(a character device\)'
                   [dir]='Is a directory'
                   [huge.json]='file is too large \(104857600 bytes; the limit is 67108864 bytes\)')
for f in fifo.json urandom.json zero.json dir huge.json; do
  expect "model-$f" 2 "tree/$f.*${reason[$f]}" -- t "$mospec" rdf "tree/$f"
  expect "shapes-$f" 2 "tree/$f.*${reason[$f]}" -- t "$mospec" validate good.json --shapes "tree/$f"
  expect "world-$f" 2 "tree/$f.*${reason[$f]}" -- t "$mospec" sim "tree/$f" --duration 0.01
  expect "urdf-$f" 2 "tree/$f.*${reason[$f]}" -- t "$mospec" import-urdf "tree/$f"
  # (a directory is a valid plot input: the trials of `mospec trials`)
  [ "$f" = dir ] || expect "log-$f" 2 "tree/$f.*${reason[$f]}" -- t "$mospec" plot "tree/$f" -o plot.svg
done

# An import and a shape file named by an app: located at the app's line.
app_header='{ "@context": { "app": "https://comp-rob2b.github.io/metamodels/application/",
    "import": { "@id": "app:import", "@type": "@id" },
    "constraints": { "@id": "app:constraints", "@type": "@id", "@container": "@set" },
    "iri-map": { "@id": "app:iri-map", "@container": "@id" },
    "path": { "@id": "app:path" } },
  "@id": "https://m.example/app",'
# write_app IMPORTS CONSTRAINTS IRI-MAP-PATH NAME: tree/NAME.json. Quads are
# located at their node's @id: the app node's on line 6 (imports and
# constraints), the iri-map entry's on line 9.
write_app() {
  printf '%s\n  "import": [ %s ],\n  "constraints": [ %s ],\n  "iri-map": { "https://m.example/": { "path": "%s" } } }\n' \
    "$app_header" "$1" "$2" "${3:-.}" > "tree/$4.json"
}
for f in fifo.json dir huge.json urandom.json; do
  write_app "\"https://m.example/$f\"" '' . "import-${f%.json}"
done
echo '{ "@context": { "ex": "https://ex.org/" }, "@id": "https://ex.org/ok", "ex:p": 1 }' > tree/ok.json
write_app '"https://m.example/ok.json"' '"https://m.example/fifo.ttl"' . shapes-fifo
(
  cd tree
  expect import-fifo 2 '^import-fifo\.json:6:[0-9]+: error: .*fifo\.json.*not a regular file \(a FIFO\)' \
    -- t "$mospec" rdf import-fifo.json
  expect import-dir 2 '^import-dir\.json:6:[0-9]+: error: .*dir.*Is a directory' \
    -- t "$mospec" rdf import-dir.json
  expect import-huge 2 '^import-huge\.json:6:[0-9]+: error: .*huge\.json.*file is too large' \
    -- t "$mospec" rdf import-huge.json
  # A link inside the tree to a device resolves outside it.
  expect import-urandom 2 '^import-urandom\.json:6:[0-9]+: error: .*outside the model tree' \
    -- t "$mospec" rdf import-urandom.json
  expect shapes-fifo 2 '^shapes-fifo\.json:6:[0-9]+: error: .*fifo\.ttl.*not a regular file \(a FIFO\)' \
    -- t "$mospec" validate shapes-fifo.json
  echo "$passed $failures" > ../counts
)
read passed failures < counts

# ---- the sandbox: nothing outside the tree is read -----------------------------
secret=$work/secret
mkdir -p "$secret"
# A secret that is valid JSON-LD (it would reach the RDF output if loaded), one
# that is not JSON (its first byte would be quoted), and a Turtle one.
echo '{ "@context": { "s": "https://s.example/" }, "@id": "https://s.example/k", "s:key": "TOPSECRET-JSON" }' > "$secret/s.json"
echo 'TOPSECRET-RAW' > "$secret/raw.json"
echo '<https://s.example/k> <https://s.example/key> "TOPSECRET-TTL" .' > "$secret/s.ttl"
ln -s "$secret/s.json" tree/link.json
ln -s "$secret" tree/linkdir
echo '{ "@context": { "ex": "https://ex.org/" } }' > tree/ctx.json

# no_secret NAME: the last command's stdout and stderr hold no secret.
no_secret() {
  if grep -q TOPSECRET "$work/stdout.txt" "$work/stderr.txt"; then
    fail "$1: a secret leaked"; grep TOPSECRET "$work/stdout.txt" "$work/stderr.txt" | head -3
  fi
}
# escape NAME IRI: importing IRI, using it as a context and as a shape file are
# located errors (the app's line / the model's line) that leak nothing.
escape() {
  local name=$1 iri=$2
  write_app "\"https://m.example/ok.json\", \"$iri\"" '' . "imp-$name"
  write_app '"https://m.example/ok.json"' "\"$iri\"" . "shp-$name"
  printf '{ "@context": [ "https://m.example/ctx.json",\n  "%s" ],\n  "@id": "https://ex.org/x" }\n' "$iri" > "tree/ctx-$name.json"
  (
    cd tree
    expect "import-$name" 2 "^imp-$name\.json:6:[0-9]+: error: .*(outside the model tree|control character)" \
      -- t "$mospec" rdf "imp-$name.json"
    no_secret "import-$name"
    expect "shapes-$name" 2 "^shp-$name\.json:6:[0-9]+: error: .*(outside the model tree|control character)" \
      -- t "$mospec" validate "shp-$name.json"
    no_secret "shapes-$name"
    expect "context-$name" 2 "^ctx-$name\.json:2:[0-9]+: error: .*(outside the model tree|control character)" \
      -- t "$mospec" rdf --map https://m.example/=. "ctx-$name.json"
    no_secret "context-$name"
    echo "$passed $failures" > ../counts
  )
  read passed failures < counts
}
escape dotdot "https://m.example/%2e%2e/secret/s.json"
escape dotdot-upper "https://m.example/%2E%2E%2Fsecret/raw.json"
escape file "file://$secret/s.json"
escape file-raw "file://$secret/raw.json"
escape proc "file:///proc/self/environ"
escape symlink "https://m.example/link.json"
escape symlink-dir "https://m.example/linkdir/s.json"
escape turtle "https://m.example/linkdir/s.ttl"
escape nul "https://m.example/ok.json%00.txt"
escape newline "https://m.example/ok%0a.json"

# An app's iri-map may not map an IRI outside its tree (the current directory).
write_app '"https://m.example/s.json"' '' "$secret" map-abs
write_app '"https://m.example/s.json"' '' "../secret" map-dotdot
write_app '"https://m.example/s.json"' '' "linkdir" map-link
write_app '"https://m.example/ok.json"' '' . inside
(
  cd tree
  for a in map-abs map-dotdot map-link; do
    expect "$a" 2 "^$a\.json:9:[0-9]+: error: iri-map entry <https://m\.example/> names the directory '.*', outside the model tree" \
      -- t "$mospec" rdf "$a.json"
    no_secret "$a"
  done
  expect "map-abs as [invalid iri-map] (MOSPEC_DIAGNOSTIC_CODES=1)" 2 "^map-abs\.json:9:[0-9]+: error\[invalid iri-map\]: iri-map entry" \
    -- t env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" rdf map-abs.json
  # Inside the tree everything still loads.
  expect inside 0 '' -- t "$mospec" rdf inside.json
  stdout_has inside '<https://ex.org/ok> <https://ex.org/p>'
  echo "$passed $failures" > ../counts
)
read passed failures < counts
# --map is the user's word: a directory named there may be read.
# (The app's own iri-map entry for https://m.example/ resolves against --root.)
expect user-map 0 '' -- t "$mospec" rdf --map https://s.example/="$secret" --root tree tree/imp-file.json
stdout_has user-map 'TOPSECRET-JSON' 

# A non-JSON file inside the tree: its first byte is quoted only when printable.
printf '\x01\x02rest' > tree/binary.json
expect binary-byte 2 'binary\.json:1:1: error: unexpected byte 0x01; expected a JSON value' \
  -- t "$mospec" rdf tree/binary.json
check binary-no-raw-bytes bash -c "! grep -q \$'\\x01' '$work/stderr.txt'"

# ---- malformed @id values are reported, and refused under --strict ------------
cat > controller.json <<'J'
{ "@context": { "ex": "https://ex.org/",
    "constraints": { "@id": "ex:constraints", "@type": "@id", "@container": "@set" } },
  "@graph": [
    { "@id": "https://ex.org/controller", "@type": "ex:Controller",
      "constraints": [ "https://ex.org/c1", "https://ex.org/c 2", "https://ex.org/c3" ] },
    { "@id": "https://ex.org/c 2", "@type": "ex:Constraint" } ] }
J
cat > shapes.ttl <<'T'
@prefix sh: <http://www.w3.org/ns/shacl#> .
@prefix ex: <https://ex.org/> .
ex:ControllerShape a sh:NodeShape ; sh:targetClass ex:Controller ;
  sh:property [ sh:path ex:constraints ; sh:minCount 1 ] .
T
expect malformed-id-warns 0 '^controller\.json:5:[0-9]+: warning: @id value "https://ex\.org/c 2" is not a well-formed IRI \(it contains a space' \
  -- t "$mospec" validate controller.json --shapes shapes.ttl
check malformed-id-both grep -q '^controller\.json:6:[0-9]*: warning: @id value "https://ex.org/c 2"' "$work/stderr.txt"
expect malformed-id-strict 1 'controller\.json:5:[0-9]+: warning: .*not a well-formed IRI' \
  -- t "$mospec" validate --strict controller.json --shapes shapes.ttl
expect malformed-id-rdf-strict 1 'controller\.json:5:[0-9]+: warning: .*not a well-formed IRI' \
  -- t "$mospec" rdf --strict controller.json -o controller.nq
[ ! -e controller.nq ] || fail "malformed-id-rdf-strict: output written despite findings"

# ---- a context listed twice is not a cycle -------------------------------------
mkdir -p ctx
echo '{ "@context": { "ex": "https://ex.org/", "name": "ex:name" } }' > ctx/base.jsonld
echo '{ "@context": [ "https://ctx.example/base.jsonld", { "nick": "https://ex.org/nick" } ] }' > ctx/more.jsonld
cat > twice.json <<'J'
{ "@context": [ "https://ctx.example/base.jsonld", "https://ctx.example/more.jsonld",
                "https://ctx.example/base.jsonld" ],
  "@id": "https://ex.org/a", "name": "A", "nick": "B" }
J
expect context-twice 0 '' -- t "$mospec" rdf --strict --map https://ctx.example/=ctx twice.json
stdout_has context-twice '<https://ex.org/a> <https://ex.org/nick> "B"'

finish untrusted
