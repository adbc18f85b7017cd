#!/usr/bin/env bash
# Every run says what happened (issue #15 item 8): `mospec run` ends with a
# verdict on the console and in the summary ("verdict"), and exits 1 only when
# a goal of a motion was not met when it ended (#33 item 1), a limit was
# breached, a command was not finite or a `while` aborted a motion.
#   - sc0a for 31 s: its motion ends through its own timeout (an `until`) at
#     tick 30000, the end effector keeps its contact while it pushes: "ok",
#     exit 0;
#   - a copy whose angular-velocity gain is 1e4 (instead of 100): the arm is
#     destabilised, its torques are clamped, it loses the table and a joint
#     leaves its range: "FAILED: a limit was breached", exit 1 (run with
#     --run-diverging, past the loop check that refuses the gain);
#   - a copy whose elbow height reference is -1 m (below the floor,
#     unreachable): the elbow is driven down until a joint leaves its range,
#     exit 1; the reference's constraint is named as not met, against the
#     1 cm tolerance the model states;
#   - (#33 item 1) a copy whose elbow height reference is 2.7 cm above the
#     start, its PD 100 times softer and its tolerance not stated: the elbow
#     stays 2.7 cm off for the whole run, nothing else goes wrong; run for
#     3 s, the motion still runs and the goal is "not met yet" (exit 0); run
#     to its 30 s timeout, the goal is judged against the default tolerance
#     of a position (1 mm): FAILED, naming the constraint, its value, its
#     reference and the tolerance's source, exit 1 (this run said "ok"
#     before);
#   - (#33 item 3) sc1 with its shoulder-contact tubes narrowed to
#     [0.68, 0.701] m: the tubes are `while`s no controller acts on (the
#     distance setpoint's PD does), and its timeouts at 6 s: the verdict
#     watches the tubes while the motions run (left after holding) and judges
#     them when the motions end: not met, exit 1.
# Interpreted and generated controllers give the same verdict, console and
# summary. (The while-violated abort: tests/models/guards_test.sh.)
# Usage: verdict_test.sh MOSPEC SOURCE_DIR
SRC=$(realpath "$2")
source "$SRC/tests/support/cli_lib.sh"

# The console's verdict: from "mospec: verdict:" to the end.
verdict_lines() { sed -n '/^mospec: verdict:/,$p' "$1"; }
# A summary's verdict, printed as one value per line: PATH (a Python
# expression on the verdict object `v`).
field() { python3 -c 'import json, sys; v = json.load(open(sys.argv[1]))["verdict"]; print(eval(sys.argv[2]))' "$1" "$2"; }
same_verdict() {
  python3 -c '
import json, sys
sys.exit(json.load(open(sys.argv[1]))["verdict"] != json.load(open(sys.argv[2]))["verdict"])' "$1" "$2"
}
eq() { test "$1" = "$2"; }

# --- sc0a: ended by its own timeout, contact kept: ok, exit 0 ----------------
cd "$SRC" || exit 1
expect "sc0a (interpreted): verdict ok, exit 0" 0 "^mospec: verdict: ok$" -- \
  "$mospec" run models/sc0a.json --sim --interpret --duration 31 --summary "$work/ok.json" \
  --log "$work/ok.csv"
verdict_lines "$work/stderr.txt" > "$work/ok.txt"
check "sc0a: the motion ran from tick 0 and ended through its timeout at tick 30000" \
  grep -q '^  motion motion-rightarm: ticks 0 to 30000 (0 s to 30 s), ended by its `until` cstr-time-sc0a-timeout (a timeout)$' "$work/ok.txt"
check "sc0a: the console lists the events" \
  grep -q '^  events: 2: motion-rightarm.ended until at tick 30000; mon-sc0a-timeout.event rising at tick 30000$' "$work/ok.txt"
check "sc0a: no limit breached, nothing non-finite, no degraded solve" \
  grep -Pzq '  limits: none breached\n  non-finite commands: none\n  degraded solves: none\n' "$work/ok.txt"
check "sc0a: the right arm kept its contact while it pushed (30000 ticks)" \
  grep -q '^  contact: right arm kept it while pushing (30000 ticks); left arm pushed nothing$' "$work/ok.txt"
check "sc0a: a peak torque ratio per arm" \
  grep -Eq '^  peak torque ratio \|tau\|/limit: right arm 0\.[0-9]+ \(tick [0-9]+\), left arm 0\.[0-9]+ \(tick [0-9]+\)$' "$work/ok.txt"
check "sc0a summary: status ok, exit status 0" eq "$(field "$work/ok.json" 'v["status"], v["exit_status"]')" "('ok', 0)"
check "sc0a summary: ended by its until, the timeout constraint named" \
  eq "$(field "$work/ok.json" '[(m["ended_by"], m["ended_tick"], [(g["constraint"], g["timeout"]) for g in m["guards"]]) for m in v["motions"]]')" \
  "[('until', 30000, [('https://mospec.example/models/cstr-time-sc0a-timeout', True)])]"
