#!/usr/bin/env python3
"""The JSON keys a document names are keys mospec reads, where it names them.

Usage: docs_keys.py SOURCE_DIR DOC.md... [--json FILE.json...]

The convention (docs/testing.md, "Keys in the documents"):
- a model node's key (an object with @type in a ```json block or in inline
  code) is a term of the contexts the node uses, its types' scoped contexts
  included, and a property the shapes of metamodels/ allow on its type (or
  that a shipped model uses on it);
- `"key"` in inline code in a sentence that names a class (`BilateralConstraint`)
  is that class's key, checked the same way; so is each backticked property of
  a table with `class` and `property` columns (only a term when its outcome is
  not "honoured");
- a key of a ```json block without @type or @context is a world file's: one
  src/sim/config.cpp reads;
- any other `"key"` is a model term, a shipped world file's key, or a key of a
  JSON file given after --json (the IR or a run summary the documents wrote).

Prints one line per key that fails, DOC:LINE first, with the nearest key the
class allows ("did you mean"); exit 1 when there is one.
"""
import difflib
import json
import pathlib
import re
import sys

RDF = "http://www.w3.org/1999/02/22-rdf-syntax-ns#"
RDFS = "http://www.w3.org/2000/01/rdf-schema#"
SH = "http://www.w3.org/ns/shacl#"
PUBLISHED = "https://comp-rob2b.github.io/metamodels/"
# The group's extension vocabulary, which mospec resolves to its own contexts
# under metamodels/secorolab/ (src/app/app.cpp).
EXTENSIONS = "https://secorolab.github.io/metamodels/"

# ---- Turtle (enough of it for the shape files) ------------------------------

TOKEN = re.compile(
    r'(?P<ws>\s+|#[^\n]*)'
    r'|(?P<iri><[^>\s]*>)'
    r'|(?P<str3>"""(?:[^"\\]|\\.|"(?!""))*"""|\'\'\'(?:[^\'\\]|\\.|\'(?!\'\'))*\'\'\')'
    r'|(?P<str>"(?:[^"\\\n]|\\.)*"|\'(?:[^\'\\\n]|\\.)*\')'
    r'|(?P<at>@[A-Za-z]+(?:-[A-Za-z0-9]+)*)'
    r'|(?P<dt>\^\^)'
    r'|(?P<num>[+-]?(?:\d+\.\d+|\.\d+|\d+)(?:[eE][+-]?\d+)?)'
    r'|(?P<punct>[.;,\[\]()])'
    r'|(?P<pname>(?:[A-Za-z][\w-]*)?:(?:[\w\-:%]|\.(?=[\w\-:%]))*|_:[\w-]+)'
    r'|(?P<word>[A-Za-z]+)')


