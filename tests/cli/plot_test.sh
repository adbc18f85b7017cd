#!/usr/bin/env bash
# `mospec plot`: figures from small hand-made run logs (svg and png, checked by
# their first bytes), a trials directory, and the errors (exit 2, located).
# Usage: plot_test.sh MOSPEC
. "$(dirname "$0")/../support/cli_lib.sh"

# A run log as `mospec run --log` writes it: SC1's columns (the platform
# wrench) or SC2's (no wrench; the distance controllers' outputs). $2 scales
# the distances, so trials differ.
run_log() {  # run_log sc1|sc2 SCALE > FILE
  awk -v kind="$1" -v k="$2" 'BEGIN {
    printf "t,cstr-dist-leftarm-shoulder-ee.value,cstr-dist-leftarm-shoulder-ee.lower,cstr-dist-leftarm-shoulder-ee.upper,"
    printf "cstr-dist-rightarm-shoulder-ee.value,cstr-dist-rightarm-shoulder-ee.lower,cstr-dist-rightarm-shoulder-ee.upper,"
    printf "ctrl-dist-leftarm-shoulder-ee.output,ctrl-dist-rightarm-shoulder-ee.output"
    if (kind == "sc1") printf ",base-force-distribution.fx,base-force-distribution.fy,base-force-distribution.mz"
    printf ",base_x\n"
    for (i = 1; i <= 60; i++) {
      t = i * 0.05
      dl = 0.70 + k * 0.10 * exp(-t); dr = 0.70 - k * 0.08 * exp(-t / 2)
      printf "%g,%.6f,0.68,0.72,%.6f,0.68,0.72,%.4f,%.4f", t, dl, dr, -40 * (dl - 0.70), -40 * (dr - 0.70)
      if (kind == "sc1") printf ",%.4f,%.4f,%.4f", -30 * exp(-t), 5 * sin(t), 2 * exp(-t / 3)
      printf ",%g\n", t / 10
    }
  }'
}

is_svg() { head -c 200 "$1" | grep -Eq '^(<\?xml|<svg)'; }
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }
has_text() { grep -q -- "$2" "$1"; }
no_temp() { ! ls -a "$1" | grep -q '^\.mospec-plot-'; }

run_log sc1 1 > "$work/sc1.csv"
run_log sc2 1 > "$work/sc2.csv"

# One run, both formats: the figure exists and is what its name says.
expect "sc1 svg" 0 "wrote" -- "$mospec" plot "$work/sc1.csv" -o "$work/sc1.svg" --title "SC1 (test)"
check "sc1 svg is svg" is_svg "$work/sc1.svg"
check "sc1 svg has the legend" grep -q "thr" "$work/sc1.svg"
expect "sc1 png" 0 "wrote" -- "$mospec" plot "$work/sc1.csv" -o "$work/sc1.png"
check "sc1 png is png" is_png "$work/sc1.png"
check "no temporary left" no_temp "$work"
# No platform wrench (SC2): the distance controllers' outputs instead.
expect "sc2 svg" 0 "wrote" -- "$mospec" plot "$work/sc2.csv" -o "$work/sc2.svg"
check "sc2 svg is svg" is_svg "$work/sc2.svg"
# Chosen columns; a quote in the title reaches gnuplot as text.
expect "chosen columns" 0 "" -- "$mospec" plot "$work/sc1.csv" -o "$work/pick.png" \
  --distance cstr-dist-leftarm-shoulder-ee.value --force base_x --title "it's \"quoted\""
check "chosen columns png" is_png "$work/pick.png"

# Errors: exit 2, the file (and line) named, nothing written.
expect "missing --force column" 2 "sc1.csv:1:1: error: no column 'nope' \(--force\); the columns are: t, cstr-dist" -- \
  "$mospec" plot "$work/sc1.csv" -o "$work/bad.svg" --force nope
# A log without both distances is another app's: its own default (below).
cut -d, -f1-4,8- "$work/sc1.csv" > "$work/no-right.csv"
expect "one distance only: the constraints' values" 0 "wrote" -- \
  "$mospec" plot "$work/no-right.csv" -o "$work/no-right.svg"
