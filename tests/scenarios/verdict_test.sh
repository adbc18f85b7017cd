#!/usr/bin/env bash
# Every run says what happened (issue #15 item 8): `mospec run` ends with a
# verdict on the console and in the summary ("verdict"), and exits 1 only when
# a limit was breached, a command was not finite or a `while` aborted a motion.
#   - sc0a for 31 s: its motion ends through its own timeout (an `until`) at
#     tick 30000, the end effector keeps its contact while it pushes: "ok",
#     exit 0;
#   - a copy whose angular-velocity gain is 1e4 (instead of 100): the arm is
#     destabilised, its torques are clamped, it loses the table and a joint
#     leaves its range: "FAILED: a limit was breached", exit 1;
#   - a copy whose elbow height reference is -1 m (below the floor,
#     unreachable): the elbow is driven down until a joint leaves its range,
#     exit 1; the reference's constraint is named as not met.
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
  eq "$(field "$work/ok.json" '[(c["name"], c["relation"], c["guard"], c["satisfied"], c["judged"], c["final_error"] is not None) for c in v["constraints"] if c["name"] in ("cstr-time-sc0a-timeout", "cstr-pos-rightarm-elbow-height", "cstr-frc-rightarm-ee-contact")]')" \
  "[('cstr-time-sc0a-timeout', 'greater-than', True, True, True, True), ('cstr-frc-rightarm-ee-contact', 'assignment', False, True, True, False), ('cstr-pos-rightarm-elbow-height', 'equality', False, False, False, True)]"
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
  "^mospec: verdict: FAILED: a limit was breached: commands clamped from tick [0-9]+; a joint beyond its limits from tick [0-9]+$" -- \
  "$mospec" run models/sc0a.json --sim --interpret --duration 3 --summary "$work/gain.json"
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
expect "a gain of 1e4 (generated): limits breached, exit 1" 1 "^mospec: verdict: FAILED: a limit was breached" -- \
  "$mospec" run models/sc0a.json --sim --duration 3 --summary "$work/gain-gen.json" --cache "$work/cache"
check "gain: generated and interpreted print the same verdict" \
  cmp -s "$work/gain.txt" <(verdict_lines "$work/stderr.txt")
check "gain: generated and interpreted summaries hold the same verdict" \
  same_verdict "$work/gain.json" "$work/gain-gen.json"

# --- an unreachable reference: a joint beyond its range, exit 1 --------------
rm -rf models && cp -r "$SRC/models" .
sed -i 's/"value": "0.4926"/"value": "-1.0"/' models/sc0a/00-misc.json
check "the copy has the unreachable elbow height" grep -q '"value": "-1.0"' models/sc0a/00-misc.json
expect "an elbow height of -1 m: a joint beyond its limits, exit 1" 1 \
  "^mospec: verdict: FAILED: a limit was breached: a joint beyond its limits from tick [0-9]+$" -- \
  "$mospec" run models/sc0a.json --sim --interpret --duration 3 --summary "$work/reach.json"
check "reach: the elbow height (an equality without a tolerance) is named with its error" \
  grep -Eq '^  equalities without a tolerance \(final error, not judged\): .*cstr-pos-rightarm-elbow-height -1\.[0-9]+' "$work/stderr.txt"
check "reach summary: the joint breach and the elbow height's error" \
  eq "$(field "$work/reach.json" '[b["limit"] for b in v["limit_breaches"]], [round(c["final_error"]) for c in v["constraints"] if c["name"] == "cstr-pos-rightarm-elbow-height"]')" \
  "(['joint position'], [-1])"
cd "$SRC" || exit 1

finish verdict
