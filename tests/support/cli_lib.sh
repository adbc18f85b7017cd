# Shared by the black-box CLI tests (sourced). Sets up:
#   mospec   absolute path of the binary under test ($1 of the test script)
#   work     a scratch directory, removed on exit
# and the checks below, which count into $passed / $failures; finish prints the
# closing "NAME: N passed, M failed" line and sets the exit status.
set -u
mospec=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passed=0

fail() { echo "FAIL $1"; failures=$((failures+1)); }

# expect NAME CODE PATTERN -- COMMAND...: exit code must be CODE and stderr must
# match the extended regex PATTERN (empty: anything); never a crash. The
# command's output is kept in $work/stdout.txt and $work/stderr.txt.
expect() {
  local name=$1 code=$2 pattern=$3
  shift 4
  "$@" > "$work/stdout.txt" 2> "$work/stderr.txt"
  local got=$?
  if [ "$got" -ne "$code" ]; then
    fail "$name: exit $got, expected $code"; sed 's/^/  stderr: /' "$work/stderr.txt" | head -20; return
  fi
  if [ -n "$pattern" ] && ! grep -Eq -- "$pattern" "$work/stderr.txt"; then
    fail "$name: stderr does not match /$pattern/"; sed 's/^/  stderr: /' "$work/stderr.txt" | head -20; return
  fi
  if grep -q -i -E 'terminate called|Segmentation|AddressSanitizer|runtime error|internal error' "$work/stderr.txt"; then
    fail "$name: crashed"; cat "$work/stderr.txt"; return
  fi
  # Every diagnostic has one of the two shapes (docs/architecture.md):
  # FILE:LINE:COL: severity: ..., or mospec: severity: ... with no place.
  # (A place written into a "mospec:" message is the first shape built by hand.)
  if grep -E '^[^[:space:]]+: (error|warning|note): ' "$work/stderr.txt" \
      | grep -v -E '^mospec: |^[^[:space:]]+:[0-9]+:[0-9]+: ' > "$work/shape.txt" ||
     grep -E '^mospec: (error|warning|note): [^[:space:]]+:[0-9]+(:[0-9]+)?: ' "$work/stderr.txt" \
      > "$work/shape.txt"; then
    fail "$name: a diagnostic of another shape"; sed 's/^/  /' "$work/shape.txt" | head -5; return
  fi
  passed=$((passed+1))
}

# check NAME COMMAND...: the command succeeds.
check() {
  local name=$1; shift
  if "$@"; then passed=$((passed+1)); else fail "$name"; fi
}

# stdout_has NAME PATTERN: the last command's stdout matches the extended regex.
stdout_has() {
  grep -Eq -- "$2" "$work/stdout.txt" || { fail "$1: stdout does not match /$2/"; sed 's/^/  stdout: /' "$work/stdout.txt" | head -20; }
}

# validates_clean APP: `mospec validate --strict APP` exits 0 with no finding at all.
validates_clean() {
  expect "validates with zero findings" 0 "" -- "$mospec" validate "$1" --strict
  stdout_has "validates with zero findings" '^shacl: 0 violations, 0 warnings, 0 infos'
}

# Reading a run's CSV log (header line, then rows; column "t" is the time):
# csv_at FILE NAME T    the value of column NAME in the first row with t >= T;
# csv_range FILE NAME T the smallest and largest value of NAME over the rows
#                       with t >= T, as "MIN MAX";
# csv_has FILE NAME     the header has a column NAME;
# holds EXPRESSION      awk's verdict on a numeric condition, e.g. holds "0.39 < 0.4".
csv_at() {
  awk -F, -v name="$2" -v t="$3" '
    NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $c["t"] + 1e-9 >= t { print $c[name]; exit }' "$1"
}
csv_range() {
  awk -F, -v name="$2" -v t="$3" '
    NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $c["t"] + 1e-9 >= t { v = $c[name] + 0; if (!n++ || v < lo) lo = v; if (n == 1 || v > hi) hi = v }
    END { printf "%.17g %.17g\n", lo, hi }' "$1"
}
# check_program SCRIPT ARGS...: runs the Python check SCRIPT of a lowered
# program (it imports ir_checks from this folder and prints one line per
# failed expectation) with ARGS; passes when it prints nothing. No bytecode
# is written: the source tree stays as it is.
check_program() {
  local script=$1; shift
  PYTHONDONTWRITEBYTECODE=1 PYTHONPATH="$(dirname "${BASH_SOURCE[0]}")" python3 "$script" "$@" > "$work/problems.txt" 2>&1
  check "the lowered program is the intended one ($(head -1 "$work/problems.txt"))" \
    test ! -s "$work/problems.txt"
  if [ -s "$work/problems.txt" ]; then sed 's/^/  /' "$work/problems.txt"; fi
}

csv_has() { head -1 "$1" | tr ',' '\n' | grep -qx -- "$2"; }
holds() { awk "BEGIN { exit !($1) }"; }

# finish SUITE: the closing summary line; exit status 0 only without failures.
finish() {
  echo "$1: $passed passed, $failures failed"
  [ "$failures" -eq 0 ]
}