check "its left panel is the remaining constraint's value" \
  has_text "$work/no-right.svg" "cstr-dist-leftarm-shoulder-ee.value \[m\]"
cut -d, -f1-7,10 "$work/sc2.csv" > "$work/no-force.csv"
expect "no force columns" 2 "no-force.csv:1:1: error: no force columns: .*--force" -- \
  "$mospec" plot "$work/no-force.csv" -o "$work/bad.svg"
{ head -3 "$work/sc1.csv"; echo "0.2,0.7,0.68,zero,0.7,0.68,0.72,1,1,1,1,1,1"; } > "$work/bad-number.csv"
expect "malformed number" 2 "bad-number.csv:4:[0-9]+: error: column 'cstr-dist-leftarm-shoulder-ee.upper': 'zero' is not a number" -- \
  "$mospec" plot "$work/bad-number.csv" -o "$work/bad.svg"
{ head -4 "$work/sc1.csv"; echo "0.25,0.7,0.68"; } > "$work/short-row.csv"
expect "short row" 2 "short-row.csv:5:[0-9]+: error: expected 13 fields \(as in the header\), got 3" -- \
  "$mospec" plot "$work/short-row.csv" -o "$work/bad.svg"
: > "$work/empty.csv"
expect "empty file" 2 "empty.csv:1:1: error: the file is empty" -- "$mospec" plot "$work/empty.csv" -o "$work/bad.svg"
expect "missing file" 2 "cannot read '.*/absent.csv'" -- "$mospec" plot "$work/absent.csv" -o "$work/bad.svg"
expect "unknown format" 2 "must end in .svg or .png" -- "$mospec" plot "$work/sc1.csv" -o "$work/bad.pdf"
expect "missing output dir" 2 "no directory" -- "$mospec" plot "$work/sc1.csv" -o "$work/nowhere/bad.svg"
mkfifo "$work/fifo.svg"
expect "output not a regular file" 2 "fifo.svg': not a regular file" -- \
  "$mospec" plot "$work/sc1.csv" -o "$work/fifo.svg"
rm "$work/fifo.svg"
expect "no gnuplot" 2 "gnuplot.*gnuplot-nox" -- env PATH=/nonexistent "$mospec" plot "$work/sc1.csv" -o "$work/bad.svg"
check "no output after errors" test ! -e "$work/bad.svg"
check "no temporary after errors" no_temp "$work"

# Trials: three runs with the same columns and time base -> mean +- 1 std.
mkdir "$work/trials"
for i in 0 1 2; do run_log sc2 "1.$i" > "$work/trials/trial-$i.csv"; done
expect "trials svg" 0 "3 trials" -- "$mospec" plot "$work/trials" -o "$work/trials.svg"
check "trials svg is svg" is_svg "$work/trials.svg"
expect "trials png" 0 "3 trials" -- "$mospec" plot "$work/trials" -o "$work/trials.png"
check "trials png is png" is_png "$work/trials.png"
# A trial on another time base is refused at its first differing row.
mkdir "$work/skewed"
cp "$work/trials/trial-0.csv" "$work/trials/trial-1.csv" "$work/skewed/"
sed '3s/^0.1,/0.11,/' "$work/trials/trial-2.csv" > "$work/skewed/trial-2.csv"
expect "trials time base" 2 "skewed/trial-2.csv:3:1: error: t = 0.11.* differs" -- \
  "$mospec" plot "$work/skewed" -o "$work/bad.svg"
# A manifest from `mospec trials`: a trial that did not exit 0 is left out.
cat > "$work/trials/trials.json" <<'JSON'
{"trials": [{"index": 0, "exit_code": 0, "csv": "trial-0.csv"},
            {"index": 1, "exit_code": 1, "csv": "trial-1.csv"},
            {"index": 2, "exit_code": null, "signal": 9, "csv": "trial-2.csv"}]}
JSON
expect "failed trials left out" 0 "\(1 trial\)" -- "$mospec" plot "$work/trials" -o "$work/trials.svg"
check "failed trial warned" grep -q "leaving out .*trial-1.csv: its run did not exit 0" "$work/stderr.txt"
echo '{"trials": 3}' > "$work/trials/trials.json"
expect "bad manifest" 2 "trials/trials.json:1:12: error: not a .mospec trials. manifest: \"trials\" is not an array" -- \
  "$mospec" plot "$work/trials" -o "$work/trials.svg"
