#!/usr/bin/env bash
# `mospec run --sim` and its controller cache, as an attacker would try it:
#   - a model bundle that ships a `.mospec-cache/` (a Makefile and a library
#     that would leave a marker) in the working directory: never used, and the
#     run writes nothing there; the cache is $XDG_CACHE_HOME/mospec, private;
#   - a library replaced in the real cache entry (by one whose constructor
#     leaves a marker): detected before loading, built again, never loaded;
#   - a cache directory others can write into: refused, naming it and the fix;
#   - a relative XDG_CACHE_HOME is ignored (HOME's .cache instead); neither
#     set: an error asking for --cache.
# usage: cache_cli_test.sh MOSPEC SOURCE_DIR CXX
SRC="$2"
CXX="$3"
source "$SRC/tests/support/cli_lib.sh"

export XDG_CACHE_HOME="$work/xdg"
markers="$work/markers"
mkdir -p "$markers"

# A library that leaves a marker the moment it is loaded, and a Makefile that
# leaves one when it is run.
cat > "$work/evil.cpp" <<EOF
#include <cstdio>
__attribute__((constructor)) static void planted() {
  if (std::FILE* f = std::fopen("$markers/loaded", "w")) std::fclose(f);
}
EOF
"$CXX" -shared -fPIC -o "$work/evil.so" "$work/evil.cpp" || { echo "cannot compile evil.so"; exit 1; }

# The bundle: the model and a planted cache beside it, at every key a cwd
# cache could have had (any name: mospec must not look).
bundle="$work/bundle"
mkdir -p "$bundle"
cp -r "$SRC/models" "$SRC/robots" "$SRC/metamodels" "$bundle/"
for key in planted 0123456789abcdef; do
  mkdir -p "$bundle/.mospec-cache/$key/build"
  printf 'all:\n\ttouch %s/make-ran\n' "$markers" > "$bundle/.mospec-cache/$key/build/Makefile"
  cp "$work/evil.so" "$bundle/.mospec-cache/$key/build/libmospec_controller.so"
done
(cd "$bundle" && find . -exec stat -c '%n %s %Y' {} + | sort) > "$work/bundle-before.txt"

cd "$bundle" || exit 1
expect "a run in the bundle builds its controller" 0 "generated and built the controller in $XDG_CACHE_HOME/mospec/[0-9a-f]{64}" -- \
  "$mospec" run models/sc0a --sim --duration 0.05
check "the planted Makefile did not run" test ! -e "$markers/make-ran"
check "the planted library was not loaded" test ! -e "$markers/loaded"
(cd "$bundle" && find . -exec stat -c '%n %s %Y' {} + | sort) > "$work/bundle-after.txt"
check "nothing written in the working directory" diff "$work/bundle-before.txt" "$work/bundle-after.txt"
entry=$(ls -d "$XDG_CACHE_HOME"/mospec/*/ | head -1)
entry=${entry%/}
check "the cache root is private (0700)" test "$(stat -c %a "$XDG_CACHE_HOME/mospec")" = 700
check "the entry is private (0700)" test "$(stat -c %a "$entry")" = 700
check "the entry's manifest records the library's SHA-256" \
  grep -q "^sha256 $(sha256sum "$entry/build/libmospec_controller.so" | cut -c1-64)\$" "$entry/manifest"

expect "a second run reuses the entry" 0 "" -- "$mospec" run models/sc0a --sim --duration 0.05
check "reused, not built again" bash -c "! grep -q 'generated and built' '$work/stderr.txt'"

# The library in the real entry replaced: detected before loading, rebuilt.
rm "$entry/build/libmospec_controller.so"
cp "$work/evil.so" "$entry/build/libmospec_controller.so"
expect "a tampered library is built again" 0 \
  "the cached controller in $entry was not used: its library's SHA-256 [0-9a-f]{64} is not the [0-9a-f]{64} recorded when it was built; built it again" -- \
  "$mospec" run models/sc0a --sim --duration 0.05
check "the tampered library was not loaded" test ! -e "$markers/loaded"
check "the rebuilt library matches its manifest" \
  grep -q "^sha256 $(sha256sum "$entry/build/libmospec_controller.so" | cut -c1-64)\$" "$entry/manifest"

# A cache others can write into: refused before anything in it is used.
chmod 0777 "$XDG_CACHE_HOME/mospec"
expect "a world-writable cache root is refused" 2 \
  "^mospec: error: refusing the controller cache directory '$XDG_CACHE_HOME/mospec': other users can write into it; make it private with \`chmod go-w '$XDG_CACHE_HOME/mospec'\`" -- \
  "$mospec" run models/sc0a --sim --duration 0.05
chmod 0700 "$XDG_CACHE_HOME/mospec"
chmod 0775 "$entry"
expect "a group-writable entry is refused" 2 "refusing the controller cache directory '$entry': other users can write" -- \
  "$mospec" run models/sc0a --sim --duration 0.05
chmod 0700 "$entry"
mkdir -m 0777 "$work/shared-cache"
expect "--cache DIR has the same checks" 2 "refusing the controller cache directory '$work/shared-cache'" -- \
  "$mospec" run models/sc0a --sim --duration 0.05 --cache "$work/shared-cache"

# Where the cache is: a relative XDG_CACHE_HOME is ignored (the refusal of a
# planted, world-writable HOME cache shows which directory was chosen).
mkdir -p "$work/home/.cache/mospec"
chmod 0777 "$work/home/.cache/mospec"
expect "a relative XDG_CACHE_HOME is ignored" 2 "refusing the controller cache directory '$work/home/.cache/mospec'" -- \
  env XDG_CACHE_HOME=relative HOME="$work/home" "$mospec" run models/sc0a --sim --duration 0.05
check "nothing made for the relative path" test ! -e "$bundle/relative"
expect "no HOME and no XDG_CACHE_HOME: asks for --cache" 2 \
  "^mospec: error: no cache directory for generated controllers: .*--cache DIR" -- \
  env -u XDG_CACHE_HOME -u HOME "$mospec" run models/sc0a --sim --duration 0.05
expect "--interpret needs no cache" 0 "" -- \
  env -u XDG_CACHE_HOME -u HOME "$mospec" run models/sc0a --sim --interpret --duration 0.05

# A --cache path CMake could not quote: refused.
expect "a cache path with a line break is refused" 2 "the controller cache directory '.*\\\\x0Ab' holds the control character 0x0A" -- \
  "$mospec" run models/sc0a --sim --duration 0.05 --cache "$work/a
b"
check "the planted library was never loaded" test ! -e "$markers/loaded"

finish codegen-cache-cli