check "sc0a summary: each constraint's final error and whether it is met" \
  eq "$(field "$work/ok.json" '[(c["name"], c["relation"], c["guard"], c["goal"], c["satisfied"], c["judged"], c["final_error"] is not None) for c in v["constraints"] if c["name"] in ("cstr-time-sc0a-timeout", "cstr-pos-rightarm-elbow-height", "cstr-frc-rightarm-ee-contact")]')" \
  "[('cstr-time-sc0a-timeout', 'greater-than', True, False, True, True, True), ('cstr-frc-rightarm-ee-contact', 'assignment', False, False, True, True, False), ('cstr-pos-rightarm-elbow-height', 'equality', False, True, True, True, True)]"
check "sc0a: its six goals judged when the motion ended, all met" \
  grep -q '^  goals of motion-rightarm when it ended (tick 30000): 6 of 6 met$' "$work/ok.txt"
check "sc0a: its whiles watched while it ran (the wrist's velocities leave 0 in the first ticks' contact)" \
  grep -Eq '^  whiles of motion-rightarm while it ran: 3 of 6 held throughout; LEFT after holding: cstr-angvel-rightarm-ee-x 1 time from tick [0-9]+ \([0-9]+ ticks in all\)' "$work/ok.txt"
check "sc0a summary: each goal, its tolerance and where it comes from" \
  eq "$(field "$work/ok.json" '[(g["name"], g["while"], g["judged_at"], g["tick"], g["met"], g["tolerance"], g["tolerance_source"], g["unit"]) for g in v["goals"]]')" \
  "[('cstr-angvel-rightarm-ee-x', True, 'motion-end', 30000, True, 0.05, 'default', 'RAD-PER-SEC'), ('cstr-angvel-rightarm-ee-y', True, 'motion-end', 30000, True, 0.05, 'default', 'RAD-PER-SEC'), ('cstr-angvel-rightarm-ee-z', True, 'motion-end', 30000, True, 0.05, 'default', 'RAD-PER-SEC'), ('cstr-linvel-rightarm-ee-lateral', True, 'motion-end', 30000, True, 0.01, 'default', 'M-PER-SEC'), ('cstr-linvel-rightarm-ee-vertical', True, 'motion-end', 30000, True, 0.01, 'default', 'M-PER-SEC'), ('cstr-pos-rightarm-elbow-height', True, 'motion-end', 30000, True, 0.01, 'stated', 'M')]"
check "sc0a summary: the contact record" \
  eq "$(field "$work/ok.json" 'v["contact"]["right"]["losses"], v["contact"]["right"]["commanded_ticks"], v["contact"]["right"]["forces"]')" \
  "(0, 30000, ['https://mospec.example/models/spec-frc-rightarm-ee-contact'])"
check "sc0a summary: no breach" eq "$(field "$work/ok.json" 'v["limit_breaches"], v["non_finite_commands"]["ticks"]')" "([], 0)"

expect "sc0a (generated): verdict ok, exit 0" 0 "^mospec: verdict: ok$" -- \
  "$mospec" run models/sc0a.json --sim --duration 31 --summary "$work/ok-gen.json" \
  --cache "$work/cache"
check "sc0a: generated and interpreted print the same verdict" \
  cmp -s "$work/ok.txt" <(verdict_lines "$work/stderr.txt")
check "sc0a: generated and interpreted summaries hold the same verdict" \
  same_verdict "$work/ok.json" "$work/ok-gen.json"

# --- a destabilising gain: limits breached, exit 1 ---------------------------
tree="$work/tree"
mkdir -p "$tree"
cp -r "$SRC/models" "$SRC/robots" "$SRC/metamodels" "$tree/"
cd "$tree" || exit 1
# The first angular-velocity PID (proportional-gain 100.0) at 1e4.
sed -i '0,/"proportional-gain": "100.0"/s//"proportional-gain": "1e4"/' \
  models/right-arm/05-constraint-handler.json
check "the copy has the high gain" grep -q '"proportional-gain": "1e4"' \
  models/right-arm/05-constraint-handler.json
expect "a gain of 1e4 (interpreted): limits breached, exit 1" 1 \
  "^mospec: verdict: FAILED: .*a limit was breached: commands clamped from tick [0-9]+; a joint beyond its limits from tick [0-9]+$" -- \
  "$mospec" run models/sc0a.json --sim --interpret --run-diverging --duration 3 --summary "$work/gain.json"