expect "... as [trials] (MOSPEC_DIAGNOSTIC_CODES=1)" 2 "trials/trials.json:1:12: error\[trials\]: not a .mospec trials. manifest" -- \
  env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" plot "$work/trials" -o "$work/trials.svg"
echo '{"trials": [{"exit_code": "0", "csv": "trial-0.csv"}]}' > "$work/trials/trials.json"
expect "a manifest field of the wrong type" 2 "trials/trials.json:1:27: error: not a .mospec trials. manifest: a trial's \"exit_code\" is not a number or null" -- \
  "$mospec" plot "$work/trials" -o "$work/trials.svg"
# Issue #17: the title is the scenario's name (trials.json's app; a run's
# summary next to its log); a start-up spike is clipped and said; markers at
# motion starts and events, labelled; labels follow the chosen columns.
mkdir "$work/named"
for i in 0 1; do run_log sc2 "1.$i" > "$work/named/trial-$i.csv"; done
echo '{"app": "models/sc2.json", "trials": []}' > "$work/named/trials.json"
expect "trials titled by the scenario" 0 "2 trials" -- "$mospec" plot "$work/named" -o "$work/named.svg"
check "the title names sc2" has_text "$work/named.svg" "sc2: mean ± 1 std over 2 trials"
run_log sc1 1 > "$work/sc1-run.csv"
echo '{"scenario": "models/sc1.json"}' > "$work/sc1-run-summary.json"
expect "run titled by its summary's scenario" 0 "wrote" -- \
  "$mospec" plot "$work/sc1-run.csv" -o "$work/sc1-run.svg"
check "the title is sc1" has_text "$work/sc1-run.svg" ">sc1</text>"
expect "without a summary: the file's name" 0 "wrote" -- "$mospec" plot "$work/sc1.csv" -o "$work/plain.svg"
check "the title is the file's name" has_text "$work/plain.svg" ">sc1.csv</text>"
# A -900 N spike in the first row, a motion starting in the second row, an
# event in the 30th row.
awk -F, -v OFS=, 'NR == 1 { print $0, "motion-m.running", "mon-e.event"; next }
  { if (NR == 2) $(NF - 3) = -900; print $0, (NR >= 3 ? 1 : 0), (NR == 31 ? 1 : 0) }' \
  "$work/sc1.csv" > "$work/spike.csv"
expect "spike" 0 "wrote" -- "$mospec" plot "$work/spike.csv" -o "$work/spike.svg"
check "the clipped note" has_text "$work/spike.svg" "clipped: start-up spike down to -900 N"
check "the motion start marker" has_text "$work/spike.svg" "motion-m starts"
check "the event marker" has_text "$work/spike.svg" "mon-e rising"
check "no clipped note without a spike" sh -c '! grep -q clipped "$1"' - "$work/plain.svg"
expect "labels follow columns" 0 "wrote" -- "$mospec" plot "$work/sc1.csv" -o "$work/cols.svg" \
  --distance base_x --force base-force-distribution.fx
check "left label: base_x [m]" has_text "$work/cols.svg" "base_x \[m\]"
check "right label: the force column [N]" has_text "$work/cols.svg" "base-force-distribution.fx \[N\]"
# A threshold far outside the data is not drawn: an upper bound of 40 m.
sed '2,$s/,0\.72,/,40,/g' "$work/sc2.csv" > "$work/far.csv"
check "the copy has the far bound" grep -q ',40,' "$work/far.csv"
expect "far threshold" 0 "wrote" -- "$mospec" plot "$work/far.csv" -o "$work/far.svg"
check "the distance axis does not reach 40 m" sh -c '! grep -Eq ">(40|35|30|20|10)</text>" "$1"' - "$work/far.svg"

