#!/usr/bin/env bash
# The world file's values with units, the table's pose (issue #33 item 10), and
# an arm's actuation defaulting to its robot description's limits (item 7).
# Each refusal's expected message stands beside the offending file.
# Usage: world_file_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$work" || exit 1

first() {  # the value of column NAME in the log's first row
  awk -F, -v name="$1" 'NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { print $c[name]; exit }' "$2"
}

# --- Angles: a bare number is radians; degrees are written as such ---------
echo '{"base": "planar", "initial": {"base_yaw": 20}}' > bare-degrees.json
expect "a bare angle beyond a turn (degrees meant) is refused, saying how to write degrees" 2 \
  '^bare-degrees.json:1:44: error: base_yaw: 20 is outside the accepted range \[-6.283185307179586, 6.283185307179586\] rad; a bare number is in radians, an angle in degrees is written as such: "20 deg"' -- \
  "$mospec" sim bare-degrees.json --duration 0.01
echo '{"base": "planar", "initial": {"base_yaw": "20 degrees"}}' > bad-unit.json
expect "an unknown unit is refused, naming the accepted ones" 2 \
  "^bad-unit.json:1:44: error: base_yaw: '20 degrees' is not a number and its unit, one space apart, the unit one of rad, deg" -- \
  "$mospec" sim bad-unit.json --duration 0.01
echo '{"base": "planar", "initial": {"base_x": "-60 deg"}}' > angle-for-length.json
expect "an angle's unit for a length is refused" 2 \
  "^angle-for-length.json:1:42: error: base_x: '-60 deg' is not a number and its unit, one space apart, the unit one of m, cm, mm" -- \
  "$mospec" sim angle-for-length.json --duration 0.01
echo '{"base": "planar", "initial": {"base_yaw": "400 deg"}}' > too-far.json
expect "a value with a unit is range-checked in SI" 2 \
  "^too-far.json:1:44: error: base_yaw: '400 deg' \(6.981317007977318\) is outside the accepted range" -- \
  "$mospec" sim too-far.json --duration 0.01
echo '{"base": "planar", "initial": {"base_yaw": true}}' > not-a-number.json
expect "a value of another JSON kind names both forms" 2 \
  '^not-a-number.json:1:44: error: base_yaw: expected a number \[rad\] or a string of a number and its unit \("1 rad", "1 deg"\)' -- \
  "$mospec" sim not-a-number.json --duration 0.01

# "10 deg" and "66 cm" are the same world as their radians and metres.
echo '{"base": "planar", "initial": {"base_x": -0.66, "base_yaw": 0.17453292519943295},
       "arms": {"right": {"q": [-0.1989, 1.7282, -0.947, -2.1654, -0.3097, 0.4927, 0.7853981633974483]}}}' > si.json
echo '{"base": "planar", "initial": {"base_x": "-66 cm", "base_yaw": "10 deg"},
       "arms": {"right": {"q": [-0.1989, 1.7282, -0.947, -2.1654, -0.3097, 0.4927, "45 deg"]}}}' > units.json
expect "the world in SI units runs" 0 '' -- "$mospec" sim si.json --duration 0.05 --log si.csv
expect "the world with units runs" 0 '' -- "$mospec" sim units.json --duration 0.05 --log units.csv
check "degrees and centimetres give the same run, byte for byte" cmp -s si.csv units.csv
check "the run started at the yaw given in degrees" \
  holds "$(first base_yaw units.csv) > 0.1745 && $(first base_yaw units.csv) < 0.1746"

# --- The table's pose --------------------------------------------------------
echo '{"base": "fixed"}' > table-home.json
echo '{"base": "fixed", "table": {"pose": {"x": 0.5, "y": "20 cm", "yaw": "90 deg"}}}' > table-moved.json
expect "the table at home" 0 '' -- "$mospec" sim table-home.json --duration 0.01 --log home.csv
expect "the table moved and turned" 0 '' -- "$mospec" sim table-moved.json --duration 0.01 --log moved.csv
dx=$(awk -v a="$(first base_x moved.csv)" -v b="$(first base_x home.csv)" 'BEGIN { printf "%.9f", a - b }')
check "the robot starts in front of the moved table (its x moved by the table's 0.5 m: $dx)" \
  holds "$dx > 0.4999999 && $dx < 0.5000001"
check "the robot's own y and yaw stay what the world file says (0)" \
  holds "$(first base_y moved.csv) == 0 && $(first base_yaw moved.csv) == 0"
echo '{"table": {"pose": {"z": 0.1}}}' > table-z.json
expect "a table pose has x, y and yaw only" 2 \
  "^table-z.json:1:21: error: table.pose: unknown key 'z' \(expected one of: x, y, yaw\)" -- \
  "$mospec" sim table-z.json --duration 0.01

# --- `mospec run`: the world it used, the simulation by default --------------
expect "run names the world file beside the app, and needs no --sim" 0 \
  "^mospec: world: models/sc0a.world.json$" -- \
  env -C "$src" "$mospec" run models/sc0a.json --interpret --duration 0.01
check "the world is the run's first line" bash -c "head -1 '$work/stderr.txt' | grep -q '^mospec: world: '"
cp "$src/models/sc0a.world.json" "$work/other.world.json"
sed -i 's#"\.\./robots/#"'"$src"'/robots/#; s#"\.\./metamodels"#"'"$src"'/metamodels"#' "$work/other.world.json"
expect "run names the --world file" 0 "^mospec: world: $work/other.world.json$" -- \
  env -C "$src" "$mospec" run models/sc0a.json --world "$work/other.world.json" --interpret --duration 0.01
cp "$src/models/sc0a.json" "$work/lonely.json"
expect "run says when it found no world file" 0 \
  "^mospec: world: mospec's default world \(there is no $work/lonely.world.json\)$" -- \
  env -C "$src" "$mospec" run "$work/lonely.json" --interpret --duration 0.01
expect "--sim is still accepted" 0 "" -- \
  env -C "$src" "$mospec" run models/sc0a.json --sim --interpret --duration 0.01

# --- --help lists only flags that act -----------------------------------------
"$mospec" run --help > run-help.txt
check "run --help does not list --sim (the only target)" bash -c "! grep -q -- '--sim' run-help.txt"
"$mospec" trials --help > trials-help.txt
check "trials --help does not list --sim" bash -c "! grep -q -- '--sim' trials-help.txt"
for cmd in rdf stats new; do
  "$mospec" "$cmd" --help > "$cmd-help.txt"
  check "$cmd --help does not list --listed-shapes-only (it validates nothing)" \
    bash -c "! grep -q -- '--listed-shapes-only' $cmd-help.txt"
done
check "new --help does not list --strict (it reports no loader warnings)" \
  bash -c "! grep -q -- '--strict' new-help.txt"
check "validate --help lists --listed-shapes-only" grep -q -- '--listed-shapes-only' <("$mospec" validate --help)

finish world_file
