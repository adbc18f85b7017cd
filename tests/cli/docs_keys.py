#!/usr/bin/env python3
"""The JSON keys a document names are keys mospec reads.

Usage: docs_keys.py SOURCE_DIR DOC.md... [--json FILE.json...]

A key is named in a document as `"key"` (or `"key": value`) in inline code.
In a paragraph or list item that names a metamodel class in inline code
(`BilateralConstraint`), every key must be a model term: defined by a
JSON-LD context of metamodels/ or of a shipped app, and, for a metamodel
term, covered by a shape (its name in a metamodels/**/*.ttl file) or listed
in metamodels/mospec/unshaped-terms.txt. Elsewhere a key may also be a key
of a shipped world file (models/**/*.world.json) or of a JSON file given
after --json (a run's summary the documents' commands wrote). Prints one
line per key that is none of these, DOC:LINE first; exit 1 when there is one.
"""
import json
import pathlib
import re
import sys


def context_terms(node, out, app):
    """Every term of every @context in node: name -> (IRI, from an app file)."""
    if isinstance(node, dict):
        for k, v in node.items():
            if k == "@context":
                collect(v, out, app)
            else:
                context_terms(v, out, app)
    elif isinstance(node, list):
        for x in node:
            context_terms(x, out, app)


def collect(ctx, out, app):
    if isinstance(ctx, list):
        for c in ctx:
            collect(c, out, app)
        return
    if not isinstance(ctx, dict):
        return
    for term, d in ctx.items():
        if term.startswith("@"):
            continue
        iri = d if isinstance(d, str) else d.get("@id") if isinstance(d, dict) else None
        out.setdefault(term, []).append((iri or term, app))
        if isinstance(d, dict) and "@context" in d:
            collect(d["@context"], out, app)


def json_keys(node, out):
    if isinstance(node, dict):
        for k, v in node.items():
            out.add(k)
            json_keys(v, out)
    elif isinstance(node, list):
        for x in node:
            json_keys(x, out)


def load(path):
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (ValueError, OSError):
        return None


def main(argv):
    src = pathlib.Path(argv[1])
    docs, extra = [], []
    rest = argv[2:]
    if "--json" in rest:
        i = rest.index("--json")
        docs, extra = rest[:i], rest[i + 1:]
    else:
        docs = rest
    terms = {}
    for f in sorted((src / "metamodels").rglob("*.json")):
        context_terms(load(f), terms, False)
    for f in sorted((src / "models").rglob("*.json")):
        if not f.name.endswith(".world.json"):
            context_terms(load(f), terms, True)
    shapes = "\n".join(p.read_text(encoding="utf-8") for p in (src / "metamodels").rglob("*.ttl"))
    shapes += (src / "metamodels/mospec/unshaped-terms.txt").read_text(encoding="utf-8")

    def shaped(iri):
        local = re.split(r"[:#/]", iri)[-1]
        return re.search(r"[:#/]" + re.escape(local) + r"\b", shapes) is not None

    def model_term(key):
        return any(app or shaped(iri) for iri, app in terms.get(key, []))

    others = set()
    for f in sorted((src / "models").rglob("*.world.json")):
        json_keys(load(f), others)
    for f in extra:
        json_keys(load(pathlib.Path(f)), others)
    classes = {t for t in terms if t[:1].isupper()}
    bad = 0
    for doc in docs:
        lines = pathlib.Path(doc).read_text(encoding="utf-8").split("\n")
        # Paragraphs and list items, outside fenced blocks: (first line, text).
        blocks, fenced, start, text = [], False, 0, []
        for n, line in enumerate(lines, 1):
            if line.startswith("```"):
                fenced = not fenced
                continue
            new_item = re.match(r"\s*([-*]|\d+\.) ", line) is not None
            if fenced or not line.strip() or new_item:
                if text:
                    blocks.append((start, " ".join(text)))
                text = []
            if not fenced and line.strip():
                if not text:
                    start = n
                text.append(line)
        if text:
            blocks.append((start, " ".join(text)))
        for start, block in blocks:
            named = [c for c in re.findall(r"`([A-Za-z][\w-]*)`", block) if c in classes]
            for key in re.findall(r'`"([^"`]+)"(?::[^`]*)?`', block):
                if model_term(key):
                    continue
                if not named and (key in others or key.startswith("@")):
                    continue
                where = "beside `" + named[0] + "`, a model key" if named else "a key"
                print(f'{doc}:{start}: `"{key}"` ({where}) is not one mospec reads: no context '
                      "of metamodels/ or of a shipped app defines it with a shape"
                      + ("" if named else ", and no world file or summary has it"))
                bad += 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
