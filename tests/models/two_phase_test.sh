#!/usr/bin/env bash
# models/examples/two-phase: one arm pushes with 20 N for 5 s, then with 10 N,
# as two guarded motions (phase 1 ends, and phase 2 starts, when the clock
# passes 5 s) whose handlers share the arm's six PID controllers and their
# evaluators. A controller listed by several motions' handlers is active while
# any of them runs (an `any-of` step gates it): the shared controllers run
# through the switch without being reset, and the measured contact force is
# the one each phase asks for. Interpreted and generated runs log the same bytes.
# Measured (10 s run): |f - 20 N| <= 0.0013 N over [1 s, 5 s), |f - 10 N| <=
# 0.00023 N over [5.5 s, 10 s]; the test allows 0.01 N.
# Usage: two_phase_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the app's iri-map paths are relative to the repository root
app=models/examples/two-phase.json

validates_clean "$app"

# Each of the six shared controllers is gated by one any-of step.
expect "lowers" 0 "" -- "$mospec" ir "$app" -o "$work/ir.json"
any_of=$(grep -c '"kind": *"any-of"' "$work/ir.json")
check "six any-of steps, one per shared controller (got $any_of)" test "$any_of" -eq 6

expect "runs (interpreted)" 0 "" -- "$mospec" run "$app" --sim --interpret --duration 10 \
  --log "$work/run.csv" --summary "$work/run.json"
check "no instability" grep -q '"instabilities": 0' "$work/run.json"

# Columns by name; prints what the awk program computes.
measure() {
  awk -F, -v prog="$1" '
    NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { t = $c["t"]; f = $c["right_fn"]; p1 = $c["motion-rightarm-phase1.running"];
      p2 = $c["motion-rightarm-phase2.running"]; u = $c["ctrl-angvel-rightarm-ee-y.output"] }
    prog == "phase1" && t >= 1 && t < 4.99 { d = f - 20; if (d < 0) d = -d; if (d > m) m = d
                                             if (p1 != 1 || p2 != 0) bad = 1 }
    prog == "phase2" && t >= 5.5 { d = f - 10; if (d < 0) d = -d; if (d > m) m = d
                                   if (p1 != 0 || p2 != 1) bad = 1 }
    prog == "switch" && p2 == 1 && !s { s = t; before = prev_u; after = u }
    { prev_u = u }
    END { if (prog == "switch") print s, before, after; else print (bad ? "wrong-phase" : m) }
  ' "$work/run.csv"
}
within() { awk -v x="$1" -v lo="$2" -v hi="$3" 'BEGIN{exit !(x>=lo && x<=hi)}'; }

p1=$(measure phase1)
check "phase 1 runs alone and the contact force is 20 N within 0.01 N over [1 s, 5 s) (max deviation $p1)" \
  within "$p1" 0 0.01
p2=$(measure phase2)
check "phase 2 runs alone and the contact force is 10 N within 0.01 N over [5.5 s, 10 s] (max deviation $p2)" \
  within "$p2" 0 0.01
read -r switch before after <<< "$(measure switch)"
check "phase 2 starts when the clock passes 5 s (at t = $switch)" within "$switch" 4.99 5.01
# A controller gated by phase 1 alone would stop (output 0, integral reset) at
# the switch; a shared one carries on.
check "a shared controller is not reset at the switch ($before -> $after)" \
  awk -v a="$before" -v b="$after" 'BEGIN{d=a-b; if(d<0)d=-d; exit !(a!=0 && b!=0 && d<1)}'

# Monitors report for the motions whose handlers list them, the tick a motion
# ends included; one no handler lists watches the whole run. Every tick logged
# (--log-every 1), so the one-tick flag of phase 1's monitor is in the log.
# All three watch "the clock passed 5 s", phase 1's post-condition.
expect "runs 6 s, every tick logged" 0 "" -- "$mospec" run "$app" --sim --interpret --duration 6 \
  --log-every 1 --log "$work/ticks.csv"
monitors() {
  awk -F, '
    NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { p1 = $c["motion-rightarm-phase1.running"]; whole = $c["mon-past-switch.flag"]
      listed = $c["mon-phase1-past-switch.flag"]; e = $c["mon-phase-switch.event"] }
    p1 == 0 && was_p1 == 1 { end = $c["t"] }
    whole == 1 && !first_whole { first_whole = $c["t"] }
    whole == 1 { n_whole++ }
    listed == 1 { n_listed++; t_listed = $c["t"] }
    e == 1 { n_events++; t_event = $c["t"] }
    { was_p1 = p1 }
    END { print end, first_whole, n_whole + 0, n_listed + 0, t_listed, n_events + 0, t_event }
  ' "$work/ticks.csv"
}
read -r end first_whole n_whole n_listed t_listed n_events t_event <<< "$(monitors)"
check "phase 1 ends at 5 s (tick at t = $end)" within "$end" 4.99 5.01
check "the unlisted monitor's flag rises when the clock passes 5 s and stays up ($first_whole, $n_whole rows)" \
  test "$first_whole" = "$end" -a "$n_whole" -ge 990
check "phase 1's monitor raises its flag only in the tick phase 1 ends ($n_listed rows, at $t_listed)" \
  test "$n_listed" -eq 1 -a "$t_listed" = "$end"
check "phase 1's edge monitor emits its one event in that tick ($n_events, at $t_event)" \
  test "$n_events" -eq 1 -a "$t_event" = "$end"

# The generated controller does exactly what the interpreter does.
expect "runs (generated)" 0 "" -- "$mospec" run "$app" --sim --duration 10 --log "$work/gen.csv" \
  --cache "$work/cache"
check "generated and interpreted logs are byte-identical" cmp -s "$work/run.csv" "$work/gen.csv"

finish two_phase
