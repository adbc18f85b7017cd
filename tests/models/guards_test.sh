#!/usr/bin/env bash
# models/examples/guards: issue #15's guards and monitors in simulation, the
# two-phase task (one arm pushes with 20 N, then 10 N) with
#   - phase 1's `until` and phase 2's `when` an EQUALITY on the clock's time,
#     t = 3.003 s with a tolerance (mos-grd:tolerance) of 0.4 ms: satisfied at
#     tick 3003 alone, it ends phase 1 and starts phase 2 there;
#   - phase 2's `while` the per-condition t <= 6.0055 s: it holds when phase 2
#     starts and is violated at tick 6006, which aborts phase 2
#     (`.ended` = 2, while-violated);
#   - monitors: a rising-edge (default) and a level monitor on the equality
#     (one tick each), and a FALLING-edge monitor (mos-grd:edge) on the
#     per-condition's error (fires at tick 6006).
# The log keeps every 10th tick (the default): none of those ticks is kept,
# so each signal must be latched into the next logged row (tick 3010, 6010),
# and the summary lists every event with its tick. The abort fails the run:
# exit 1, and the verdict (console and summary) names the motion, its tick and
# the violated `while`, and the `until` that ended phase 1. Interpreted and
# generated runs log the same bytes, list the same events and give the same
# verdict.
# Usage: guards_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the app's iri-map paths are relative to the repository root
app=models/examples/guards.json

validates_clean "$app"

expect "lowers" 0 "" -- "$mospec" ir "$app" -o "$work/ir.json"
check "phase 2 checks one per-condition (its equalities without tolerance are enforced only)" \
  grep -Eq '"while": 1' "$work/ir.json"
check "the deadline monitor reports falling edges" grep -q '"edges": "falling"' "$work/ir.json"
check "the equality guard carries its tolerance" grep -Eq '"tolerance": 0.0004,?$' "$work/ir.json"

expect "runs (interpreted); the aborted motion fails the run" 1 \
  "^mospec: verdict: FAILED: the motion 'motion-rightarm-phase2' was aborted at tick 6006: its \`while\` cstr-time-deadline was violated$" -- \
  "$mospec" run "$app" --sim --interpret --duration 8 --log "$work/run.csv" --summary "$work/run.json"
# The verdict's lines on the console (the lines after "mospec: verdict:").
verdict_lines() { sed -n '/^mospec: verdict:/,$p' "$1"; }
verdict_lines "$work/stderr.txt" > "$work/verdict.txt"
check "the console's timeline: phase 1 ended by its until at tick 3003" \
  grep -q '^  motion motion-rightarm-phase1: ticks 0 to 3003 (0 s to 3.003 s), ended by its `until` cstr-time-phase-switch$' "$work/verdict.txt"
check "the console's timeline: phase 2 aborted at tick 6006" \
  grep -q '^  motion motion-rightarm-phase2: ticks 3003 to 6006 (3.003 s to 6.006 s), ABORTED: its `while` cstr-time-deadline was violated$' "$work/verdict.txt"
check "the console lists the four events" \
  grep -q '^  events: 4: motion-rightarm-phase1.ended until at tick 3003; mon-phase-switch.event rising at tick 3003; motion-rightarm-phase2.ended while-violated at tick 6006; mon-deadline.event falling at tick 6006$' "$work/verdict.txt"
check "no limit breached" grep -q '^  limits: none breached$' "$work/verdict.txt"
# The summary's verdict: status and each motion's ticks, how it ended and the guard's IRI.
timeline() {
  python3 -c '
import json, sys
v = json.load(open(sys.argv[1]))["verdict"]
print(v["status"], v["exit_status"])
for m in v["motions"]:
    print(m["name"], m["started_tick"], m["ended_tick"], m["ended_by"],
          " ".join(g["constraint"].rsplit("/", 1)[1] + (" timeout" if g["timeout"] else "") for g in m["guards"]))' "$1"
}
timeline "$work/run.json" > "$work/timeline.txt"
cat > "$work/expected-timeline.txt" <<'END'
failed 1
motion-rightarm-phase1 0 3003 until cstr-time-phase-switch
motion-rightarm-phase2 3003 6006 while-violated cstr-time-deadline
END
check "the summary's verdict: failed, with each motion's ticks, end and guard" \
  cmp -s "$work/timeline.txt" "$work/expected-timeline.txt"
