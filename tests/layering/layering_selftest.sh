#!/usr/bin/env bash
# layering_selftest.sh CHECKER SRC_DIR: proves check_layers.sh can fail. Runs it
# on small trees built here and on a copy of SRC_DIR with a planted violating
# include and a planted cycle; each broken tree must fail with its message, the
# clean ones must pass.
set -u
checker=$(realpath "$1")
src=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passed=0
fail() { echo "FAIL $1"; failures=$((failures+1)); }

# expect NAME CODE PATTERN TREE: the checker on TREE exits CODE and its output
# matches the extended regex PATTERN.
expect() {
  local name=$1 code=$2 pattern=$3 tree=$4 got
  "$checker" "$tree" > "$work/out.txt" 2>&1
  got=$?
  if [ "$got" -ne "$code" ]; then
    fail "$name: exit $got, expected $code"; sed 's/^/  out: /' "$work/out.txt"; return
  fi
  if ! grep -Eq -- "$pattern" "$work/out.txt"; then
    fail "$name: output does not match /$pattern/"; sed 's/^/  out: /' "$work/out.txt"; return
  fi
  passed=$((passed+1))
}

# tree NAME LAYERS-TEXT: a tree with folders base, mid, top; top includes mid
# and base, mid includes base.
tree() {
  local t=$work/$1
  mkdir -p "$t/base" "$t/mid" "$t/top"
  printf '#include "base/b.hpp"\n' > "$t/base/b.cpp"
  printf '#pragma once\n#include "base/b.hpp"\n' > "$t/mid/m.hpp"
  printf '#include "mid/m.hpp"\n#include <vector>\n  #  include "base/b.hpp"\n' > "$t/top/t.cpp"
  printf '%s\n' "$2" > "$t/LAYERS"
  echo "$t"
}

t=$(tree clean $'base:\nmid: base\ntop: mid base')
expect "clean tree passes" 0 'layering: OK \(3 folders, 4 includes' "$t"

t=$(tree upward $'base:\nmid: base\ntop: mid base')
printf '\n#include "top/t.hpp"  // planted\n' >> "$t/base/b.cpp"
expect "lower folder including a higher one" 1 \
  'base/b\.cpp:3: error: #include "top/t\.hpp"  // planted: src/base may not include src/top; .*LAYERS:1 lets base include only itself$' "$t"

t=$(tree skip $'base:\nmid: base\ntop: mid')
expect "include not listed (not transitive)" 1 'top/t\.cpp:3: error: .*may not include src/base; the rule .*LAYERS:3 lets top include only itself, mid$' "$t"

t=$(tree angle $'base:\nmid: base\ntop: mid base')
printf '#include <Eigen/Dense>\n#include <mid/m.hpp>\n' > "$t/base/angle.hpp"
expect "angle-bracket include of a src/ folder" 1 'base/angle\.hpp:2: error: #include <mid/m\.hpp>: src/base may not include src/mid' "$t"

t=$(tree cycle $'base: top\nmid: base\ntop: mid base')
expect "cycle" 1 'error: the layering has a cycle: (base -> top -> mid -> base|top -> mid -> base -> top|base -> top -> base)' "$t"

t=$(tree unknown $'base:\nmid: base basement\ntop: mid base')
expect "unknown listed folder" 1 'LAYERS:2: error: mid lists basement, but .* is not a folder' "$t"

t=$(tree stale $'base:\nmid: base\ntop: mid base\ngone: base')
expect "declared folder that does not exist" 1 'LAYERS:4: error: gone is declared but .*gone is not a folder' "$t"

t=$(tree missing $'base:\ntop: mid base')
expect "folder without a line" 1 'error: folder .*/mid has no line' "$t"

t=$(tree twice $'base:\nmid: base\ntop: mid base\nmid: base')
expect "folder declared twice" 1 'LAYERS:4: error: folder mid is declared twice' "$t"

t=$(tree malformed $'base:\nmid base\ntop: mid base')
expect "malformed line" 1 'LAYERS:2: error: malformed line' "$t"

# The project's own tree and declaration, then with planted breakage.
cp -r "$src" "$work/src"
expect "project tree passes" 0 'layering: OK' "$work/src"
printf '#include <vector>\n#include "ir/lower.hpp"\n' > "$work/src/support/planted.cpp"
expect "project tree with support including ir" 1 \
  'support/planted\.cpp:2: error: #include "ir/lower\.hpp": src/support may not include src/ir' "$work/src"
rm -rf "$work/src" && cp -r "$src" "$work/src"
printf '# planted\ntarget_link_libraries(mospec_support PRIVATE mospec_warnings\n  mospec_ir)\n' \
  >> "$work/src/support/CMakeLists.txt"
n=$(wc -l < "$work/src/support/CMakeLists.txt")
expect "project tree with support linking ir" 1 \
  "support/CMakeLists\.txt:$n: error: mospec_ir\): src/support may not link mospec_ir \(src/ir\)" "$work/src"
rm -rf "$work/src" && cp -r "$src" "$work/src"
sed -i -E 's/^support:.*/support: cli/' "$work/src/LAYERS"
expect "project declaration with support -> cli" 1 'error: the layering has a cycle: .*support.*cli' "$work/src"

echo "layering_selftest: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
