#!/usr/bin/env bash
# check_layers.sh SRC_DIR [LAYERS_FILE]: the include layering between the
# folders of SRC_DIR, as declared in LAYERS_FILE (default SRC_DIR/LAYERS; format
# and rule in src/LAYERS). Fails (exit 1) when
#   - the declaration names a folder that is not under SRC_DIR, declares a folder
#     twice, or has a malformed line;
#   - a folder under SRC_DIR has no line;
#   - the declared edges form a cycle;
#   - a file in SRC_DIR/Y/ has `#include "X/..."` (or <X/...>) for a folder X other than Y
#     that Y's line does not list (printed as file:line, the include and the rule),
#     or a CMakeLists.txt in SRC_DIR/Y/ links a library defined in such an X.
# Reads sources only: no build needed.
set -u
src=${1:?usage: check_layers.sh SRC_DIR [LAYERS_FILE]}
layers=${2:-$src/LAYERS}
[ -d "$src" ] || { echo "check_layers: $src: not a directory" >&2; exit 2; }
[ -f "$layers" ] || { echo "check_layers: $layers: no such file" >&2; exit 2; }

folders=$(cd "$src" && for d in */; do [ -d "$d" ] && echo "${d%/}"; done)

# Every #include "X/..." or <X/...> (a path with a folder part) in the sources,
# as "I<TAB>folder<TAB>path:line<TAB>X<TAB>the include line". Only X that are folders
# of SRC_DIR are checked (src/ is on the include path, so <ir/lower.hpp> works
# too); third-party paths such as <Eigen/Dense> are skipped.
includes=$(cd "$src" && grep -rnE --include='*.hpp' --include='*.cpp' --include='*.h' --include='*.hh' \
  --include='*.cc' --include='*.inc' --include='*.mustache' '^[[:space:]]*#[[:space:]]*include[[:space:]]*["<][^"<>/]+/' . |
  sed -E 's|^\./||' |
  awk '{
    split($0, a, ":"); path = a[1]; line = a[2]
    text = substr($0, length(path) + length(line) + 3)
    folder = path; sub(/\/.*/, "", folder)
    inc = text; sub(/^[^"<]*["<]/, "", inc); sub(/\/.*/, "", inc)
    sub(/^[[:space:]]+/, "", text)
    printf "I\t%s\t%s:%s\t%s\t%s\n", folder, path, line, inc, text
  }')