def read_turtle(text, triples, scope):
    """Appends the file's triples; its blank nodes are _:<scope>.<n>."""
    toks, pos = [], 0
    while pos < len(text):
        m = TOKEN.match(text, pos)
        if not m:
            raise ValueError(f"turtle: cannot read {text[pos:pos + 20]!r}")
        pos = m.end()
        if m.lastgroup != "ws":
            toks.append((m.lastgroup, m.group()))
    prefixes, i, blank = {}, 0, [0]

    def fresh():
        blank[0] += 1
        return f"_:{scope}.{blank[0]}"

    def term(kind, text):
        if kind == "iri":
            return text[1:-1]
        if kind == "pname":
            if text.startswith("_:"):
                return f"_:{scope}.{text[2:]}"
            p, _, local = text.partition(":")
            return prefixes[p] + local
        if kind == "word" and text == "a":
            return RDF + "type"
        if kind in ("str", "str3"):
            return ("lit", text[3:-3] if kind == "str3" else text[1:-1])
        return ("lit", text)

    def obj():
        nonlocal i
        kind, text = toks[i]
        i += 1
        if text == "[" and kind == "punct":
            node = fresh()
            if toks[i][1] != "]":
                pred_objects(node)
            i += 1  # ]
            return node
        if text == "(" and kind == "punct":
            items = []
            while toks[i][1] != ")":
                items.append(obj())
            i += 1
            head = RDF + "nil"
            for item in reversed(items):
                node = fresh()
                triples.append((node, RDF + "first", item))
                triples.append((node, RDF + "rest", head))
                head = node
            return head
        value = term(kind, text)
        if i < len(toks) and toks[i][0] == "at" and kind in ("str", "str3"):
            i += 1
        elif i < len(toks) and toks[i][0] == "dt":
            i += 2
        return value

    def pred_objects(subject):
        nonlocal i
        while True:
            kind, text = toks[i]
            i += 1
            pred = term(kind, text)
            while True:
                triples.append((subject, pred, obj()))
                if toks[i][1] != ",":
                    break
                i += 1
            if toks[i][1] != ";":
                return
            while toks[i][1] == ";":
                i += 1
            if toks[i][1] in (".", "]"):
                return

    while i < len(toks):
        kind, text = toks[i]
        if (kind == "at" and text == "@prefix") or (kind == "word" and text.upper() == "PREFIX"):
            prefixes[toks[i + 1][1].rstrip(":")] = toks[i + 2][1][1:-1]
            i += 4 if kind == "at" else 3
            continue
        if (kind == "at" and text == "@base") or (kind == "word" and text.upper() == "BASE"):
            i += 3 if kind == "at" else 2
            continue
        subject = obj()
        if toks[i][1] != ".":
            pred_objects(subject)
        i += 1  # .
    return prefixes


# ---- the shapes: which properties they allow on which classes ---------------


class Shapes:
    def __init__(self, src):
        triples = []
        for n, f in enumerate(sorted((src / "metamodels").rglob("*.ttl"))):
            read_turtle(f.read_text(encoding="utf-8"), triples, n)
        self.out = {}
        for s, p, o in triples:
            self.out.setdefault(s, {}).setdefault(p, []).append(o)
        self.allowed = {}  # class IRI -> property IRIs
        self.any_type = set()  # properties whose subjects a shape targets
        self.supers = {}
        for s, p, o in triples:
            if p == RDFS + "subClassOf" and isinstance(o, str):
                self.supers.setdefault(s, set()).add(o)
        for s, ps in self.out.items():
            props = None
            for c in ps.get(SH + "targetClass", []):
                props = props if props is not None else self.props(s, set())
                self.allowed.setdefault(c, set()).update(props)
            if RDFS + "Class" in ps.get(RDF + "type", []):
                props = props if props is not None else self.props(s, set())
                self.allowed.setdefault(s, set()).update(props)
            # A shape on the subjects of a property checks it on any class: it
            # says nothing of which classes may have it.
            self.any_type.update(ps.get(SH + "targetSubjectsOf", []))

    def objs(self, s, p):
        return self.out.get(s, {}).get(p, [])

    def items(self, head):
        out = []
        while isinstance(head, str) and head != RDF + "nil" and self.objs(head, RDF + "first"):
            out.append(self.objs(head, RDF + "first")[0])
            head = self.objs(head, RDF + "rest")[0]
        return out

    def props(self, shape, seen):
        if shape in seen or not isinstance(shape, str):
            return set()
        seen.add(shape)
        out = set()
        for b in self.objs(shape, SH + "property"):
            for path in self.objs(b, SH + "path"):
                if isinstance(path, str) and not path.startswith("_:"):
                    out.add(path)
                elif isinstance(path, str):  # a sequence's first step, an alternative's items
                    seq = self.items(path)
                    if seq and isinstance(seq[0], str) and not seq[0].startswith("_:"):
                        out.add(seq[0])
                    for alt in self.objs(path, SH + "alternativePath"):
                        out.update(x for x in self.items(alt) if isinstance(x, str))
            out |= self.props(b, seen)  # sh:node and the like inside a property shape
        for q in self.objs(shape, SH + "sparql"):
            for text in self.objs(q, SH + "select") + self.objs(q, SH + "ask"):
                out |= this_properties(text[1])
        for k in ("node", "and", "or", "xone"):
            for o in self.objs(shape, SH + k):
                for sub in self.items(o) or [o]:
                    out |= self.props(sub, seen)
        return out

    def allows(self, classes, prop):
        todo, seen = list(classes), set()
        while todo:
            c = todo.pop()
            if c in seen:
                continue
            seen.add(c)
            if prop in self.allowed.get(c, ()):
                return True
            todo.extend(self.supers.get(c, ()))
        return False


