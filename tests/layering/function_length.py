#!/usr/bin/env python3
"""function_length.py ROOT [--allow FILE] | --selftest

No function in ROOT/src/ir and its subfolders (*.cpp, *.hpp) is longer than 80 lines, counted
from the line of its name to its closing brace. Prints one
`FILE:LINE: function NAME is N lines (limit 80)` per longer function and
exits 1. An allow-list (one `FILE FUNCTION` per line, `#` comments) exempts a
function; an entry that exempts nothing is an error too, so the list holds
only what still needs it.

The scan matches braces in the source with strings, character literals,
comments and preprocessor lines blanked out. A `{` at namespace or class
scope opens a namespace/struct/class/enum/union body (scanned for the
functions inside), a brace initialiser (skipped), or a function body: a
header with a parameter list ending in `)`, its qualifiers, a trailing
return type or a constructor's initialisers. Lambdas and local classes
count towards the function holding them.
"""
import os
import re
import sys
import tempfile

LIMIT = 80
QUALIFIERS = {"const", "noexcept", "override", "final", "mutable", "volatile", "try"}
CONTAINERS = re.compile(r"\b(namespace|struct|class|enum|union)\b")
OPERATOR = re.compile(r"((?:\w+\s*::\s*)*operator\s*(?:\(\s*\)|[^\s\w(]+|\s\w[\w\s:*&<>]*?))\s*$")
NAME = re.compile(r"(~?[A-Za-z_][\w]*(?:\s*::\s*~?[A-Za-z_]\w*)*)\s*$")


