#!/usr/bin/env bash
# models/examples/contact-estimate: the end-effector wrench estimated from the
# measured joint torques (mos-jnt:EstimatedWrench, issue #16 item 4) on sc0a
# (the right arm pushes the table with 20 N along the platform's x). Its x
# force drives a "contact held" constraint (estimated f_x < -5 N: the table
# pushes back) watched by a level monitor and by an edge monitor whose falling
# edge is "contact lost". The estimate is compared with the contact force the
# simulator reports (right_fx), and interpreted and generated runs log the
# same bytes.
# Usage: contact_estimate_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the app's iri-map paths are relative to the repository root
app=models/examples/contact-estimate.json

validates_clean "$app"

expect "lowers" 0 "" -- "$mospec" ir "$app" -o "$work/ir.json"
check "the estimated wrench is a solver output" grep -q '"what": *"estimated-wrench"' "$work/ir.json"

expect "runs (interpreted)" 0 "" -- "$mospec" run "$app" --sim --interpret --duration 3 \
  --log "$work/run.csv" --summary "$work/run.json"

est=cstr-frc-rightarm-ee-estimated-held.value
# The largest |estimate - simulated contact force| from time T on.
worst() {
  awk -F, -v a="$est" -v b=right_fx -v t="$1" '
    NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $c["t"] + 1e-9 >= t { d = $c[a] - $c[b]; if (d < 0) d = -d; if (d > m) m = d }
    END { print m + 0 }' "$work/run.csv"
}
at() { csv_at "$work/run.csv" "$1" "$2"; }

check "the arm pushes with 20 N (the simulator's contact force)" \
  holds "$(at right_fx 1) < -19.9 && $(at right_fx 1) > -20.1"
check "the estimate follows the simulated contact force within 0.01 N from 0.2 s on" \
  holds "$(worst 0.2) < 0.01"
check "no contact is seen before the first command (flag 0 at the first tick)" \
  holds "$(at mon-contact.flag 0) == 0"
check "the contact is seen while the arm pushes (flag 1 at 1 s and 3 s)" \
  holds "$(at mon-contact.flag 1) == 1 && $(at mon-contact.flag 3) == 1"
check "the contact is never lost (no falling edge)" \
  holds "$(awk -F, 'NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next } $c["mon-contact-lost.event"] != 0 { n++ } END { print n + 0 }' "$work/run.csv") == 0"

expect "runs (generated)" 0 "" -- "$mospec" run "$app" --sim --duration 3 --log "$work/gen.csv" \
  --summary "$work/gen.json" --cache "$work/cache"
check "generated and interpreted logs are byte-identical" cmp -s "$work/run.csv" "$work/gen.csv"

finish contact-estimate
