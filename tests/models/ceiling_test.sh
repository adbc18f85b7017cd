#!/usr/bin/env bash
# models/examples/ceiling: a one-sided (less-than) constraint driving an
# acceleration constraint (issue #15 item 4). The right arm's end effector is
# lifted by a 2 N upward force; an upper limit z <= 0.40 m on it (from
# z = 0.35 m at rest) drives the tip's vertical acceleration through a PD
# controller. Below the limit the direction is free: the tip rises under the
# force alone (a row held at the controller's output, 0 while satisfied, would
# keep z at 0.35 m). At the limit the row engages and holds z there.
# Interpreted and generated runs log the same bytes.
# Usage: ceiling_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the app's iri-map paths are relative to the repository root
app=models/examples/ceiling.json

validates_clean "$app"

expect "lowers" 0 "" -- "$mospec" ir "$app" -o "$work/ir.json"
check "the vertical row is engaged by the limit's error (one-sided)" \
  grep -q '"engaged-by":' "$work/ir.json"

expect "runs (interpreted)" 0 "" -- "$mospec" run "$app" --sim --interpret --duration 3 \
  --log "$work/run.csv" --summary "$work/run.json"

z=cstr-pos-rightarm-ee-ceiling.value
# The value of column NAME in the first row with t >= T.
at() { csv_at "$work/run.csv" "$1" "$2"; }
# The largest value of column NAME.
peak() { csv_range "$work/run.csv" "$1" 0 | cut -d' ' -f2; }

check "the tip starts at 0.35 m" holds "$(at $z 0) < 0.351 && $(at $z 0) > 0.349"
check "below the limit z moves freely: it has risen 4 cm by 0.35 s" holds "$(at $z 0.35) > 0.39"
check "the limit is not passed by more than 1 cm" holds "$(peak $z) < 0.41"
check "the limit holds the tip at 0.40 m (within 0.1 mm at 2 s and 3 s)" \
  holds "$(at $z 2) > 0.3999 && $(at $z 2) < 0.4001 && $(at $z 3) > 0.3999 && $(at $z 3) < 0.4001"

expect "runs (generated)" 0 "" -- "$mospec" run "$app" --sim --duration 3 --log "$work/gen.csv" \
  --summary "$work/gen.json" --cache "$work/cache"
check "generated and interpreted logs are byte-identical" cmp -s "$work/run.csv" "$work/gen.csv"

finish ceiling
