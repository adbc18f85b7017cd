#!/usr/bin/env bash
# Commands beyond the robot's limits (issue #12): a copy of the project's
# models whose right-arm gain is 1e300 asks for ~1e300 N·m; a copy of sc1 whose
# distance gains are 1e9 asks the base for a platform force far beyond
# traction. The robot interface clamps both, `mospec run` says which actuator,
# from which tick, how much was asked and the limit, the summary records it
# and the run exits 1. The loop check refuses such gains before a run
# (tests/models/loop_sign_test.sh), so these runs pass --run-diverging, and the
# first checks that the refusal became a warning.
# Usage: clamp_test.sh MOSPEC SOURCE_DIR
SRC="$2"
source "$SRC/tests/support/cli_lib.sh"

tree="$work/tree"
mkdir -p "$tree"
cp -r "$SRC/models" "$SRC/robots" "$SRC/metamodels" "$tree/"
cd "$tree" || exit 1

# The right arm's first PID (proportional-gain 200.0) at 1e300.
sed -i '0,/"proportional-gain": "200.0"/s//"proportional-gain": "1e300"/' \
  models/right-arm/05-constraint-handler.json
check "the copy has the huge gain" grep -q '"proportional-gain": "1e300"' \
  models/right-arm/05-constraint-handler.json

expect "sc0a with a gain of 1e300: clamped, exit 1" 1 \
  "^mospec: warning: commands beyond the robot's limits were clamped at the robot interface" -- \
  "$mospec" run models/sc0a --sim --interpret --run-diverging --duration 0.5 --summary "$work/sc0a.json" \
  --log "$work/sc0a.csv"
check "the warning names a right-arm joint, its ticks, first tick, request and limit" \
  grep -Eq '^  right_arm\.tau\[[0-6]\]: clamped in [0-9]+ ticks? from tick [0-9]+, requested up to [0-9.]+e\+(29[0-9]|30[0-9]) N·m, limit (39|9) N·m$' \
  "$work/stderr.txt"
check "the loop check's refusal is a warning under --run-diverging" \
  grep -Eq "^models/right-arm/05-constraint-handler.json:[0-9]+:[0-9]+: warning: the loop of the controller '[^']*ctrl-pos-rightarm-elbow-height' on '[^']*' is unstable at the start" \
  "$work/stderr.txt"
check "the summary says the command was clamped" grep -q '"command_clamped": true' "$work/sc0a.json"
check "the summary lists the actuator with its limit" \
  grep -Eq '"actuator": "right_arm\.tau\[[0-6]\]"' "$work/sc0a.json"
# clamped_actuators: the summary's list, one "key": value per line.
clamped() { sed -n '/"clamped_actuators": \[/,/^  \]/p' "$1"; }
check "every clamped actuator has ticks, a limit, a unit and the huge request" \
  awk '
    /"ticks":/         { n++; if ($2 + 0 <= 0) bad = 1 }
    /"limit":/         { if ($2 + 0 != 9 && $2 + 0 != 39) bad = 1 }
    /"unit":/          { if ($0 !~ /"N·m"/) bad = 1 }
    /"max_requested":/ { if ($2 + 0 < 1e200) bad = 1 }
    END { exit (n > 0 && !bad) ? 0 : 1 }' <(clamped "$work/sc0a.json")
check "the log was still written" test -s "$work/sc0a.csv"

# The log's joint columns (issue #17 item 5): after the world's columns (whose
# positions stay), each arm's q, qd and tau; tau is the torque the actuator
# applied, i.e. the command after the clamp: never beyond the limit, and at it
# while the huge gain is clamped.
joints=""
for arm in right left; do
  for field in q qd tau; do
    for j in 0 1 2 3 4 5 6; do joints="$joints,${arm}_${field}$j"; done
  done
done
check "the log ends with tau_ratio, then the 42 joint columns"   grep -q "ground_fx,ground_fy,ground_mz,tau_ratio$joints\$" <(head -1 "$work/sc0a.csv")
# awk: the largest |right_tau<j>| over the run, and whether it sits at the limit.
right_tau() {
  awk -F, -v j="$1" 'NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { x = $c["right_tau" j]; if (x < 0) x = -x; if (x > m) m = x }
    END { printf "%.17g\n", m }' "$work/sc0a.csv"
}
check "no right-arm torque in the log is beyond its limit (39 or 9 N·m)"   awk -v a="$(right_tau 0)" -v b="$(right_tau 1)" -v c="$(right_tau 2)" -v d="$(right_tau 3)"   -v e="$(right_tau 4)" -v f="$(right_tau 5)" -v g="$(right_tau 6)"   'BEGIN { exit !(a <= 39 && b <= 39 && c <= 39 && d <= 39 && e <= 9 && f <= 9 && g <= 9) }'
check "some right-arm torque in the log is at its limit (clamped, then applied)"   awk -v a="$(right_tau 0)" -v b="$(right_tau 1)" -v c="$(right_tau 2)" -v d="$(right_tau 3)"   -v e="$(right_tau 4)" -v f="$(right_tau 5)" -v g="$(right_tau 6)"   'BEGIN { exit !(a == 39 || b == 39 || c == 39 || d == 39 || e == 9 || f == 9 || g == 9) }'
check "the first row's right_q are the world's initial pose (not all 0)"   awk -F, 'NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    NR==2 { for (j = 0; j < 7; j++) if ($c["right_q" j] != 0) n++; exit !(n > 0) }' "$work/sc0a.csv"

# The generated controller's commands go through the same robot interface.
expect "sc0a with a gain of 1e300, generated controller: clamped, exit 1" 1 \
  "^  right_arm\.tau\[[0-6]\]: clamped in [0-9]+ ticks? from tick [0-9]+" -- \
  "$mospec" run models/sc0a --sim --run-diverging --duration 0.5 --cache "$work/cache" \
  --summary "$work/sc0a-generated.json" --log "$work/sc0a-generated.csv"
check "generated: the same log, joint columns included, byte for byte" \
  cmp -s "$work/sc0a.csv" "$work/sc0a-generated.csv"
check "generated: the same clamps as interpreted" \
  cmp -s <(clamped "$work/sc0a.json") <(clamped "$work/sc0a-generated.json")
check "generated: the clamp list is not empty" grep -q '"actuator"' <(clamped "$work/sc0a-generated.json")

# sc1 with distance gains of 1e9: a platform force far beyond traction.
sed -i 's/"proportional-gain": "-600.0"/"proportional-gain": "-1e9"/' \
  models/sc1/05-distance-controller.json
expect "sc1 with a base force beyond the limit: clamped, exit 1" 1 \
  "^  platform\.force: clamped in [0-9]+ ticks? from tick [0-9]+, requested up to [0-9.e+]+ N, limit [0-9.]+ N$" -- \
  "$mospec" run models/sc1 --sim --interpret --run-diverging --duration 0.3 --summary "$work/sc1.json"
check "sc1: the hub torques are clamped too" grep -Eq '^  wheel_tau\[[0-7]\]: clamped' "$work/stderr.txt"
check "sc1: the verdict names the breach" \
  grep -Eq '^  limits: BREACHED: commands clamped from tick [0-9]+ \(.+\)$' "$work/stderr.txt"
check "sc1: the summary's verdict lists platform.force" \
  python3 -c 'import json, sys; v = json.load(open(sys.argv[1]))["verdict"]; sys.exit(not (v["status"] == "failed" and "platform.force" in [b["limit"] for b in v["limit_breaches"]]))' "$work/sc1.json"
check "sc1: the summary lists platform.force" grep -q '"actuator": "platform.force"' "$work/sc1.json"

finish scenarios-clamp
