#!/usr/bin/env python3
"""tests_mirror_src.py SRC_DIR TESTS_DIR: the tests mirror the libraries.

Every folder of src/ (a library) has a folder of the same name in tests/ that
registers at least one test (mospec_test or add_test in tests/<folder>/
CMakeLists.txt, added by tests/CMakeLists.txt, or mospec_test in
tests/CMakeLists.txt itself with sources under <folder>/), so the unit tests
of a library are found beside each other and a library without any is seen.
Every folder of tests/ is named after a library, except the cross-cutting
ones below. Fails (exit 1) listing every folder that breaks either rule.

`tests_mirror_src.py --selftest SRC_DIR TESTS_DIR` checks that planted cases
are caught.
"""
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

# Folders of tests/ that test no one library, and why.
CROSS_CUTTING = {
    "conformance": "the W3C JSON-LD and SHACL test suites, through jsonld, shacl and app together",
    "scenarios": "the shipped apps run end to end (lowering, codegen, simulation, verdict)",
    "models": "the shipped models (metamodels, robots, apps) validated and run through the CLI",
    "layering": "checks of the source tree itself (include layering, vocabulary home, these rules)",
}


def code(text):
    """CMake text without comments."""
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


def registers_tests(tests, folder):
    top = code((tests / "CMakeLists.txt").read_text()) if (tests / "CMakeLists.txt").exists() else ""
    # mospec_test(NAME LABEL folder/x.cpp ...) in tests/CMakeLists.txt itself.
    for m in re.finditer(r"\bmospec_test\s*\(([^)]*)\)", top):
        if re.search(r"(^|\s)" + re.escape(folder) + r"/\S+", m.group(1)):
            return True
    if not re.search(r"\badd_subdirectory\s*\(\s*" + re.escape(folder) + r"\s*\)", top):
        return False
    own = tests / folder / "CMakeLists.txt"
    if not own.exists():
        return False
    return re.search(r"\b(mospec_test|add_test)\s*\(", code(own.read_text())) is not None


def check(src, tests):
    problems = []
    libraries = sorted(p.name for p in src.iterdir() if p.is_dir())
    folders = sorted(p.name for p in tests.iterdir() if p.is_dir())
    for lib in libraries:
        if not (tests / lib).is_dir():
            problems.append(f"{src / lib}: error: library '{lib}' has no tests/{lib}/: put its "
                            f"unit tests there (or write one for its public API)")
        elif not registers_tests(tests, lib):
            problems.append(f"{tests / lib}: error: tests/{lib}/ registers no test (no mospec_test "
                            f"or add_test in its CMakeLists.txt, or tests/CMakeLists.txt does not "
                            f"add_subdirectory({lib}))")
    for folder in folders:
        if folder not in libraries and folder not in CROSS_CUTTING:
            problems.append(f"{tests / folder}: error: tests/{folder}/ is named after no library in "
                            f"src/: move its tests to the folder of the library they test, or list "
                            f"it as cross-cutting, with the reason, in {Path(__file__).name}")
    return problems


def selftest(src, tests):
    status = 0
    with tempfile.TemporaryDirectory() as tmp:
        s, t = Path(tmp) / "src", Path(tmp) / "tests"
        shutil.copytree(src, s, ignore=shutil.ignore_patterns("*.cpp", "*.hpp", "*.json", "*.ttl"))
        shutil.copytree(tests, t, ignore=shutil.ignore_patterns("*.cpp", "*.hpp", "*.json", "*.ttl",
                                                                "*.jsonld", "data"))
        run = lambda: subprocess.run([sys.executable, __file__, str(s), str(t)],
                                     capture_output=True, text=True)
        if run().returncode != 0:
            print("tests_mirror_src selftest: the tree itself fails")
            return 1
        # A library without a test folder.
        (s / "newlib").mkdir()
        r = run()
        if r.returncode == 0 or "library 'newlib' has no tests/newlib/" not in r.stdout:
            print("tests_mirror_src selftest: a library without tests/ not caught:", r.stdout)
            status = 1
        # ... with one that registers nothing, or is not added.
        (t / "newlib").mkdir()
        (t / "newlib" / "CMakeLists.txt").write_text("# mospec_test(newlib_test newlib x.cpp)\n")
        with open(t / "CMakeLists.txt", "a") as f:
            f.write("add_subdirectory(newlib)\n")
        r = run()
        if r.returncode == 0 or "tests/newlib/ registers no test" not in r.stdout:
            print("tests_mirror_src selftest: a test folder registering nothing not caught:", r.stdout)
            status = 1
        (t / "newlib" / "CMakeLists.txt").write_text("mospec_test(newlib_test newlib x.cpp)\n")
        if run().returncode != 0:
            print("tests_mirror_src selftest: a registered test was not seen")
            status = 1
        text = (t / "CMakeLists.txt").read_text().replace("add_subdirectory(newlib)\n", "")
        (t / "CMakeLists.txt").write_text(text)
        r = run()
        if r.returncode == 0 or "tests/newlib/ registers no test" not in r.stdout:
            print("tests_mirror_src selftest: a test folder never added not caught:", r.stdout)
            status = 1
        shutil.rmtree(s / "newlib")
        shutil.rmtree(t / "newlib")
        # A test folder named after no library.
        (t / "misc").mkdir()
        r = run()
        if r.returncode == 0 or "tests/misc/ is named after no library" not in r.stdout:
            print("tests_mirror_src selftest: a stray test folder not caught:", r.stdout)
            status = 1
    if status == 0:
        print("tests_mirror_src selftest: ok")
    return status


def main(argv):
    if len(argv) == 4 and argv[1] == "--selftest":
        return selftest(Path(argv[2]), Path(argv[3]))
    if len(argv) != 3:
        print("usage: tests_mirror_src.py [--selftest] SRC_DIR TESTS_DIR")
        return 2
    problems = check(Path(argv[1]), Path(argv[2]))
    for p in problems:
        print(p)
    print("tests_mirror_src: " + ("FAILED" if problems else "ok"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
