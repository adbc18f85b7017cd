#!/usr/bin/env bash
# `mospec` is a front door (src/cli/main.cpp): it runs the model-side commands
# itself, without loading the simulator's libraries, and hands sim, run,
# import-urdf, build and --help-all to mospec-full beside it.
# Usage: front_door_test.sh MOSPEC_BINARY
source "$(dirname "$0")/../support/cli_lib.sh"
catalogue_doc="$(cd "$(dirname "$0")/../../docs" && pwd)/diagnostics.md"
cd "$work"

# What the dynamic loader maps at start-up: nothing validation never calls.
if command -v readelf >/dev/null; then
  readelf -d "$mospec" | grep NEEDED > needed.txt
  check front-door-needs-re2 grep -q 'libre2' needed.txt
  for lib in mujoco urdfdom console_bridge tinyxml crypto; do
    if grep -q "lib$lib" needed.txt; then fail "front-door-needed: mospec loads lib$lib at start-up"; else passed=$((passed+1)); fi
  done
else
  echo "front_door_test: readelf not found; skipping the NEEDED checks"
fi

# Every command is listed in --help, the forwarded ones included.
expect help 0 '' -- "$mospec" --help
for cmd in rdf validate stats sim import-urdf generate build ir run plot trials explain; do
  stdout_has "help-lists-$cmd" "^  $cmd  "
done

# `mospec explain`: a code's catalogue entry (docs/diagnostics.md); a misspelt
# code is refused with the nearest one; no code lists them all.
expect explain 0 '' -- "$mospec" explain loop-sign
stdout_has explain "^loop-sign: error \(run\): a controller's gain has the sign that makes its error grow$"
expect explain-internal 0 '' -- "$mospec" explain invalid-base
stdout_has explain-internal '^invalid-base: error, internal \(description\): '
expect explain-misspelt 2 "^mospec: error: no diagnostic code 'loop_sign'; did you mean 'loop-sign'\?" -- \
  "$mospec" explain loop_sign
expect explain-all 0 '' -- "$mospec" explain
check "explain lists every code of docs/diagnostics.md" \
  test "$(wc -l < "$work/stdout.txt")" -eq "$(grep -c '^| `' "$catalogue_doc")"
# Forwarded: their own help and their own usage errors, as mospec-full gives them.
expect run-help 0 '' -- "$mospec" run --help
stdout_has run-help '^Usage: mospec run \[OPTIONS\] app'
expect sim-help 0 '' -- "$mospec" sim --help
stdout_has sim-help '^Usage: mospec sim '
expect build-usage 2 '^mospec: dir is required' -- "$mospec" build
expect import-urdf-usage 2 'urdf is required' -- "$mospec" import-urdf
expect help-all 0 '' -- "$mospec" --help-all
stdout_has help-all '^    --seed '
# A forwarded command's exit status is mospec-full's.
expect build-nowhere 2 'holds no generated project' -- "$mospec" build "$work/nowhere"

# Without mospec-full beside it: a clear message and exit 2; the model-side
# commands still run.
mkdir alone
cp "$mospec" alone/mospec
expect alone-run 2 '^mospec: cannot run .*alone/mospec-full: .*built and installed beside mospec' -- alone/mospec run x.json --sim
cat > good.json <<'J'
{ "@context": { "ex": "https://ex.org/", "name": "ex:name" },
  "@id": "https://ex.org/a", "name": "A" }
J
expect alone-rdf 0 '' -- alone/mospec rdf good.json
stdout_has alone-rdf '^<https://ex.org/a> <https://ex.org/name> "A" '

finish front_door_test