def this_properties(query):
    """The properties a SPARQL query reads off $this: `$this p ?x ; q ?y`."""
    prefixes = dict(re.findall(r"PREFIX\s+([\w-]*):\s*<([^>]*)>", query, re.I))
    out = set()
    for seg in re.findall(r"\$this\s+([^.{}]*)", query):
        for part in seg.split(";"):
            words = part.split()
            if not words:
                continue
            w = words[0].lstrip("^")
            if w.startswith("<") and w.endswith(">"):
                out.add(w[1:-1])
            elif ":" in w and w.split(":", 1)[0] in prefixes:
                p, _, local = w.partition(":")
                out.add(prefixes[p] + local)
    return out


# ---- JSON-LD contexts --------------------------------------------------------


class Context:
    """Terms of a set of JSON-LD contexts: name -> [(IRI, scoped Context)]."""

    def __init__(self):
        self.terms = {}
        self.prefixes = {}

    def add(self, ctx, src, seen=None):
        if isinstance(ctx, list):
            for c in ctx:
                self.add(c, src, seen)
            return
        if isinstance(ctx, str):
            seen = seen if seen is not None else set()
            base = next((b for b in (PUBLISHED, EXTENSIONS) if ctx.startswith(b)), None)
            if base is not None and ctx not in seen:
                seen.add(ctx)
                f = src / "metamodels" / ("" if base == PUBLISHED else "secorolab") / ctx[len(base):]
                doc = load(f)
                if isinstance(doc, dict) and "@context" in doc:
                    self.add(doc["@context"], src, seen)
            return
        if not isinstance(ctx, dict):
            return
        for term, d in ctx.items():
            if isinstance(d, str) and (d.endswith("#") or d.endswith("/")):
                self.prefixes[term] = d
        for term, d in ctx.items():
            if term.startswith("@"):
                continue
            iri = d if isinstance(d, str) else d.get("@id") if isinstance(d, dict) else None
            scoped = None
            if isinstance(d, dict) and "@context" in d:
                scoped = Context()
                scoped.prefixes = dict(self.prefixes)
                scoped.add(d["@context"], src)
            self.terms.setdefault(term, []).append((self.expand(iri or term), scoped))

    def expand(self, iri):
        if "://" in iri or ":" not in iri:
            return iri
        p, _, local = iri.partition(":")
        return self.prefixes[p] + local if p in self.prefixes else iri

    def iris(self, key, types):
        """The IRIs `key` means on a node of these type terms (none: not a term)."""
        defs = list(self.terms.get(key, []))
        for t in types:
            for _, scoped in self.terms.get(t, []):
                if scoped is not None:
                    defs += scoped.terms.get(key, [])
        if defs:
            return {iri for iri, _ in defs}
        if "://" in key:
            return {key}
        if ":" in key and key.split(":", 1)[0] in self.prefixes:
            return {self.expand(key)}
        return set()

    def keys_for(self, types):
        out = set(k for k in self.terms if k[:1].islower())
        for t in types:
            for _, scoped in self.terms.get(t, []):
                if scoped is not None:
                    out |= set(scoped.terms)
        return out


def nearest(key, candidates):
    """The candidate a key is likely a slip for: one that contains it or that
    it contains (the closest in length), else the closest spelling."""
    within = sorted((abs(len(c) - len(key)), c) for c in candidates if key in c or c in key)
    if within:
        return [within[0][1]]
    return difflib.get_close_matches(key, candidates, 1, 0.5)


def load(path):
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (ValueError, OSError):
        return None


