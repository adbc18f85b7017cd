#!/usr/bin/env bash
# The robot comes from the models (issue #16 items 1 and 5): robots other than
# the default two Gen3, in closed loop, interpreted and generated alike.
#   models/ur5e.json: a UR5e (robots/ur5e.urdf, imported to ur5e.jsonld) on the
#     platform presses the table's face with 15 N while its other five
#     end-effector directions are held. Criteria: the motion runs for 5 s, the
#     contact force is 15 N +- 10 % after 1 s, the tip moves less than 5 mm
#     sideways and vertically from its start, torques stay within the UR5e's
#     limits, and the log has the arm's 6 joints and no second arm.
#   models/sc0a-one-arm.json: sc0a on a robot with only the right arm. sc0a's
#     criteria (20 N +- 10 %, elbow within 2 cm) and no left-arm columns.
# Each: interpreted and generated logs byte-identical, verdict ok (exit 0).
# Usage: arms_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the apps' iri-map paths are relative to the repository root

within() {  # NAME LOG COLUMN FROM LO HI: the column stays in [LO, HI] from time FROM on
  local lo hi
  read -r lo hi <<< "$(csv_range "$2" "$3" "$4")"
  echo "$1: $3 from $4 s in [$lo, $hi]"
  check "$1" holds "$lo >= $5 && $hi <= $6"
}

both_ways() {  # NAME APP DURATION: run interpreted and generated, logs alike
  expect "$1: runs (interpreted)" 0 "verdict: ok" -- "$mospec" run "$2" --sim --interpret \
    --duration "$3" --log "$work/$1.csv" --summary "$work/$1.json"
  expect "$1: runs (generated)" 0 "verdict: ok" -- "$mospec" run "$2" --sim --duration "$3" \
    --log "$work/$1.gen.csv" --cache "$work/cache"
  check "$1: generated and interpreted logs are byte-identical" cmp -s "$work/$1.csv" "$work/$1.gen.csv"
}

# --- UR5e ---
validates_clean models/ur5e.json
both_ways ur5e models/ur5e.json 5
log=$work/ur5e.csv
check "ur5e: the log has the arm's six joints" csv_has "$log" right_q5
check "ur5e: ... and no seventh" eval '! csv_has "$log" right_q6'
check "ur5e: ... and no left arm" eval '! csv_has "$log" left_q0'
within "ur5e: contact force 15 N +- 10 % after 1 s" "$log" right_fn 1 13.5 16.5
within "ur5e: the motion runs throughout" "$log" motion-ur5e.running 0 1 1
for axis in y z; do
  start=$(csv_at "$log" right_ee_$axis 0)
  within "ur5e: the tip's $axis is held within 5 mm" "$log" right_ee_$axis 0 \
    "$(awk "BEGIN { print $start - 0.005 }")" "$(awk "BEGIN { print $start + 0.005 }")"
done
within "ur5e: torques within the UR5e's limits" "$log" tau_ratio 0 0 0.999999

# A world whose arm names another joint count than the chain: refused, located.
sed 's/"q": \[ *0,/"q": [/' models/ur5e.world.json > "$work/short.world.json"
sed -i 's|"\.\./robots/|"'"$src"'/robots/|; s|"\.\./metamodels"|"'"$src"'/metamodels"|' "$work/short.world.json"
expect "ur5e: a q of 5 numbers for the 6-joint arm is refused, located" 2 \
  'short.world.json:[0-9]+:[0-9]+: error: the chain .* of the right arm has 6 joints, but arms.right.q has 5 entries' \
  -- "$mospec" run models/ur5e.json --sim --interpret --duration 0.1 --world "$work/short.world.json"

# --- sc0a with one arm ---
both_ways one models/sc0a-one-arm.json 5
log=$work/one.csv
check "one arm: no left-arm columns" eval '! csv_has "$log" left_q0 && ! csv_has "$log" left_fn'
within "one arm: contact force 20 N +- 10 % after 1 s" "$log" right_fn 1 18 22
within "one arm: the elbow within 2 cm of its reference" "$log" \
  cstr-pos-rightarm-elbow-height.error 1 -0.02 0.02
expect "one arm: a fault on the absent arm's sensor is refused" 2 "no sensor named 'left_arm.q\[0\]'" \
  -- "$mospec" run models/sc0a-one-arm.json --sim --interpret --duration 0.1 \
  --fault 'nan:left_arm.q[0]@5'

finish arms