def blank(text):
    """text with comments, strings, char literals and preprocessor lines replaced
    by spaces (newlines kept, so offsets keep their line)."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if line_start and c == "#":
            j = i
            while j < n and (text[j] != "\n" or text[j - 1] == "\\"):
                j += 1
            wipe(i, j)
            i = j
            continue
        if c == "\n":
            line_start = True
            i += 1
            continue
        if not c.isspace():
            line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            wipe(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            wipe(i, j)
            i = j
        elif c == "R" and i + 1 < n and text[i + 1] == '"' and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^()\\\s]{0,16})\(', text[i:])
            if not m:
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i + m.end())
            j = n if end < 0 else end + len(m.group(1)) + 2
            wipe(i, j)
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                i += 1  # a digit separator: 1'000
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            wipe(i, min(j + 1, n))
            i = j + 1
        else:
            i += 1
    return "".join(out)


def match_brace(code, i):
    """Index of the `}` closing the `{` at i."""
    depth = 0
    for j in range(i, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code) - 1


def strip_template(header):
    m = re.match(r"\s*template\s*<", header)
    if not m:
        return header
    depth, j = 1, m.end()
    while j < len(header) and depth:
        depth += {"<": 1, ">": -1}.get(header[j], 0)
        j += 1
    return " " * j + header[j:]


NOT_PARAMETERS = re.compile(r"\b(decltype|alignas|__attribute__|noexcept)\s*$")


def top_level(header):
    """header with everything inside (), [] and {} blanked, and the offset of
    the first top-level `(` that opens a parameter list (not decltype(...)'s),
    or -1."""
    out, depth, first = [], 0, -1
    for k, ch in enumerate(header):
        if ch in "([{":
            if depth == 0 and ch == "(" and first < 0 and not NOT_PARAMETERS.search(header[:k]):
                first = k
            depth += 1
            out.append(ch if depth == 1 else " ")
        elif ch in ")]}":
            depth -= 1
            out.append(ch if depth == 0 else " ")
        else:
            out.append(ch if depth == 0 else " ")
    return "".join(out), first


def classify(header):
    """'container', 'function' (with its name and the header offset of its
    parameter list) or 'init' for the `{` after header."""
    header = strip_template(header)
    flat, paren = top_level(header)
    before = flat if paren < 0 else flat[:paren]
    if CONTAINERS.search(before):
        return "container", None, None
    if paren < 0:
        return ("container" if not flat.strip() else "init"), None, None
    if re.search(r"(?<![=!<>])=(?!=)", before.replace("operator", " ")) and "operator" not in before:
        return "init", None, None  # a lambda or value assigned at namespace scope
    last = re.search(r"([\w]+|\S)\s*$", flat)
    after = flat[flat.rfind(")") + 1:] if ")" in flat else ""
    if last and re.match(r"\w", last.group(1)) and last.group(1) not in QUALIFIERS and "->" not in after:
        return "init", None, None  # a member initialiser x_{...} in a constructor's list
    m = OPERATOR.search(header[:paren]) or NAME.search(header[:paren])
    if not m or m.group(1) in ("if", "for", "while", "switch", "catch", "return"):
        return "init", None, None
    return "function", re.sub(r"\s+", "", m.group(1)), paren


def functions(text):
    """(name, first line, line count) of every function defined in text."""
    code = blank(text)
    found = []
    header_start = 0
    i = 0
    while i < len(code):
        ch = code[i]
        if ch == ";" or ch == "}":
            header_start = i + 1
        elif ch == ":" and re.search(r"\b(public|private|protected)\s*$", code[header_start:i]):
            header_start = i + 1
        elif ch == "{":
            header = code[header_start:i]
            # A brace inside parentheses (a lambda in a constructor's
            # initialiser) is part of the header.
            open_parens = header.count("(") - header.count(")")
            kind, name, paren = ("init", None, None) if open_parens > 0 else classify(header)
            if kind == "container":
                header_start = i + 1
            else:
                end = match_brace(code, i)
                if kind == "function":
                    first = code.count("\n", 0, header_start + paren) + 1
                    last = code.count("\n", 0, end) + 1
                    found.append((name, first, last - first + 1))
                    header_start = end + 1
                i = end
        i += 1
    return found


def scan(root, files, allow):
    problems, used = [], set()
    for rel in files:
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            text = f.read()
        for name, line, length in functions(text):
            if length <= LIMIT:
                continue
            if (rel, name) in allow:
                used.add((rel, name))
                continue
            problems.append(f"{rel}:{line}: function {name} is {length} lines (limit {LIMIT})")
    for rel, name in sorted(set(allow) - used):
        problems.append(f"{allow[(rel, name)]}: '{rel} {name}' is allowed but is no function "
                        f"over {LIMIT} lines: remove it from the allow-list")
    return problems


def read_allow(path):
    allow = {}
    with open(path, encoding="utf-8") as f:
        for number, raw in enumerate(f, 1):
            line = raw.split("#", 1)[0].split()
            if not line:
                continue
            if len(line) != 2:
                sys.exit(f"{path}:{number}: error: expected `FILE FUNCTION`, got '{raw.strip()}'")
            allow[(line[0], line[1])] = f"{path}:{number}"
    return allow


def ir_files(root):
    """Every C++ file under src/ir, its subfolders (kinds/) included."""
    found = []
    for folder, _, files in os.walk(os.path.join(root, "src", "ir")):
        rel = os.path.relpath(folder, root)
        found += [os.path.join(rel, f) for f in files if f.endswith((".cpp", ".hpp"))]
    return sorted(found)


def check(root, allow_path):
    allow = read_allow(allow_path) if allow_path else {}
    files = ir_files(root)
    problems = scan(root, files, allow)
    for p in problems:
        print(p)
    if problems:
        print(f"function_length: {len(problems)} problem(s); split long functions into "
              f"small, named ones")
        return 1
    print(f"function_length: OK ({len(files)} files, every function <= {LIMIT} lines, "
          f"{len(allow)} allowed)")
    return 0


def body(lines):
    """A function body of `lines` lines in all (its header and closing brace included)."""
    return "\n".join(f"  x += {k};  // {{ not a brace" for k in range(lines - 2))


def selftest():
    """The scanner on planted sources: what it must flag, and what it must not."""
    failures = []

    def expect(what, text, want):
        got = [(n, length) for n, _, length in functions(text)]
        if got != want:
            failures.append(f"{what}: found {got}, expected {want}")

    expect("an 80-line function", "int f(int x) {\n" + body(80) + "\n}\n", [("f", 80)])
    expect("an 81-line function", "int f(int x) {\n" + body(81) + "\n}\n", [("f", 81)])
    expect("multi-line header counted from the name",
           "std::string\nState::datum(int a,\n             int b) const {\n  return {};\n}\n",
           [("State::datum", 4)])
    expect("strings, chars, comments and raw strings hide braces",
           'void g() {\n  s = "}}";\n  c = \'{\';\n  /* } */\n  r = R"x(})x";\n}\n'
           "// void h() {\n", [("g", 6)])
    expect("namespace, struct and member functions",
           "namespace a {\nnamespace {\nstruct S : B {\n  int m() const { return 1; }\n"
           "  S() : x_(1), y_{2} {\n    go();\n  }\n int z{3};\n};\n}  // namespace\n}\n",
           [("m", 1), ("S", 3)])
    expect("brace initialisers and lambdas at namespace scope are no functions",
           "const std::vector<int> v = {1, 2};\nconst auto l = [](int a) {\n  return a;\n};\n"
           "Table t{{\"a\", [](int) { return 0; }}};\nenum class E : int { A, B };\n", [])
    expect("trailing return types, templates, operators",
           "template <class T = int>\nauto f(T t) -> std::vector<T> {\n  return {t};\n}\n"
           "bool operator==(const A& a, const A& b) noexcept {\n  return true;\n}\n",
           [("f", 3), ("operator==", 3)])
    expect("a lambda in a constructor's initialiser is part of its header",
           "E::E(int d)\n    : B([&] {\n        return d;\n      }()),\n      d_(d) {}\n"
           "int g() {\n  return 1;\n}\n", [("E::E", 5), ("g", 3)])
    expect("a deduced return type",
           "template <class K>\ndecltype(auto) run(K&& k) {\n  return k();\n}\n", [("run", 3)])
    expect("lambdas and control blocks count towards their function",
           "void f() {\n  auto g = [&] {\n    if (x) {\n    }\n  };\n}\n", [("f", 6)])

    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "src", "ir"))

        def write(name, text):
            with open(os.path.join(root, "src", "ir", name), "w", encoding="utf-8") as f:
                f.write(text)

        write("long.cpp", "namespace n {\n\nint too_long() {\n" + body(81) + "\n}\n"
              "int fits() {\n" + body(80) + "\n}\n}\n")
        write("short.hpp", "#pragma once\ninline int f() { return 1; }\n")
        problems = scan(root, ir_files(root), {})
        want = ["src/ir/long.cpp:3: function too_long is 81 lines (limit 80)"]
        if problems != want:
            failures.append(f"81-line function: reported {problems}, expected {want}")
        allow_path = os.path.join(root, "allow.txt")
        with open(allow_path, "w", encoding="utf-8") as f:
            f.write("# why\nsrc/ir/long.cpp too_long  # being rewritten\n")
        if scan(root, ir_files(root), read_allow(allow_path)):
            failures.append("an allowed function is still reported")
        with open(allow_path, "a", encoding="utf-8") as f:
            f.write("src/ir/long.cpp fits\n")
        problems = scan(root, ir_files(root), read_allow(allow_path))
        if len(problems) != 1 or "allow.txt:3: 'src/ir/long.cpp fits' is allowed but" not in problems[0]:
            failures.append(f"a stale allow-list entry: reported {problems}")
        if check(root, None) != 1:
            failures.append("the check passes a tree with an 81-line function")

    for f in failures:
        print("FAIL " + f)
    if failures:
        return 1
    print("function_length selftest: OK")
    return 0


def main(argv):
    if argv[1:] == ["--selftest"]:
        return selftest()
    if len(argv) == 2:
        return check(argv[1], None)
    if len(argv) == 4 and argv[2] == "--allow":
        return check(argv[1], argv[3])
    sys.exit("usage: function_length.py ROOT [--allow FILE] | --selftest")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
