#!/usr/bin/env bash
# The arms' mounts come from the task models (issue #16 item 2): the simulator
# mounts each arm where the models' constant pose (the solver's root -> the
# chain's root) puts it, so the IR and the simulated robot agree by
# construction; a world file stating another mount for such an arm is refused.
# Usage: mount_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
tree="$work/tree"
mkdir -p "$tree"
cp -r "$src/models" "$src/robots" "$src/metamodels" "$tree/"
cd "$tree" || exit 1

# The value of column NAME in the log's first row.
first() {
  awk -F, -v name="$1" 'NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { print $c[name]; exit }' "$2"
}

expect "sc0a as shipped" 0 "" -- "$mospec" run models/sc0a.json --sim --interpret --duration 0.01 \
  --log "$work/shipped.csv"

# The right arm's mount moved 10 cm along the platform's y, in the models only.
sed -i '/"@id": "pose-rightarm-platform-shoulder"/,/"z":/ s/"y": -0.1,/"y": 0.0,/' \
  models/platform/01-world-model.json
check "the models' mount moved" grep -q '"y": 0.0,' models/platform/01-world-model.json
expect "sc0a with the moved mount" 0 "" -- "$mospec" run models/sc0a.json --sim --interpret \
  --duration 0.01 --log "$work/moved.csv"
shift_y=$(awk -v a="$(first right_ee_y "$work/moved.csv")" -v b="$(first right_ee_y "$work/shipped.csv")" \
  'BEGIN { printf "%.9f", a - b }')
check "the simulated end effector moved with the models' mount (by 0.1 m along y: $shift_y)" \
  holds "$shift_y > 0.0999999 && $shift_y < 0.1000001"

# A world file that puts the right arm elsewhere than the models do.
python3 - <<'PY'
import json
w = json.load(open("models/sc0a.world.json"))
w["arms"] = {"right": {"mount": {"x": 0.0, "y": -0.1, "z": 0.1}}}
json.dump(w, open("models/sc0a.world.json", "w"))
PY
expect "a world file's mount that differs from the models' is refused" 2 \
  "the arm solver 'https://mospec.example/models/slv-rightarm' mounts its chain at 'https://mospec.example/models/pose-rightarm-platform-shoulder' \(position \(0, 0, 0.1\) m\), but the world file's arms.right.mount puts the right arm elsewhere \(position \(0, -0.1, 0.1\) m\); state the mount once" -- \
  "$mospec" run models/sc0a.json --sim --interpret --duration 0.01
check "the refusal is located at the solver" grep -Eq '^models/sc0a/07-scenario.json:[0-9]+:[0-9]+: error: the arm solver' "$work/stderr.txt"

# The same mount in both places is not a conflict.
python3 - <<'PY'
import json
w = json.load(open("models/sc0a.world.json"))
w["arms"] = {"right": {"mount": {"x": 0.0, "y": 0.0, "z": 0.1}}}
json.dump(w, open("models/sc0a.world.json", "w"))
PY
expect "a world file repeating the models' mount runs" 0 "" -- \
  "$mospec" run models/sc0a.json --sim --interpret --duration 0.01

finish mount
