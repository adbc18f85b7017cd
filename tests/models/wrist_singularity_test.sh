#!/usr/bin/env bash
# models/examples/wrist-singularity: a degraded solve in simulation (issue #15
# item 7). The UR5e's end effector is held in all six directions (six
# acceleration constraints from velocity PI loops, no force) while the arm
# sits at its wrist singularity, q5 = 0: joints 2, 3, 4 and 6 are parallel, the
# tip's rotation about x_P cannot be produced, and the 6 x 6 constraint
# coupling of the ACHD solve has lost rank (its smallest eigenvalue is round-off,
# 5e-19 of the largest). Nothing moves the arm out of it (q5 stays within 1e-17
# rad; the solve stops reporting "degraded" only beyond about 8.5e-10 rad), so
# every tick's solve is degraded:
#   - the solver's `.degraded` log column is 1;
#   - the summary's verdict counts the degraded ticks;
#   - the console warns, naming the solver;
#   - the run still exits 0 with verdict "ok": a degraded solve is reported,
#     not a failure.
# The same app started away from the singularity (q5 = -pi/2, models/ur5e's
# q0) reports no degraded solve. Interpreted and generated runs log the same
# bytes and give the same verdict.
# Usage: wrist_singularity_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
cd "$src"  # the app's iri-map paths are relative to the repository root
app=models/examples/wrist-singularity.json
world=models/examples/wrist-singularity.world.json
solver=slv-ur5e
ticks=2000

# A summary's field: a Python expression on the summary `s` and its verdict `v`.
field() {
  python3 -c 'import json, sys
s = json.load(open(sys.argv[1])); v = s["verdict"]; print(eval(sys.argv[2]))' "$1" "$2"
}
# How many logged rows have column NAME equal to 1, and how many rows there are.
rows_set() {
  awk -F, -v name="$2" 'NR==1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $c[name] == 1 { n++ } END { print n + 0 }' "$1"
}
rows() { echo $(($(wc -l < "$1") - 1)); }
warning="^mospec: warning: the solver '$solver' lost constraint directions in $ticks of $ticks ticks"

validates_clean "$app"

check "the world starts the arm at its wrist singularity (q5 = 0)" \
  python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1]))["arms"]["right"]["q"][4] != 0)' "$world"

# --- at the singularity: every solve degraded, reported, exit 0 -------------
for mode in interpreted generated; do
  if [ "$mode" = interpreted ]; then flags=(--interpret); else flags=(--cache "$work/cache"); fi
  expect "runs ($mode): exits 0 and warns that '$solver' lost constraint directions in every tick" \
    0 "$warning" -- "$mospec" run "$app" --sim "${flags[@]}" --duration 2 \
    --log "$work/$mode.csv" --summary "$work/$mode.json"
  cp "$work/stderr.txt" "$work/$mode.stderr"
  log=$work/$mode.csv sum=$work/$mode.json
  check "$mode: the log has the solver's $solver.degraded column" csv_has "$log" "$solver.degraded"
  check "$mode: $solver.degraded is 1 in every logged row ($(rows_set "$log" "$solver.degraded") of $(rows "$log"))" \
    test "$(rows_set "$log" "$solver.degraded")" -eq "$(rows "$log")" -a "$(rows "$log")" -gt 0
  check "$mode: the summary's verdict counts $ticks degraded ticks for $solver" \
    test "$(field "$sum" 'v["degraded_solves"]["'$solver'"]')" = "$ticks"
  check "$mode: the summary's own count agrees" \
    test "$(field "$sum" 's["degraded_solves"]["'$solver'"]')" = "$ticks"
  check "$mode: the verdict is ok with exit status 0 (a degraded solve is no failure)" \
    test "$(field "$sum" 'v["status"] + " " + str(v["exit_status"]) + " " + str(v["why"])')" = "ok 0 []"
  check "$mode: the console's verdict lists the degraded solves" \
    grep -q "^  degraded solves: $solver in $ticks ticks$" "$work/$mode.stderr"
  # The premise: the arm stays at the singularity (q5 is column right_q4).
  read -r lo hi <<< "$(csv_range "$log" right_q4 0)"
  check "$mode: q5 stays within 1e-12 rad of 0 (range $lo .. $hi)" holds "$lo > -1e-12 && $hi < 1e-12"
done
check "generated and interpreted logs are byte-identical" cmp -s "$work/interpreted.csv" "$work/generated.csv"
check "generated and interpreted verdicts are the same" \
  python3 -c 'import json, sys
sys.exit(json.load(open(sys.argv[1]))["verdict"] != json.load(open(sys.argv[2]))["verdict"])' \
  "$work/interpreted.json" "$work/generated.json"

# --- the same task away from the singularity: nothing degraded --------------
python3 - "$world" "$work/regular.world.json" "$src" <<'PY'
import json, os, sys
w = json.load(open(sys.argv[1]))
right = w["arms"]["right"]
right["q"][4] = -1.5708  # models/ur5e.world.json's wrist: square to the forearm
# The copy lives elsewhere: its paths are made absolute.
right["robot"]["model"] = os.path.join(sys.argv[3], "robots/ur5e.jsonld")
right["robot"]["map"] = {k: os.path.join(sys.argv[3], "metamodels") for k in right["robot"]["map"]}
json.dump(w, open(sys.argv[2], "w"), indent=2)
PY
expect "runs away from the singularity (q5 = -pi/2, interpreted): exits 0" 0 "" -- \
  "$mospec" run "$app" --sim --interpret --duration 2 --world "$work/regular.world.json" \
  --log "$work/regular.csv" --summary "$work/regular.json"
check "away from the singularity: no degraded-solve warning" \
  bash -c "! grep -q 'lost constraint directions' '$work/stderr.txt'"
check "away from the singularity: $solver.degraded is 0 in every logged row" \
  test "$(rows_set "$work/regular.csv" "$solver.degraded")" -eq 0
check "away from the singularity: the verdict counts no degraded tick" \
  test "$(field "$work/regular.json" 'v["degraded_solves"]["'$solver'"]')" = 0

finish wrist_singularity
