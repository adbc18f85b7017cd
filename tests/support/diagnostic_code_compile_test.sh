#!/usr/bin/env bash
# A literal diagnostic code is checked when mospec compiles: a code in the
# catalogue (src/support/diagnostic_codes.hpp) compiles, a misspelt one does
# not, and the compiler names the reason. Usage: diagnostic_code_compile_test.sh CXX SOURCE_DIR
cxx=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
compile() {  # compile NAME CODE: the compiler's exit status, its output in $work/NAME.txt
  printf '#include "support/diagnostics.hpp"\nvoid f() { throw mospec::Error("%s", "message"); }\n' "$2" \
    > "$work/$1.cpp"
  "$cxx" -std=c++20 -fsyntax-only -I"$src/src" "$work/$1.cpp" > "$work/$1.txt" 2>&1
}
if ! compile known loop-sign; then
  echo "FAIL a catalogued code does not compile:"; cat "$work/known.txt"; failures=$((failures + 1))
fi
if compile misspelt loop-sing; then
  echo "FAIL a code that is not in the catalogue compiles"; failures=$((failures + 1))
elif ! grep -q "diagnostic_code_not_in_catalogue" "$work/misspelt.txt"; then
  echo "FAIL the compiler does not say why a misspelt code is refused:"; head -20 "$work/misspelt.txt"
  failures=$((failures + 1))
fi
echo "diagnostic_code_compile_test: $failures failed"
[ "$failures" -eq 0 ]
