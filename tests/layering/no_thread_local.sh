#!/usr/bin/env bash
# no_thread_local.sh SRC_DIR: no per-thread state under SRC_DIR. A
# thread_local buffer or counter is hidden state: two evaluations on one
# thread share it and can interfere, and what a call depends on is not in its
# signature. State a call reuses (buffers, memos) or counts (work charged to a
# budget) belongs to an object the caller owns and passes in: a workspace
# (json::ParseScratch, sparql::PathWorkspace), a prepared value
# (rdf::IriBase) or the Budget that already flows through evaluation.
# Fails (exit 1), printing file:line and the fix, for every thread_local,
# __thread or _Thread_local in a source file.
# `no_thread_local.sh --selftest SRC_DIR` checks that planted cases are caught.
set -u
if [ "${1:-}" = "--selftest" ]; then
  src=${2:?usage: no_thread_local.sh --selftest SRC_DIR}
  tmp=$(mktemp -d) || exit 2
  trap 'rm -rf "$tmp"' EXIT
  cp -r "$src" "$tmp/src"
  "$0" "$tmp/src" > /dev/null || { echo "no_thread_local selftest: the tree itself fails"; exit 1; }
  status=0
  for plant in 'thread_local Scratch scratch;' \
               'static thread_local std::vector<int> pool;' \
               'static __thread int depth;' \
               'inline _Thread_local unsigned long searched = 0;'; do
    for ext in cpp hpp; do
      printf 'namespace x {\n%s\n}\n' "$plant" > "$tmp/src/sparql/planted.$ext"
      if out=$("$0" "$tmp/src"); then
        echo "no_thread_local selftest: not caught in .$ext: $plant"; status=1
      elif ! grep -q "sparql/planted.$ext:2:" <<< "$out"; then
        echo "no_thread_local selftest: caught but not located: $out"; status=1
      fi
      rm -f "$tmp/src/sparql/planted.$ext"
    done
  done
  # Words that merely contain it are not it.
  printf '%s\n' 'int my_thread_local_count = 0;' > "$tmp/src/sparql/planted.cpp"
  "$0" "$tmp/src" > /dev/null || { echo "no_thread_local selftest: a longer name was refused"; status=1; }
  [ $status = 0 ] && echo "no_thread_local selftest: ok"
  exit $status
fi

src=${1:?usage: no_thread_local.sh SRC_DIR}
[ -d "$src" ] || { echo "no_thread_local: no directory $src"; exit 2; }
hits=$(find "$src" \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' -o -name '*.inc' \) -print0 \
  | sort -z | xargs -0 -r grep -nwE 'thread_local|__thread|_Thread_local')
if [ -n "$hits" ]; then
  while IFS= read -r hit; do
    file=${hit%%:*}; rest=${hit#*:}; line=${rest%%:*}
    echo "$file:$line: error: per-thread state (${rest#*:}); it is hidden state two evaluations on one thread share: make it a workspace or member the caller owns and passes in (see tests/layering/no_thread_local.sh)"
  done <<< "$hits"
  echo "no_thread_local: FAILED"
  exit 1
fi
echo "no_thread_local: ok"
