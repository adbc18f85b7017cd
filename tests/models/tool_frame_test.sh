#!/usr/bin/env bash
# A tool link fixed to the arm's last moving link (a URDF's tool0) as the
# controlled frame (issue #33 item 7). tests/models/data/tool-frame/tool-arm.urdf
# (a lift axis, a shoulder and a pitching hand, tool0 0.12 m along the hand)
# is imported by `mospec import-urdf`; the task there (tool-frame/) outputs
# tool0's pose, attaches three linear acceleration constraints to link-tool0
# and drives tool0's origin to a goal by PD controllers on its position. The
# app validates; lowers to tip outputs and constraints at the tool (ACHD's tip
# frame is tool0); in simulation the run is "ok" and tool0's origin ends at
# the goal within 1 mm, computed from the final joint positions by this
# test's own forward kinematics (not mospec's), while the last link's origin
# ends elsewhere; the generated controller's log is byte-identical to the
# interpreter's.
# Usage: tool_frame_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
data="$src/tests/models/data/tool-frame"
# The app's tree: the metamodels and the shared models it imports, the task,
# and the robot as import-urdf writes it.
tree="$work/tree"
mkdir -p "$tree/models" "$tree/robots"
cp -r "$src/metamodels" "$tree/"
cp -r "$src/models/common" "$src/models/platform" "$tree/models/"
cp -r "$data" "$tree/tool-frame"
cd "$tree"

expect "imports the URDF, noting the tool link" 0 \
  "^mospec: note: the tip link 'tool0' is fixed to the last moving link 'hand' \(fixed joint hand-tool0\): the model states it as the link <https://mospec.example/robots/tool-arm/link-tool0> .*It can be an arm solver's controlled frame: attach its motion drivers to <https://mospec.example/robots/tool-arm/link-tool0>" \
  -- "$mospec" import-urdf tool-frame/tool-arm.urdf -o robots/tool-arm.jsonld
expect "... as [fixed-tip] (MOSPEC_DIAGNOSTIC_CODES=1)" 0 "^mospec: note\[fixed-tip\]: the tip link 'tool0'" \
  -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" import-urdf tool-frame/tool-arm.urdf -o "$work/tool-arm-again.jsonld"
app=tool-frame/app.json
expect "validates" 0 "" -- "$mospec" validate "$app"
stdout_has "validates with no finding" '^shacl: 0 violations, 0 warnings, 0 infos'

expect "lowers" 0 "" -- "$mospec" ir "$app" -o "$work/ir.json"
cat > "$work/check.py" <<'PY'
import json, sys
from ir_checks import want, single_arm, report
ir = json.load(open(sys.argv[1]))
arm = single_arm(ir)
want(arm["tip-is-last-segment"] is False, "the constraints act at the tool, not the last link")
want([c["component"] for c in arm["acceleration-constraints"]] == [3, 4, 5],
     f"three linear constraints: {arm['acceleration-constraints']}")
want([o["what"] for o in arm["outputs"]] == ["tip-pose"], f"outputs {arm['outputs']}")
p = arm["X_NT"]["p"]
want(abs(p[0] - 0.12) < 1e-15 and abs(p[1]) < 1e-15 and abs(p[2]) < 1e-15, f"X_NT {arm['X_NT']}")
report()
PY
check_program "$work/check.py" "$work/ir.json"

expect "runs (interpreted), verdict ok" 0 "^mospec: verdict: ok$" -- "$mospec" run "$app" --interpret --duration 3 \
  --log "$work/run.csv" --summary "$work/run.json"
check "every goal of the motion met" \
  grep -q "goals of motion-reach at the run's end .*: 3 of 3 met" "$work/stderr.txt"
cat > "$work/fk.py" <<'PY'
# tool0's origin and the hand's (the last link's) in the platform frame, from
# the last logged joint positions: the mount (0.1, 0, 0), the lift along z
# from 0.2, the shoulder 0.1 above the carriage about z, the wrist 0.3 along
# the arm about y, tool0 0.12 along the hand.
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
q = [float(rows[-1][f"tool_q{i}"]) for i in range(3)]
d, a, b = q
reach = 0.3 + 0.12 * math.cos(b)
tool = (0.1 + math.cos(a) * reach, math.sin(a) * reach, 0.3 + d - 0.12 * math.sin(b))
hand = (0.1 + 0.3 * math.cos(a), 0.3 * math.sin(a), 0.3 + d)
goal = (0.45, 0.11, 0.40)
err = math.dist(tool, goal)
if err > 1e-3:
    print(f"tool0 ends at {tool}, {err:.3g} m from the goal {goal} (q = {q})")
if math.dist(hand, goal) < 0.05:
    print(f"the hand's origin {hand} is near the goal too: the test cannot tell the two apart")
PY
check_program "$work/fk.py" "$work/run.csv"

# The generated controller does exactly what the interpreter does.
expect "runs (generated)" 0 "" -- "$mospec" run "$app" --duration 3 --log "$work/gen.csv" \
  --cache "$work/cache"
check "generated and interpreted logs are byte-identical" cmp -s "$work/run.csv" "$work/gen.csv"

finish tool_frame