def as_list(v):
    return v if isinstance(v, list) else [v]


def nodes(doc):
    """Every JSON object of a document that has an @type."""
    if isinstance(doc, dict):
        if "@type" in doc:
            yield doc
        for k, v in doc.items():
            if k != "@context":
                yield from nodes(v)
    elif isinstance(doc, list):
        for x in doc:
            yield from nodes(x)


def json_keys(node, out):
    if isinstance(node, dict):
        for k, v in node.items():
            out.add(k)
            json_keys(v, out)
    elif isinstance(node, list):
        for x in node:
            json_keys(x, out)


# ---- a ```json block: comments and placeholders allowed ---------------------


def parse_block(text):
    lines = []
    for line in text.split("\n"):
        # A `//` comment after an even number of quotes (not inside a string).
        for m in re.finditer(r"//", line):
            if line[:m.start()].count('"') % 2 == 0:
                line = line[:m.start()]
                break
        if line.strip() in ("...", "...,"):
            continue
        lines.append(line)
    t = "\n".join(lines).strip().rstrip(",")
    t = re.sub(r"\{\s*\.\.\.[^{}]*\}", "{}", t)  # { ...prose... }
    t = re.sub(r",(\s*[\]}])", r"\1", t)  # a trailing comma a placeholder left
    # A node, a list of nodes, or the members of one.
    for wrapped in (t, "[" + t + "]", "{" + t + "}"):
        try:
            return json.loads(wrapped)
        except ValueError:
            continue
    return None


