#!/usr/bin/env bash
# docs/tutorial.md and README.md stay true to the code.
# - Every command in their ```sh blocks is run, in order, in a fresh copy of
#   the repository's models/, robots/ and metamodels/ (one for each
#   document), with mospec on PATH. A command must exit 0, or the status its
#   line states with a trailing "# exits N"; a line continued with '\' is
#   one command. `make` targets are not run (they build and test the whole
#   tree; `make test` is this suite): the test says so.
# - Every JSON key they and the other docs/*.md name is one mospec reads
#   where they name it (tests/cli/docs_keys.py; docs/testing.md, "Keys in
#   the documents"): a model node's key a term of its contexts that the
#   shapes allow on its class, a world file's key one the world file reader
#   reads, a summary's or the IR's key one the documents' commands wrote.
# Then the claims the tutorial makes about the results are checked.
# Usage: tutorial_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")

# A copy of the model tree with mospec on PATH as the guides name it.
make_tree() {  # make_tree DIR
  mkdir -p "$1/build/release/bin"
  cp -r "$src/models" "$src/robots" "$src/metamodels" "$1/"
  # The guides' PATH line names build/release/bin under the repository's root.
  ln -s "$mospec" "$1/build/release/bin/mospec"
  ln -s "$(dirname "$mospec")/mospec-full" "$1/build/release/bin/mospec-full"
}