# Any other app: its constraints' values of the unit most share, with their
# setpoints and thresholds, and its controllers' outputs, one unit a panel.
# The units and the constants come from the run's summary beside the log.
awk 'BEGIN {
  print "t,pos-z.value,pos-z.error,pos-y.value,pos-y.error,ang.value,ang.error,ctl-z.output,ctl-y.output,ctl-a.output"
  for (i = 1; i <= 40; i++) { t = i * 0.05; z = 0.25 - 0.1 * exp(-t); y = 0.1 * exp(-t)
    printf "%g,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%.4f,%.4f\n", t, z, 0.25 - z, y, 0, 0.3 * t, 0, 40 * (0.25 - z), -y, 0.5 }
}' > "$work/other.csv"
cat > "$work/other.json" <<'JSON'
{"scenario": "models/examples/other.json", "verdict": {"status": "ok"},
 "log": {"units": {"pos-z.value": "M", "pos-z.error": "M", "pos-y.value": "M", "pos-y.error": "M",
                   "ang.value": "RAD", "ang.error": "RAD",
                   "ctl-z.output": "N", "ctl-y.output": "N", "ctl-a.output": "N-M"},
         "constraints": {"pos-z": {"relation": "equality", "reference": 0.25, "tolerance": 0.001},
                         "pos-y": {"relation": "less-than", "upper": 0.2, "tolerance": 0}}}}
JSON
expect "another app's run" 0 "wrote" -- "$mospec" plot "$work/other.csv" -o "$work/other.svg"
check "left: the two values in metres" has_text "$work/other.svg" "pos-z.value, pos-y.value \[m\]"
check "the radians stay off that axis" sh -c '! grep -q "ang.value" "$1"' - "$work/other.svg"
check "the equality's setpoint is drawn" has_text "$work/other.svg" "pos-z.setpoint"
check "the limit's threshold is drawn" has_text "$work/other.svg" "pos-y.upper"
check "right: the outputs in newtons" has_text "$work/other.svg" "ctl-z.output, ctl-y.output \[N\]"
check "the torque output stays off that axis" sh -c '! grep -q "ctl-a.output" "$1"' - "$work/other.svg"
# A motion's `until` is a condition, not a goal: left out of the default.
cp "$work/other.csv" "$work/guard.csv"
sed 's/"upper": 0.2, "tolerance": 0}/"upper": 0.2, "tolerance": 0, "guard": true}/' "$work/other.json" > "$work/guard.json"
check "the guard is marked in the copy" grep -q '"guard": true' "$work/guard.json"
expect "a run with a guard" 0 "wrote" -- "$mospec" plot "$work/guard.csv" -o "$work/guard.svg"
check "the guard's value is not drawn" sh -c '! grep -q "pos-y.value" "$1"' - "$work/guard.svg"
check "the goal's is" has_text "$work/guard.svg" "pos-z.value \[m\]"
cp "$work/other.csv" "$work/bare.csv"
expect "another app's run without a summary" 0 "wrote" -- "$mospec" plot "$work/bare.csv" -o "$work/bare.svg"
check "its constraints' values, named" has_text "$work/bare.svg" "pos-z.value, pos-y.value and 1 more"
cut -d, -f1,2,4,6 "$work/other.csv" > "$work/no-out.csv"
cp "$work/other.json" "$work/no-out.json"
sed -i 's/"ang.value": "RAD", "ang.error": "RAD",//' "$work/no-out.json"
expect "no controller outputs and no errors" 2 "no-out.csv:1:1: error: no force columns" -- \
  "$mospec" plot "$work/no-out.csv" -o "$work/bad.svg"
cut -d, -f1-7 "$work/other.csv" > "$work/errors.csv"
cp "$work/other.json" "$work/errors.json"
expect "no controller outputs: the errors" 0 "wrote" -- "$mospec" plot "$work/errors.csv" -o "$work/errors.svg"
check "right: the plotted constraints' errors" has_text "$work/errors.svg" "pos-z.error, pos-y.error \[m\]"
echo '{"verdict": {}, "log": {"units": {"pos-z.value": 3}}}' > "$work/broken.json"
cp "$work/other.csv" "$work/broken.csv"
expect "a summary that does not read: a warning" 0 "broken.json:1:[0-9]+: warning: a unit of log.units is a number" -- \
  "$mospec" plot "$work/broken.csv" -o "$work/broken.svg"

mkdir "$work/none"
expect "no trials" 2 "no trial-<i>.csv" -- "$mospec" plot "$work/none" -o "$work/bad.svg"

finish plot_test