# The libraries each folder's CMakeLists.txt files define ("D<TAB>target<TAB>folder")
# and every mospec_* name they mention outside comments, i.e. what they link
# ("L<TAB>folder<TAB>path:line<TAB>target<TAB>the line"): a folder may link only
# the libraries of the folders it may include.
links=$(cd "$src" && find . -mindepth 2 -name CMakeLists.txt -exec awk '{
    path = FILENAME; sub(/^\.\//, "", path); folder = path; sub(/\/.*/, "", folder)
    text = $0; sub(/#.*/, "", text)
    if (match(text, /add_library\([[:space:]]*mospec_[a-z0-9_]+/)) {
      t = substr(text, RSTART, RLENGTH); sub(/^add_library\([[:space:]]*/, "", t)
      printf "D\t%s\t%s\n", t, folder
    }
    rest = text; shown = text; sub(/^[[:space:]]+/, "", shown)
    while (match(rest, /mospec_[a-z0-9_]+/)) {
      printf "L\t%s\t%s:%d\t%s\t%s\n", folder, path, FNR, substr(rest, RSTART, RLENGTH), shown
      rest = substr(rest, RSTART + RLENGTH)
    }
  }' {} +)

printf '%s\n%s\n' "$includes" "$links" | awk -v layers="$layers" -v src="$src" -v folders="$folders" '
BEGIN {
  bad = 0
  k = split(folders, ds, "\n")
  for (i = 1; i <= k; i++) if (ds[i] != "") { isdir[ds[i]] = 1; ndirs++; dirs[ndirs] = ds[i] }
  n = 0
  while ((getline raw < layers) > 0) {
    lineno++
    l = raw; sub(/#.*/, "", l); gsub(/^[[:space:]]+|[[:space:]]+$/, "", l)
    if (l == "") continue
    if (l !~ /^[A-Za-z0-9_.-]+:/) {
      printf "%s:%d: error: malformed line \"%s\" (expected \"folder: allowed folders...\")\n", layers, lineno, raw
      bad = 1; continue
    }
    f = l; sub(/:.*/, "", f); rest = l; sub(/^[^:]*:/, "", rest)
    if (f in declared) {
      printf "%s:%d: error: folder %s is declared twice (first on line %d)\n", layers, lineno, f, declared[f]
      bad = 1; continue
    }
    declared[f] = lineno; n++; order[n] = f
    if (!(f in isdir)) {
      printf "%s:%d: error: %s is declared but %s/%s is not a folder\n", layers, lineno, f, src, f; bad = 1
    }
    k = split(rest, deps, /[[:space:]]+/)
    for (i = 1; i <= k; i++) {
      if (deps[i] == "") continue
      if (deps[i] == f) continue
      allow[f, deps[i]] = 1; adj[f] = adj[f] " " deps[i]; depline[f, deps[i]] = lineno
      if (!(deps[i] in isdir)) {
        printf "%s:%d: error: %s lists %s, but %s/%s is not a folder\n", layers, lineno, f, deps[i], src, deps[i]
        bad = 1
      }
    }
  }
  for (i = 1; i <= ndirs; i++) if (!(dirs[i] in declared)) {
    printf "%s: error: folder %s/%s has no line; add \"%s: <the folders it may include>\"\n", layers, src, dirs[i], dirs[i]
    bad = 1
  }

  # Cycles: depth-first search, colour 1 = on the current path, 2 = done.
  for (i = 1; i <= n; i++) if (!(order[i] in colour)) visit(order[i], "")

  # The includes.
  nl = 0
  while ((getline row) > 0) {
    if (row == "") continue
    split(row, c, "\t")
    if (c[1] == "D") { libfolder[c[2]] = c[3]; continue }
    if (c[1] == "L") { nl++; lrow[nl] = row; continue }
    y = c[2]; x = c[4]; c[2] = c[3]; c[4] = c[5]
    if (!(x in isdir) || !(y in isdir)) continue  # not a src/ folder (e.g. <Eigen/Dense>)
    checked++
    if (x == y) continue
    used[y, x] = 1
    if ((y, x) in allow) continue
    printf "%s/%s: error: %s: src/%s may not include src/%s; the rule %s:%s lets %s include only %s\n", src, c[2],
      c[4], y, x, layers, (y in declared ? declared[y] : 0), y, (adj[y] != "" ? "itself," adj[y] : "itself")
    bad = 1
  }
  # The links.
  for (r = 1; r <= nl; r++) {
    split(lrow[r], c, "\t"); y = c[2]; lib = c[4]
    if (!(lib in libfolder) || !(y in isdir)) continue  # not a library of a src/ folder (mospec_warnings)
    x = libfolder[lib]; linked++
    if (x == y) continue
    used[y, x] = 1
    if ((y, x) in allow) continue
    printf "%s/%s: error: %s: src/%s may not link %s (src/%s); the rule %s:%s lets %s include only %s\n", src, c[3],
      c[5], y, lib, x, layers, (y in declared ? declared[y] : 0), y, (adj[y] != "" ? "itself," adj[y] : "itself")
    bad = 1
  }
  # Allowed but unused edges: not an error, a reminder to tighten the declaration.
  for (i = 1; i <= n; i++) {
    k = split(adj[order[i]], deps, " ")
    for (j = 1; j <= k; j++) if (deps[j] != "" && !((order[i], deps[j]) in used))
      printf "%s:%d: note: %s may include %s but does not\n", layers, depline[order[i], deps[j]], order[i], deps[j]
  }
  if (bad) { print "layering: FAILED"; exit 1 }
  printf "layering: OK (%d folders, %d includes and %d links checked)\n", n, checked, linked
  exit 0
}
function visit(v, path,    k, ds, j, w) {
  colour[v] = 1
  path = path " -> " v
  k = split(adj[v], ds, " ")
  for (j = 1; j <= k; j++) {
    w = ds[j]; if (w == "") continue
    if ((w in colour) && colour[w] == 1) {
      cyc = path " "; cyc = substr(cyc, index(cyc, " -> " w " ") + 4); sub(/ $/, "", cyc)
      printf "%s:%d: error: the layering has a cycle: %s -> %s\n", layers, depline[v, w], cyc, w
      bad = 1
    } else if (!(w in colour)) visit(w, path)
  }
  colour[v] = 2
}'
