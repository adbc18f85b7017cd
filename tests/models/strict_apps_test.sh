#!/usr/bin/env bash
# Every shipped app passes its own `mospec validate --strict`: the apps are
# found, not listed (every JSON file under models/ that is an app: a node with
# `import` in a file whose context names the application vocabulary), so a
# new app is covered as soon as it is added. An app whose iri-map paths are
# relative to its own folder (models/examples/two-frames) is validated with
# --root there, the others from the source tree.
# Then the unit note: a finding about a value shared by many nodes (a unit, a
# quantity kind) notes it where the user's node uses it, never at the first
# other node that does (tests/models/data/unit-note: the full output beside
# the input, expected.txt).
# Usage: strict_apps_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src" || exit 1

python3 - "$src" > "$work/apps.txt" <<'PY'
import json, pathlib, sys
src = pathlib.Path(sys.argv[1])
APP = "https://comp-rob2b.github.io/metamodels/application/"
for f in sorted((src / "models").rglob("*.json")):
    if f.name.endswith(".world.json"):
        continue
    try:
        doc = json.loads(f.read_text(encoding="utf-8"))
    except ValueError:
        continue
    if not isinstance(doc, dict) or APP not in json.dumps(doc.get("@context")):
        continue
    nodes = doc.get("@graph", [doc])
    apps = [n for n in nodes if isinstance(n, dict) and "import" in n]
    if not apps:
        continue
    # Its imports resolve through its iri-map from the source tree, or from
    # its own folder.
    def resolves(base):
        for n in apps:
            for iri in n["import"] if isinstance(n["import"], list) else [n["import"]]:
                for prefix, v in n.get("iri-map", {}).items():
                    if isinstance(v, dict) and iri.startswith(prefix):
                        if not (base / v.get("path", "") / iri[len(prefix):]).exists():
                            return False
        return True
    root = "." if resolves(src) else str(f.parent.relative_to(src))
    print(f.relative_to(src), root)
PY
count=$(wc -l < "$work/apps.txt")
check "the shipped apps are found ($count)" test "$count" -ge 15
check "the lift example is among them" grep -q '^models/examples/lift.json ' "$work/apps.txt"
while read -r app root; do
  expect "$app passes validate --strict" 0 "" -- "$mospec" validate --strict "$app" --root "$root"
done < "$work/apps.txt"

case="tests/models/data/unit-note"
"$mospec" validate "$case/app.json" > "$work/unit-note.txt" 2>&1
check "the unit note case is refused with the expected diagnostics ($case/expected.txt)" \
  diff -u "$case/expected.txt" "$work/unit-note.txt"
check "no note points at the other file that uses the same unit" \
  bash -c "! grep -q 'shared.json' '$work/unit-note.txt'"
check "no note is labelled with a query's variable of one letter" \
  bash -c "! grep -Eq 'note: [a-z] <' '$work/unit-note.txt'"

finish strict_apps
