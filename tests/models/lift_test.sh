#!/usr/bin/env bash
# models/examples/lift (issue #16 item 1, prismatic joints): a lift arm
# (robots/lift.jsonld, imported by `mospec import-urdf` from robots/lift.urdf:
# a vertical prismatic axis carrying two revolute joints), added to the robot
# by the world file's `arms`, holds its slide at 0.25 m (a JointPosition in M)
# by a PID whose output, a force in N, drives the slide through a joint-force
# driver. It validates; lowers to a prismatic joint and two revolute ones with
# the joint force on the slide; in simulation the slide rises from 0.15 m and
# holds 0.25 m within 1 mm, carrying the arm's weight (5 kg, 49.05 N), the
# generated controller's log is byte-identical to the interpreter's, and the
# reference is honoured, not a coincidence (at 0.30 m the slide ends there).
# Usage: lift_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the app's iri-map paths are relative to the repository root
app=models/examples/lift.json

expect "validates" 0 "" -- "$mospec" validate "$app"
stdout_has "validates with no finding" '^shacl: 0 violations, 0 warnings, 0 infos'

expect "lowers" 0 "" -- "$mospec" ir "$app" -o "$work/ir.json"
cat > "$work/check.py" <<'PY'
import json, sys
from ir_checks import want, single_arm, report
ir = json.load(open(sys.argv[1]))
arm = single_arm(ir)
segs = arm["segments"]
want([(s["joint"], s["type"]) for s in segs] ==
     [("lift", "prismatic"), ("shoulder", "revolute"), ("wrist", "revolute")],
     f"joints {[(s['joint'], s['type']) for s in segs]}")
want(segs[0]["axis"] == [0.0, 0.0, 1.0], f"slide axis {segs[0]['axis']}")
jf = arm["joint-forces"]
want(len(jf) == 1 and jf[0]["joint"] == 0, f"one joint force, on the slide: {jf}")
want(arm["X_RB"]["p"] == [0.1, 0.0, 0.0], f"mount {arm['X_RB']}")
data = {d["name"]: d for d in ir["data"]}
want(data["q_lift"]["unit"] == "M", f"q-lift in {data['q_lift'].get('unit')}")
want(data["frc_lift"]["unit"] == "N", f"frc-lift in {data['frc_lift'].get('unit')}")
want(data["frc_lift_measured"]["unit"] == "N", "the measured slide force in N")
report()
PY
check_program "$work/check.py" "$work/ir.json"

expect "runs (interpreted)" 0 "" -- "$mospec" run "$app" --sim --interpret --duration 4 \
  --log "$work/run.csv" --summary "$work/run.json"
check "the log has the lift arm's columns" csv_has "$work/run.csv" lift_q0
start=$(csv_at "$work/run.csv" lift_q0 0)
check "the slide starts at 0.15 m (got $start)" holds "$start == 0.15"
read -r lo hi <<< "$(csv_range "$work/run.csv" lift_q0 2.5)"
check "the slide holds 0.25 m within 1 mm from 2.5 s on (got $lo .. $hi)" \
  holds "$lo >= 0.249 && $hi <= 0.251"
read -r lo hi <<< "$(csv_range "$work/run.csv" lift_tau0 2.5)"
check "the slide carries the arm's weight, 49.05 N (got $lo .. $hi)" \
  holds "$lo >= 49.0 && $hi <= 49.1"
check "no torque limit exceeded" grep -q '"torque_limit_exceeded": false' "$work/run.json"
check "no joint limit exceeded" grep -q '"joint_limit_exceeded": false' "$work/run.json"

# The generated controller does exactly what the interpreter does.
expect "runs (generated)" 0 "" -- "$mospec" run "$app" --sim --duration 4 --log "$work/gen.csv" \
  --cache "$work/cache"
check "generated and interpreted logs are byte-identical" cmp -s "$work/run.csv" "$work/gen.csv"

# The reference is honoured, not a coincidence of the start.
mkdir -p "$work/tree" && cp -r models metamodels robots "$work/tree/"
sed -i 's/"value": "0.25"/"value": "0.30"/' "$work/tree/models/examples/lift/00-misc.json"
(cd "$work/tree" && "$mospec" run "$app" --sim --interpret --duration 4 --log run.csv > /dev/null 2>&1)
last=$(csv_at "$work/tree/run.csv" lift_q0 4)
check "with the reference at 0.30 m the slide ends there (got $last)" \
  holds "$last >= 0.299 && $last <= 0.301"

finish lift
