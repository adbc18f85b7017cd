#!/usr/bin/env bash
# `mospec generate` / `mospec build` as a user sees them: the tiny model
# (tests/ir/data) generates the same bytes every time; a model that does not
# lower is refused with its located finding and nothing is written; usage and
# environment errors exit 2 with a "mospec:" message.
# usage: generate_cli_test.sh MOSPEC SOURCE_DIR
SRC="$2"
source "$SRC/tests/support/cli_lib.sh"
D="$SRC/tests/ir/data"

expect "tiny generates" 0 "" -- "$mospec" generate --root "$D" "$D/tiny.json" -o "$work/a"
check "the project's three files" test -f "$work/a/CMakeLists.txt" -a -f "$work/a/controller.hpp" \
  -a -f "$work/a/controller.cpp"
expect "tiny generates again" 0 "" -- "$mospec" generate --root "$D" "$D/tiny.json" -o "$work/b"
check "byte-identical" diff -r "$work/a" "$work/b"
check "steps name their model file and line" grep -Eq '^  //     .*tiny/model\.json:[0-9]+:[0-9]+$' \
  "$work/a/controller.cpp"
check "no temporary files left" test "$(ls -A "$work/a" | wc -l)" -eq 3

# A dependency cycle (as in tests/ir/ir_cli_test.sh): refused, located, nothing written.
mkdir -p "$work/cycle/tiny"
cp "$D/tiny.json" "$work/cycle/"
sed 's/"quantity": "time", "reference-value"/"quantity": "effort", "reference-value"/' \
  "$D/tiny/model.json" > "$work/cycle/tiny/model.json"
expect "a model that does not lower is refused" 1 \
  'tiny/model.json:[0-9]+:[0-9]+: error: .*dependency cycle' -- \
  "$mospec" generate --root "$work/cycle" "$work/cycle/tiny.json" -o "$work/cycle-out"
check "nothing written for a refused model" test ! -e "$work/cycle-out"

expect "-o is required" 2 "mospec: .*output" -- "$mospec" generate --root "$D" "$D/tiny.json"
expect "a missing app" 2 "no-such.json" -- "$mospec" generate "$work/no-such.json" -o "$work/c"
touch "$work/file"
expect "an output below a regular file" 2 "^mospec: error: cannot create directory '$work/file/sub': Not a directory" -- \
  "$mospec" generate --root "$D" "$D/tiny.json" -o "$work/file/sub"
expect "build: no project" 2 "^mospec: error: '$work/nothing' holds no generated project" -- \
  "$mospec" build "$work/nothing"
expect "build: --jobs 0" 2 "mospec: .*jobs" -- "$mospec" build "$work/a" --jobs 0

finish generate-cli
