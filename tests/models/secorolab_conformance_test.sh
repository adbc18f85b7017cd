#!/usr/bin/env bash
# mospec's contexts of the secorolab extension metamodels
# (metamodels/secorolab/<path>.json, what https://secorolab.github.io/metamodels/<path>.json
# resolves to) agree with the published ones: every term mospec's file defines
# is defined by the published context of the same path, expands to the same
# IRI, and has the same @type and @container where either gives one (also in
# type-scoped contexts). Reads the published snapshot in SHARED_DIR/upstream/
# secorolab-metamodels; skipped (exit 77) when it is absent.
# Usage: secorolab_conformance_test.sh SOURCE_DIR SHARED_DIR
set -u
src=$(realpath "$1")
published="$2/upstream/secorolab-metamodels"
if [ ! -d "$published" ]; then
  echo "SKIP: the published secorolab metamodels are not at $published (../shared absent)"
  exit 77
fi
python3 - "$src/metamodels/secorolab" "$published" <<'PY'
import json, os, sys
mine_dir, pub_dir = sys.argv[1], sys.argv[2]
failures, checked = [], 0
KEYWORDS = {"@version", "@base", "@vocab", "@language", "@protected", "@propagate", "@import"}

def prefixes(ctx, outer):
    out = dict(outer)
    for k, v in ctx.items():
        iri = v if isinstance(v, str) else (v.get("@id") if isinstance(v, dict) else None)
        if isinstance(iri, str) and not k.startswith("@") and (iri.endswith("#") or iri.endswith("/")):
            out[k] = iri
    return out

def expand(value, pre):
    if not isinstance(value, str) or value.startswith("@") or "://" in value:
        return value
    p, sep, local = value.partition(":")
    return pre[p] + local if sep and p in pre else value

def definition(v):
    return {"@id": v} if isinstance(v, str) else v

def compare(where, mine, pub, outer_mine, outer_pub):
    global checked
    pm, pp = prefixes(mine, outer_mine), prefixes(pub, outer_pub)
    for term, v in mine.items():
        if term in KEYWORDS:
            continue
        at = f"{where}: term '{term}'"
        if term not in pub:
            failures.append(f"{at}: the published context does not define it")
            continue
        dm, dp = definition(v), definition(pub[term])
        checked += 1
        im, ip = expand(dm.get("@id"), pm), expand(dp.get("@id"), pp)
        if im != ip:
            failures.append(f"{at}: mospec maps it to {im}, the published context to {ip}")
        for key in ("@type", "@container"):
            km, kp = expand(dm.get(key), pm), expand(dp.get(key), pp)
            if km != kp:
                failures.append(f"{at}: {key} is {km!r} in mospec's context, {kp!r} in the published one")
        if "@context" in dm or "@context" in dp:
            compare(f"{at} (type-scoped)", dm.get("@context", {}), dp.get("@context", {}), pm, pp)

files = sorted(os.path.relpath(os.path.join(d, f), mine_dir)
               for d, _, fs in os.walk(mine_dir) for f in fs if f.endswith(".json"))
if not files:
    failures.append(f"no context under {mine_dir}")
for rel in files:
    pub_path = os.path.join(pub_dir, rel)
    if not os.path.isfile(pub_path):
        failures.append(f"{rel}: the published vocabulary has no context of this path")
        continue
    mine = json.load(open(os.path.join(mine_dir, rel)))["@context"]
    pub = json.load(open(pub_path))["@context"]
    before = len(failures)
    compare(rel, mine, pub, {}, {})
    if len(failures) == before:
        print(f"ok   {rel}: every term as the published context defines it")
for f in failures:
    print("FAIL " + f)
print(f"{checked} term(s) checked in {len(files)} context(s), {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
PY
