#!/usr/bin/env bash
# diagnostic_shape.sh SRC_DIR: every diagnostic mospec prints has one of two
# shapes, `FILE:LINE:COL: severity: message` or `mospec: severity: message`,
# and only src/support/diagnostics.cpp (format()) builds them from a place.
# Fails (exit 1), printing file:line and the fix, when a file under SRC_DIR
#   1. writes a severity by hand: a string literal holding ": error: ",
#      ": warning: " or ": note: " (or starting with one) that is not the
#      "mospec: ..." shape — build a Diagnostic or throw mospec::Error instead;
#   2. builds a place by hand: ':' + std::to_string(...) — pass the line and
#      column to Error / located() and let format() write them;
#   3. starts an Error's message with a path (`Error(code, path + ": ...")`)
#      — pass the file, line and column as the Error's arguments.
# `diagnostic_shape.sh --selftest SRC_DIR` checks that planted cases are caught.
set -u
if [ "${1:-}" = "--selftest" ]; then
  src=${2:?usage: diagnostic_shape.sh --selftest SRC_DIR}
  tmp=$(mktemp -d) || exit 2
  trap 'rm -rf "$tmp"' EXIT
  cp -r "$src" "$tmp/src"
  "$0" "$tmp/src" > /dev/null || { echo "diagnostic_shape selftest: the tree itself fails"; exit 1; }
  status=0
  for plant in 'std::cerr << path << ": error: no such joint\n";' \
               'out += at + ": note: the shape that fired";' \
               'std::string where = file + '"':'"' + std::to_string(line);' \
               'throw Error("io", path + ": cannot read it");' \
               'throw Error("io",
                  log_path + ": no t column");'; do
    printf '%s\n' "$plant" > "$tmp/src/support/planted.cpp"
    if out=$("$0" "$tmp/src"); then
      echo "diagnostic_shape selftest: not caught: $plant"; status=1
    elif ! grep -q 'support/planted.cpp:1:' <<< "$out"; then
      echo "diagnostic_shape selftest: caught but not located: $out"; status=1
    fi
  done
  # The allowed shapes pass.
  printf '%s\n' 'std::cerr << "mospec: warning: the cache is stale\n";' \
                'throw Error("io", "cannot read " + path, path, line, column);' > "$tmp/src/support/planted.cpp"
  "$0" "$tmp/src" > /dev/null || { echo "diagnostic_shape selftest: an allowed shape was refused"; status=1; }
  [ $status = 0 ] && echo "diagnostic_shape selftest: ok"
  exit $status
fi

src=${1:?usage: diagnostic_shape.sh SRC_DIR}
find "$src" -name '*.cpp' -o -name '*.hpp' | sort | grep -v '/support/diagnostics\.cpp$' \
  | xargs perl -0777 -ne '
    my $text = $_;
    (my $code = $text) =~ s{//[^\n]*}{ "" }ge;  # comments say what they like
    my $line = sub { my $at = shift; (substr($code, 0, $at) =~ tr/\n//) + 1 };
    while ($code =~ /"((?:[^"\\\n]|\\.)*)"/g) {
      my ($s, $at) = ($1, $-[0]);
      next if $s =~ /^mospec: /;
      if ($s =~ /(^|: )(error|warning|note): /) {
        printf "%s:%d: error: a diagnostic written by hand (\"%s\"); build a Diagnostic or throw mospec::Error so that format() writes FILE:LINE:COL or mospec:\n", $ARGV, $line->($at), $s;
        $bad = 1;
      }
    }
    while ($code =~ /(?:\x27:\x27|":")\s*\+\s*std::to_string\(/g) {
      printf "%s:%d: error: a place written by hand (\x27:\x27 + std::to_string); pass the line and column to mospec::Error or located() and let format() write them\n", $ARGV, $line->($-[0]);
      $bad = 1;
    }
    while ($code =~ /\bError\(\s*[^,()]+(?:\([^()]*\))?,\s*(?:std::string\()?\w*(?:path|file|manifest)\w*(?:\.\w+\(\))*\)?\s*\+\s*"[:\s]/g) {
      printf "%s:%d: error: an Error whose message starts with a path; pass the file, line and column as its arguments instead\n", $ARGV, $line->($-[0]);
      $bad = 1;
    }
    END { exit($bad ? 1 : 0) }'
status=$?
[ $status = 0 ] && echo "diagnostic_shape: ok" || echo "diagnostic_shape: FAILED"
exit $status