class Checker:
    def __init__(self, src, extra):
        self.src = src
        self.shapes = Shapes(src)
        self.all = Context()
        for f in sorted((src / "metamodels").rglob("*.json")):
            doc = load(f)
            if isinstance(doc, dict):
                self.all.add(doc.get("@context"), src)
        # Shipped models: the properties they use on each class (strict-clean
        # models, so mospec reads them there: a property a shape checks on the
        # subjects of some property, or one read by lowering, names no class).
        self.used = {}
        self.cotypes = {}  # a type term -> the types shipped nodes of that type carry with it
        self.model_keys = set(k for k in self.all.terms)
        shipped = [src / "models", src / "robots", src / "tests/ir/data"]
        for f in sorted(f for d in shipped for f in list(d.rglob("*.json")) + list(d.rglob("*.jsonld"))):
            if f.name.endswith(".world.json"):
                continue
            doc = load(f)
            if not isinstance(doc, dict):
                continue
            ctx = Context()
            ctx.add(doc.get("@context"), src)
            self.model_keys |= set(ctx.terms)
            for n in nodes(doc):
                types = [t for t in as_list(n["@type"]) if isinstance(t, str)]
                for t in types:
                    self.cotypes.setdefault(t, set()).update(types)
                classes = set().union(*(ctx.iris(t, []) or {t} for t in types)) if types else set()
                for k in n:
                    for iri in ctx.iris(k, types):
                        for c in classes:
                            self.used.setdefault(c, set()).add(iri)
        self.world_keys = set()
        for f in sorted((src / "models").rglob("*.world.json")):
            json_keys(load(f), self.world_keys)
        self.others = set(self.world_keys)
        for f in extra:
            json_keys(load(pathlib.Path(f)), self.others)
        reader = (src / "src/sim/config.cpp").read_text(encoding="utf-8")
        self.config_keys = set(re.findall(r'"([a-z][\w-]*)"', reader))
        self.classes = {t for t, defs in self.all.terms.items() if t[:1].isupper()}
        # Every property term, also those only a class's scoped context defines.
        self.property_terms = {t for t in self.all.terms if t[:1].islower()}
        for defs in self.all.terms.values():
            for _, scoped in defs:
                if scoped is not None:
                    self.property_terms |= set(scoped.terms)
        self.bad = 0
        self.messages = []  # (file, line, text)
        self.checked = 0  # keys checked against a class

    def report(self, where, key, what, near):
        file, _, line = where.rpartition(":")
        self.messages.append((file, int(line), f'{where}: "{key}" {what}'
                              + (f'; did you mean "{near[0]}"?' if near else "")))
        self.bad += 1

    def check_key(self, where, ctx, types, key, honoured=True, label=None):
        """A key on a node of these type terms; True when mospec reads it there.
        A key a document says is refused (`honoured` false) need only be a term."""
        if key.startswith("@"):
            return True
        self.checked += 1
        label = label or "on a " + "/".join(types)
        if not honoured:
            if key in self.property_terms or ctx.iris(key, types):
                return True
            self.report(where, key, f"{label} is no term of any context of metamodels/",
                        nearest(key, sorted(self.property_terms)))
            return False
        classes = set()
        for t in types:
            iris = ctx.iris(t, [])
            if not iris:
                self.report(where, t, "is a type no context of metamodels/ defines", [])
                return False
            classes |= iris
        candidates = sorted(k for k in ctx.keys_for(types)
                            if any(self.allowed(classes, i) for i in ctx.iris(k, types)))
        near = nearest(key, candidates)
        iris = ctx.iris(key, types)
        if not iris:
            self.report(where, key, f"{label} is no term of the contexts it uses", near)
            return False
        if honoured and not any(self.allowed(classes, i) for i in iris):
            self.report(where, key, f"(<{sorted(iris)[0]}>) {label}: no shape of metamodels/ "
                        "allows it there", near)
            return False
        return True

    def allowed(self, classes, iri):
        return self.shapes.allows(classes, iri) or any(iri in self.used.get(c, ()) for c in classes)

    def check_block(self, doc_path, line, text, inline=False):
        doc = parse_block(text)
        if doc is None and inline:
            return  # inline code that only looks like JSON (`{"present": false}` is JSON)
        if doc is None:
            print(f"{doc_path}:{line}: a ```json block that does not parse (// comments and ... "
                  "placeholders aside)")
            self.bad += 1
            return
        found = list(nodes(doc))
        lines = text.split("\n")

        def line_of(key, start=0):
            for i in range(start, len(lines)):
                if f'"{key}"' in lines[i]:
                    return line + 1 + i
            return line

        if not found and "@context" not in json.dumps(doc):
            keys = set()
            json_keys(doc, keys)
            for k in sorted(keys):
                if k not in self.config_keys and "://" not in k:  # an IRI prefix of a "map"
                    self.report(f"{doc_path}:{line_of(k)}", k, "is no key of a world file "
                                "(src/sim/config.cpp reads no such key)",
                                difflib.get_close_matches(k, sorted(self.config_keys), 1, 0.6))
            return
        ctx = Context()
        own = [c for c in (doc.get("@context") if isinstance(doc, dict) else None,) if c is not None]
        if own:
            ctx.add(own[0], self.src)
        else:
            ctx = self.all
        for n in found:
            types = [t for t in as_list(n["@type"]) if isinstance(t, str)]
            for k in n:
                self.check_key(f"{doc_path}:{line_of(k)}", ctx, types, k)

    def check_doc(self, doc_path):
        lines = pathlib.Path(doc_path).read_text(encoding="utf-8").split("\n")
        # Paragraphs and list items outside fenced blocks: [(line, text)].
        blocks, fenced, block, fence_start, fence_lang, fence_text = [], False, [], 0, "", []
        for n, line in enumerate(lines, 1):
            if line.startswith("```"):
                if not fenced:
                    fenced, fence_start, fence_lang, fence_text = True, n, line[3:].strip(), []
                else:
                    fenced = False
                    if fence_lang == "json":
                        self.check_block(doc_path, fence_start, "\n".join(fence_text))
                if block:
                    blocks.append(block)
                block = []
                continue
            if fenced:
                fence_text.append(line)
                continue
            new_item = re.match(r"\s*([-*]|\d+\.) ", line) is not None
            if (not line.strip() or new_item) and block:
                blocks.append(block)
                block = []
            if line.strip():
                block.append((n, line))
        if block:
            blocks.append(block)
        for block in blocks:
            self.check_prose(doc_path, block)

    def check_prose(self, doc_path, block):
        if block[0][1].lstrip().startswith("|"):
            return self.check_table(doc_path, block)
        # Inline code spans in order: (line, sentence, text). A sentence ends
        # at '.', '!' or '?' before a blank and a capital (outside code).
        # A span may run over lines (an inline JSON node).
        text = "\n".join(line for _, line in block)
        starts = [0]
        for _, line in block:
            starts.append(starts[-1] + len(line) + 1)
        spans, sentence, pos = [], 0, 0
        for m in re.finditer(r"`([^`]+)`", text):
            sentence += len(re.findall(r"[.!?]\s+(?=[A-Z*(])", text[pos:m.start()]))
            n = block[max(i for i, st in enumerate(starts[:-1]) if st <= m.start())][0]
            spans.append((n, sentence, m.group(1).replace("\n", " ")))
            pos = m.end()
        for i, (n, sent, s) in enumerate(spans):
            if s.startswith("{"):
                self.check_block(doc_path, n - 1, s, inline=True)
                continue
            m = re.fullmatch(r'"([^"`\s]+)"(?::.*)?', s)
            if not m:
                continue
            key, where = m.group(1), f"{doc_path}:{n}"
            named = [(j, c) for j, (_, t, c) in enumerate(spans) if t == sent and c in self.classes]
            if ":" in key and "://" not in key and key.split(":")[0] not in self.all.prefixes:
                continue  # a compact IRI as a value ("ex:Robot"), not a key
            if named:
                before = [c for j, c in named if j < i]
                self.check_class_key(where, before[-1] if before else named[0][1], key)
            elif not (key in self.model_keys or key in self.others or key.startswith("@")):
                self.report(where, key, "is no key mospec reads: no context of metamodels/ or "
                            "of a shipped model defines it, and no world file or summary has it",
                            difflib.get_close_matches(key, sorted(self.model_keys | self.others), 1, 0.6))

    def check_class_key(self, where, cls, key, honoured=True):
        """A key the prose gives a class: on a node of that class and of the
        classes shipped nodes of it carry with it (a PID is also a Controller)."""
        types = [cls] + sorted(self.cotypes.get(cls, set()) - {cls})
        return self.check_key(where, self.all, types, key, honoured, f"beside `{cls}`")

    def check_table(self, doc_path, rows):
        """A table whose header has `class` and `property` columns (docs/ir.md):
        each row's backticked properties are keys of its classes."""
        cells = [[c.strip() for c in line.strip().strip("|").split("|")] for _, line in rows]
        head = [c.lower() for c in cells[0]]
        if "class" not in head or "property" not in head:
            return
        ci, pi = head.index("class"), head.index("property")
        oi = head.index("outcome") if "outcome" in head else None
        for (n, _), row in zip(rows[2:], cells[2:]):
            if len(row) <= max(ci, pi):
                continue
            classes = [c for c in (re.sub(r"\(.*?\)|[\w-]+:", "", x).strip("` ")
                                   for x in row[ci].split(",")) if c in self.classes]
            honoured = oi is None or row[oi].startswith("honoured")
            for key in re.findall(r"`([^`]+)`", re.sub(r"\(.*?\)", "", row[pi])):
                if row[pi].startswith("class ") or not re.fullmatch(r"[\w-]+(:[\w-]+)?", key):
                    continue
                for cls in classes:
                    self.check_class_key(f"{doc_path}:{n}", cls, key, honoured)


def main(argv):
    src = pathlib.Path(argv[1])
    rest = argv[2:]
    docs, extra = (rest[:rest.index("--json")], rest[rest.index("--json") + 1:]) \
        if "--json" in rest else (rest, [])
    checker = Checker(src, extra)
    for doc in docs:
        checker.check_doc(doc)
    for _, _, text in sorted(checker.messages):
        print(text)
    print(f"docs_keys: {checker.checked} key(s) checked against their class, "
          f"{checker.bad} wrong", file=sys.stderr)
    return 1 if checker.bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