if ! cmp -s "$work/timeline.txt" "$work/expected-timeline.txt"; then sed 's/^/  got: /' "$work/timeline.txt"; fi

# The value of column NAME in the first row with t >= T.
at() { csv_at "$work/run.csv" "$1" "$2"; }
# How many rows have NAME != 0.
rows() {
  awk -F, -v name="$1" 'NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next } $c[name] != 0 { n++ }
    END { print n + 0 }' "$work/run.csv"
}
eq() { test "$1" = "$2"; }

check "phase 1 runs until 3.003 s" eq "$(at motion-rightarm-phase1.running 3.0)" 1
check "phase 1 ended through its until (latched into the 3.010 s row)" \
  eq "$(at motion-rightarm-phase1.ended 3.004)" 1
check "phase 1's end is in one row" eq "$(rows motion-rightarm-phase1.ended)" 1
check "phase 2 runs from 3.003 s" eq "$(at motion-rightarm-phase2.running 3.004)" 1
check "the one-tick rising edge at 3.003 s is in the log" eq "$(at mon-phase-switch.event 3.004)" 1
check "the one-tick flag at 3.003 s is in the log" eq "$(at mon-phase-switch-level.flag 3.004)" 1
check "the flag is in one row" eq "$(rows mon-phase-switch-level.flag)" 1
check "phase 2 still runs at 6.005 s" eq "$(at motion-rightarm-phase2.running 6.0)" 1
check "phase 2 was aborted by its violated while (code 2, latched into the 6.010 s row)" \
  eq "$(at motion-rightarm-phase2.ended 6.0061)" 2
check "phase 2 no longer runs" eq "$(at motion-rightarm-phase2.running 6.0061)" 0
check "the falling edge at 6.006 s is in the log (code 2)" eq "$(at mon-deadline.event 6.0061)" 2
check "the deadline's falling edge is its only event" eq "$(rows mon-deadline.event)" 1

# The summary lists every event with its tick (in one tick, in column order:
# a motion's columns come before those of the monitors its handler lists,
# which report in the tick it ends).
events() {
  python3 -c '
import json, sys
for e in json.load(open(sys.argv[1]))["events"]:
    print(e["tick"], e["event"], e.get("reason", e.get("edge")))' "$1"
}
events "$work/run.json" > "$work/events.txt"
cat > "$work/expected.txt" <<'END'
3003 motion-rightarm-phase1.ended until
3003 mon-phase-switch.event rising
6006 motion-rightarm-phase2.ended while-violated
6006 mon-deadline.event falling
END
check "the summary lists the four events with their ticks" cmp -s "$work/events.txt" "$work/expected.txt"
if ! cmp -s "$work/events.txt" "$work/expected.txt"; then sed 's/^/  got: /' "$work/events.txt"; fi

# The generated controller does exactly what the interpreter does.
expect "runs (generated); the aborted motion fails the run" 1 "^mospec: verdict: FAILED: the motion 'motion-rightarm-phase2' was aborted" -- \
  "$mospec" run "$app" --sim --duration 8 --log "$work/gen.csv" --summary "$work/gen.json" \
  --cache "$work/cache"
check "generated and interpreted runs print the same verdict" \
  cmp -s "$work/verdict.txt" <(verdict_lines "$work/stderr.txt")
check "generated and interpreted summaries hold the same verdict" python3 -c '
import json, sys
sys.exit(json.load(open(sys.argv[1]))["verdict"] != json.load(open(sys.argv[2]))["verdict"])' \
  "$work/run.json" "$work/gen.json"
check "generated and interpreted logs are byte-identical" cmp -s "$work/run.csv" "$work/gen.csv"
events "$work/gen.json" > "$work/gen-events.txt"
check "generated and interpreted runs list the same events" cmp -s "$work/events.txt" "$work/gen-events.txt"

finish guards