verdict_lines "$work/stderr.txt" > "$work/gain.txt"
check "gain: the limits line names the clamped torques and the joint" \
  grep -Eq '^  limits: BREACHED: commands clamped from tick [0-9]+ \(right_arm\.tau\[[0-6]\], .*\); a joint beyond its limits from tick [0-9]+ \([0-9]+ ticks; furthest right_arm\.q\[[0-6]\], [0-9.e-]+ rad beyond\)$' "$work/gain.txt"
check "gain: the right arm's peak torque ratio is above 1" \
  grep -Eq '^  peak torque ratio \|tau\|/limit: right arm [1-9][0-9.e+]* \(tick [0-9]+\)' "$work/gain.txt"
check "gain: the end effector lost the table while it pushed" \
  grep -Eq '^  contact: right arm lost it [0-9]+ times? while pushing \(first at tick [0-9]+, ' "$work/gain.txt"
check "gain summary: failed, exit status 1, torques and a joint breached" \
  eq "$(field "$work/gain.json" 'v["status"], v["exit_status"], sorted(set(b["limit"].split("[")[0] for b in v["limit_breaches"])), v["peak_torque_ratio"]["right"]["ratio"] > 1, v["contact"]["right"]["losses"] > 0')" \
  "('failed', 1, ['joint position', 'right_arm.tau'], True, True)"
expect "a gain of 1e4 (generated): limits breached, exit 1" 1 "^mospec: verdict: FAILED: .*a limit was breached" -- \
  "$mospec" run models/sc0a.json --sim --run-diverging --duration 3 --summary "$work/gain-gen.json" --cache "$work/cache"
check "gain: generated and interpreted print the same verdict" \
  cmp -s "$work/gain.txt" <(verdict_lines "$work/stderr.txt")
check "gain: generated and interpreted summaries hold the same verdict" \
  same_verdict "$work/gain.json" "$work/gain-gen.json"

# --- an unreachable reference: a joint beyond its range, exit 1 --------------
rm -rf models && cp -r "$SRC/models" .
sed -i 's/"value": "0.4926"/"value": "-1.0"/' models/sc0a/00-misc.json
check "the copy has the unreachable elbow height" grep -q '"value": "-1.0"' models/sc0a/00-misc.json
expect "an elbow height of -1 m: the goal not met, a joint beyond its limits, exit 1" 1 \
  "^mospec: verdict: FAILED: the motion 'motion-rightarm' did not meet [0-9] of its goals: .*cstr-pos-rightarm-elbow-height.*; a limit was breached: a joint beyond its limits from tick [0-9]+$" -- \
  "$mospec" run models/sc0a.json --sim --interpret --duration 3 --summary "$work/reach.json"
check "reach: the elbow height is named with its value, reference, error and stated tolerance" \
  grep -Eq '^  goals of motion-rightarm when it ended \(tick [0-9]+\): [0-9] of 6 met; NOT MET: .*cstr-pos-rightarm-elbow-height = [0-9.e-]+ M \(wants = -1, error -1\.[0-9]+; tolerance 0\.01 M, stated\)$' "$work/stderr.txt"
check "reach summary: the joint breach and the elbow height's error" \
  eq "$(field "$work/reach.json" '[b["limit"] for b in v["limit_breaches"]], [round(c["final_error"]) for c in v["constraints"] if c["name"] == "cstr-pos-rightarm-elbow-height"]')" \
  "(['joint position'], [-1])"

# --- #33 item 1: a goal centimetres off, judged by the default tolerance -----
rm -rf models && cp -r "$SRC/models" .
sed -i 's/"value": "0.4926"/"value": "0.52"/' models/sc0a/00-misc.json
sed -i 's/"proportional-gain": "200.0"/"proportional-gain": "2.0"/; s/"derivative-gain": "30.0"/"derivative-gain": "3.0"/' \
  models/right-arm/05-constraint-handler.json
python3 - models/right-arm/03-constraints.json <<'PY'
import re, sys
s = open(sys.argv[1]).read()
open(sys.argv[1], "w").write(re.sub(r',\s*"tolerance": "pos-rightarm-elbow-height-tolerance"', "", s))
PY
check "the copy: elbow reference 0.52 m, a soft PD, no stated tolerance" \
  eq "$(grep -c '"value": "0.52"\|"proportional-gain": "2.0"\|elbow-height-tolerance"$' models/sc0a/00-misc.json models/right-arm/05-constraint-handler.json models/right-arm/03-constraints.json | cut -d: -f2 | tr '\n' ' ')" "1 1 0 "
expect "an elbow 2.7 cm off for 3 s: the motion still runs, its goal not met yet, exit 0, not a plain ok" 0 \
  "^mospec: verdict: ok so far: 1 goal\\(s\\) not met yet, as motion-rightarm was still running when the run ended \\(run longer to judge them\\)$" -- "$mospec" run models/sc0a.json --sim --interpret --duration 3
check "off, 3 s: the goal is listed as not met yet" \
  grep -Eq '^  goals of motion-rightarm at the run.s end \(tick 2999; still running, judged when it ends\): 5 of 6 met; not met yet: cstr-pos-rightarm-elbow-height = 0\.49[0-9]* M \(wants = 0\.52, error 0\.02[0-9]*; tolerance 0\.001 M, the default for M\)$' "$work/stderr.txt"
expect "an elbow 2.7 cm off to the motion's end (interpreted): the goal not met by the default tolerance, exit 1" 1 \
  "^mospec: verdict: FAILED: the motion 'motion-rightarm' did not meet 1 of its goals: cstr-pos-rightarm-elbow-height$" -- \
  "$mospec" run models/sc0a.json --sim --interpret --duration 31 --summary "$work/off.json"
verdict_lines "$work/stderr.txt" > "$work/off.txt"
check "off: the console names value, reference, error, tolerance and its source" \
  grep -Eq '^  goals of motion-rightarm when it ended \(tick 30000\): 5 of 6 met; NOT MET: cstr-pos-rightarm-elbow-height = 0\.49[0-9]* M \(wants = 0\.52, error 0\.02[0-9]*; tolerance 0\.001 M, the default for M\)$' "$work/off.txt"
check "off: the elbow never held while the motion ran" \
  grep -Eq '^  whiles of motion-rightarm while it ran: .*never held: cstr-pos-rightarm-elbow-height in 30000 ticks$' "$work/off.txt"
check "off: nothing else went wrong" \
  grep -Pzq '  limits: none breached\n  non-finite commands: none\n' "$work/off.txt"
check "off summary: the goal, its value, reference, tolerance and source" \
  eq "$(field "$work/off.json" '[(g["met"], round(g["value"], 2), g["reference"], g["tolerance"], g["tolerance_source"], g["judged_at"]) for g in v["goals"] if g["name"] == "cstr-pos-rightarm-elbow-height"], v["status"]')" \
  "([(False, 0.49, 0.52, 0.001, 'default', 'motion-end')], 'failed')"
expect "an elbow 2.7 cm off (generated): the same verdict" 1 "^mospec: verdict: FAILED: the motion 'motion-rightarm'" -- \
  "$mospec" run models/sc0a.json --sim --duration 31 --summary "$work/off-gen.json" --cache "$work/cache"
check "off: generated and interpreted print the same verdict" \
  cmp -s "$work/off.txt" <(verdict_lines "$work/stderr.txt")
check "off: generated and interpreted summaries hold the same verdict" \
  same_verdict "$work/off.json" "$work/off-gen.json"

# --- #33 item 3: a `while` no controller acts on, watched and judged ---------
rm -rf models && cp -r "$SRC/models" .
sed -i 's/"value": "0.72"/"value": "0.701"/; s/"value": "60.0"/"value": "6.0"/' models/sc1/00-misc.json
check "the copy: both tubes' upper bounds at 0.701 m, the timeouts at 6 s" \
  eq "$(grep -c '"value": "0.701"\|"value": "6.0"' models/sc1/00-misc.json)" 3
expect "sc1, tubes narrowed to [0.68, 0.701]: the tubes not met, exit 1" 1 \
  "^mospec: verdict: FAILED: the motion 'motion-sc1-leftarm' did not meet 1 of its goals: cstr-dist-leftarm-shoulder-ee; the motion 'motion-sc1-rightarm' did not meet 1 of its goals: cstr-dist-rightarm-shoulder-ee$" -- \
  "$mospec" run models/sc1.json --sim --interpret --duration 6.5 --summary "$work/tube.json"
check "tube: the right tube is named as a while no controller acts on, left after holding" \
  grep -Eq '^  whiles of motion-sc1-rightarm while it ran: .*LEFT after holding: .*cstr-dist-rightarm-shoulder-ee \(no controller acts on it\) [0-9]+ times? from tick [0-9]+ \([0-9]+ ticks in all\)' "$work/stderr.txt"
check "tube: not met, with the band and the default tolerance" \
  grep -Eq '^  goals of motion-sc1-rightarm when it ended \(tick 6000\): 7 of 8 met; NOT MET: cstr-dist-rightarm-shoulder-ee = 0\.70[0-9]* M \(wants in \[0\.68, 0\.701\], error -0\.00[0-9]*; tolerance 0\.001 M, the default for M\)$' "$work/stderr.txt"
check "tube summary: the tube, a while not acted on, its lapses counted" \
  eq "$(field "$work/tube.json" '[(g["while"], g["acted_on"], g["met"], g["reference"], g["lapses"] > 0, g["running_ticks"]) for g in v["goals"] if g["name"] == "cstr-dist-rightarm-shoulder-ee"]')" \
  "[(True, False, False, [0.68, 0.701], True, 6000)]"
cd "$SRC" || exit 1

finish verdict