# run_commands DOC TREE TAG: every command of DOC's ```sh blocks, in TREE;
# each one's output in $work/TAG-out-N.txt and TAG-err-N.txt.
run_commands() {
  local doc=$1 tree=$2 tag=$3 n=0 line want got
  awk '/^```sh$/ { on = 1; next } /^```/ { on = 0 }
       on { if (sub(/\\$/, "")) { held = held $0; next } print held $0; held = "" }' \
    "$doc" > "$work/$tag-commands.txt"
  check "$tag has commands" test -s "$work/$tag-commands.txt"
  while IFS= read -r line; do
    n=$((n + 1))
    if [[ "$line" =~ ^make\  ]]; then
      echo "SKIP ($tag command $n): '$line' builds and tests the whole tree (make test is this suite)"
      continue
    fi
    want=0
    if [[ "$line" =~ \#\ exits\ ([0-9]+)$ ]]; then want=${BASH_REMATCH[1]}; fi
    (cd "$tree" && bash -c "export PATH=\"$tree/build/release/bin:\$PATH\"; $line") \
      > "$work/out.txt" 2> "$work/err.txt" < /dev/null
    got=$?
    if [ "$got" -eq "$want" ]; then
      passed=$((passed + 1))
    else
      fail "$tag command $n exits $got, the document says $want: $line"
      sed 's/^/  stderr: /' "$work/err.txt" | tail -5
    fi
    cp "$work/out.txt" "$work/$tag-out-$n.txt"
    cp "$work/err.txt" "$work/$tag-err-$n.txt"
  done < "$work/$tag-commands.txt"
}

# The key check can fail, at the document's line, with the key it meant:
# "lower" (a joint limit's, scoped to it) beside a tube, in prose; a term of
# another class ("quantity-kind") in a table of what is read; a key no context
# defines in a JSON node; a world file's key misspelt.
cat > "$work/misnamed.md" <<'DOC'
- a tube (`BilateralConstraint`, a `"lower"` and an `"upper-threshold"`)

| class | property | outcome |
|---|---|---|
| EqualityConstraint | `reference-value` | honoured |
| BilateralConstraint | `quantity-kind`, `upper-threshold` | honoured |

```json
{ "@id": "tube", "@type": ["Constraint", "BilateralConstraint"], "quantity": "q",
  "lower-threshold": "lo", "uper-threshold": "hi" }
```

```json
{ "control_period": 0.001, "substep": 2 }
```
DOC
expect "misnamed keys are found" 1 "" -- python3 "$src/tests/cli/docs_keys.py" "$src" "$work/misnamed.md"
stdout_has "in prose, beside its class, with the key it meant" \
  '^.*misnamed.md:1: "lower" beside `BilateralConstraint` is no term of the contexts it uses; did you mean "lower-threshold"\?$'
stdout_has "in a table row, a term of another class" '^.*misnamed.md:6: "quantity-kind" \(<http://qudt.org/schema/qudt/hasQuantityKind>\) beside `BilateralConstraint`: no shape of metamodels/ allows it there; did you mean "quantity"\?$'
stdout_has "in a JSON node: a key no context defines" \
  '^.*misnamed.md:10: "uper-threshold" on a Constraint/BilateralConstraint is no term of the contexts it uses; did you mean "upper-threshold"\?$'
stdout_has "in a world file" '^.*misnamed.md:14: "substep" is no key of a world file .*did you mean "substeps"\?$'
check "four findings, the right keys passing" test "$(wc -l < "$work/stdout.txt")" = 4

readme="$work/readme-tree"
make_tree "$readme"
run_commands "$src/README.md" "$readme" readme
summaries=$(find "$readme" -maxdepth 2 -name '*.json' -newer "$work/readme-commands.txt" | grep -v '/models/' | head -20)
expect "the README's JSON keys are mospec's" 0 "" -- \
  python3 "$src/tests/cli/docs_keys.py" "$src" "$src/README.md" --json $summaries
sed 's/^/  /' "$work/stdout.txt"

tree="$work/tree"
make_tree "$tree"
cd "$tree" || exit 1
run_commands "$src/docs/tutorial.md" "$tree" tutorial
expect "the tutorial's JSON keys are mospec's" 0 "" -- \
  python3 "$src/tests/cli/docs_keys.py" "$src" "$src/docs/tutorial.md" --json "$tree/run.json"
sed 's/^/  /' "$work/stdout.txt"

# The other documents' keys, with the IR's and the summaries' keys the
# README's and the tutorial's commands wrote.
expect "the other documents' JSON keys are mospec's" 0 "" -- \
  python3 "$src/tests/cli/docs_keys.py" "$src" $(ls "$src"/docs/*.md | grep -v '/tutorial.md$') \
  --json $summaries "$tree/run.json" "$tree/two-step.json"
sed 's/^/  /' "$work/stdout.txt"

# What the guide says about the results.
check "the copy's files are the scenario's" test -f models/push-harder/07-scenario.json
check "the copy's entities keep their IRIs (the guide says so)" python3 -c '
import json, sys
ids = lambda f: sorted(n["@id"] for n in json.load(open(f))["@graph"])
sys.exit(ids(sys.argv[1]) != ids(sys.argv[2]))' models/push-harder/00-misc.json "$src/models/sc0a/00-misc.json"
check "the shared files stay shared" \
  grep -q '"https://mospec.example/models/right-arm/00-misc.json"' models/push-harder.json
check "the broken value is refused at its file and line" \
  grep -Rq 'models/push-harder/00-misc.json:[0-9]*:[0-9]*' "$work"/tutorial-out-*.txt "$work"/tutorial-err-*.txt
check "the run's verdict is in the summary" \
  python3 -c 'import json, sys; sys.exit(json.load(open("run.json"))["verdict"]["status"] != "ok")'
# The contact force the table exerts over the last second: 30 N, as edited.
check "the table pushes back with 30 N" awk -F, '
  NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
  $c["t"] >= 4 { n++; s += $c["right_fn"] } END { exit !(n > 0 && s / n > 29.5 && s / n < 30.5) }' run.csv
check "the plot and the video were written" test -s run.svg -a -s run.gif
check "two-step ran both phases (phase 1 ended by its until)" \
  python3 -c 'import json, sys; m = json.load(open("two-step.json"))["verdict"]["motions"]; sys.exit(not (len(m) == 2 and m[0]["ended_by"] == "until"))'

# The copy behaves exactly like the original.
rm -rf models && cp -r "$src/models" .
expect "a fresh copy of sc0a" 0 "" -- "$mospec" new copy --from sc0a
expect "sc0a runs" 0 "" -- "$mospec" run models/sc0a.json --sim --interpret --duration 1 --log "$work/sc0a.csv"
expect "its copy runs" 0 "" -- "$mospec" run models/copy.json --sim --interpret --duration 1 --log "$work/copy.csv"
check "the copy's log is byte-identical to sc0a's" cmp -s "$work/sc0a.csv" "$work/copy.csv"

# mospec new refuses what it cannot do, leaving nothing behind.
expect "an existing name" 2 "models/copy.json exists; choose another name" -- "$mospec" new copy --from sc0a
expect "a name that is not one" 2 "is not a task name" -- "$mospec" new ../escape --from sc0a
check "nothing escaped" test ! -e ../escape.json
expect "an unknown scenario" 2 "no scenario 'sc9'" -- "$mospec" new other --from sc9
expect "... as [new] (MOSPEC_DIAGNOSTIC_CODES=1)" 2 "^mospec: error\[new\]: mospec new: no scenario 'sc9'" -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" new other --from sc9
check "no half-made task" test ! -e models/other -a ! -e models/other.json
# A world file is copied only from inside the model tree: a planted link out of
# a shared bundle must not copy a file of the user's into the new task.
echo '{"secret": "do not copy"}' > "$work/private.json"
mv models/sc0b.world.json "$work/sc0b.world.json.orig" 2>/dev/null || true
ln -s "$work/private.json" models/sc0b.world.json
expect "a world file linked out of the tree" 2 \
  "the scenario's world file models/sc0b.world.json resolves to '.*private.json', outside the model tree" \
  -- "$mospec" new linked --from sc0b
check "nothing of it was created" test ! -e models/linked -a ! -e models/linked.json -a ! -e models/linked.world.json
check "the private file's content is not quoted" bash -c "! grep -q 'do not copy' '$work/stderr.txt'"
rm models/sc0b.world.json
ln -s sc0a.world.json models/sc0b.world.json
expect "a world file linked inside the tree is copied" 0 "" -- "$mospec" new linked --from sc0b
check "the linked world file's content was copied" cmp -s models/sc0a.world.json models/linked.world.json

finish tutorial
