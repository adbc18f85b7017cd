#!/usr/bin/env bash
# `mospec report`: one self-contained page per run or per trials directory,
# loaded in a real browser (Debian's headless Chromium): the script runs to
# its end with no console error, every chart is drawn, and nothing is fetched
# from the network.
# Usage: report_test.sh MOSPEC_BINARY SOURCE_DIR
source "$(dirname "$0")/../support/cli_lib.sh"
src=$(realpath "$2")
if ! command -v chromium > /dev/null; then
  echo "SKIP: chromium is not installed (scripts/install-deps installs it)"
  exit 77
fi
cd "$src" || exit 1

run_dir="$work/run"
mkdir -p "$run_dir"
expect "sc0a runs with a log, a summary and a video" 0 "" -- "$mospec" run models/sc0a.json --sim \
  --interpret --duration 1 --log "$run_dir/sc0a.csv" --summary "$run_dir/sc0a.json" \
  --video "$run_dir/sc0a.gif" --video-size 160x120
expect "the report is written" 0 "wrote $work/report.html \\(1 run\\)" -- \
  "$mospec" report "$run_dir" -o "$work/report.html"
page="$work/report.html"
check "the page names the verdict" grep -q 'class="status ok">ok<' "$page"
check "the page links the model's entities' files relative to the page" \
  grep -Eq '<a href="(\.\./)+[^"]*models/sc0a/05-constraint-handler.json">models/sc0a/05-constraint-handler.json:[0-9]+</a>' "$page"
check "the page embeds no absolute path of this machine" bash -c "! grep -q 'file://' '$page'"
expect "absolute links on request" 0 "" -- "$mospec" report "$run_dir" -o "$work/absolute.html" --absolute-links
check "--absolute-links links by file:// URL" \
  grep -Eq '<a href="file:///[^"]*/models/sc0a/05-constraint-handler.json">' "$work/absolute.html"
check "the video is inlined" grep -q 'src="data:image/gif;base64,' "$page"
check "nothing is fetched: no external script, style, image or link" \
  bash -c "! grep -Eiq '(src|href)=\"(https?:)?//|<link |@import|fetch\\(' '$page'"
check "dygraphs is inlined from libjs-dygraphs" grep -q 'Dygraph' "$page"

# In the browser: the DOM after the scripts ran, and the console.
browse() {
  timeout 120 chromium --headless=new --no-sandbox --disable-gpu --no-first-run \
    --enable-logging=stderr --v=0 --virtual-time-budget=5000 --dump-dom "file://$1" \
    > "$work/dom.html" 2> "$work/console.txt"
}
browse "$page"
charts=$(grep -o '<div class="chart" id="chart-[0-9]*"' "$page" | wc -l)
check "the page has charts ($charts)" test "$charts" -ge 4
check "the script ran to its end and drew every chart" \
  grep -q "data-charts=\"$charts\"" "$work/dom.html"
check "every chart has its canvas" test "$(grep -o '<canvas' "$work/dom.html" | wc -l)" -ge "$charts"
check "no console error" bash -c "! grep -Eiq 'CONSOLE.*(error|uncaught)|Uncaught' '$work/console.txt'"
# dygraphs fills each chart's legend (labelsDiv) with its series at once
# (legend: 'always'), not only on hover.
legends=$(grep -o '<div class="legend" id="chart-[0-9]*-legend"><' "$work/dom.html" | wc -l)
check "every chart's legend is drawn without hovering ($legends of $charts)" test "$legends" -eq "$charts"
check "a legend names a series" grep -Eq 'id="chart-0-legend">.*[a-z0-9-]+\.running' "$work/dom.html"
check "the controlled frame's position has its chart" \
  grep -q "<h3>Controlled frames&#39; positions in W (simulator) <span class=\"note\">\[m\]" "$page"
check "no chart mixes units: each title names one" \
  bash -c "! grep -o '<h3>[^<]*<span class=\"note\">\[[^]]*\]' '$page' | grep -Eq '\[[^]]*, [^]]*\]'"

# A real 30 s run (SC1, logged every other tick: 15000 rows): the page's chart data is decimated
# to at most 1 MB, and a one-tick extreme of the log is still on the page.
long="$work/long"
mkdir -p "$long"
expect "SC1 runs 30 s, logged every other tick" 0 "" -- "$mospec" run models/sc1.json --sim --interpret \
  --duration 30 --log-every 2 --log "$long/sc1.csv" --summary "$long/sc1.json"
expect "its report" 0 "" -- "$mospec" report "$long" -o "$work/long.html"
data_bytes=$(python3 -c '
import sys
page = open(sys.argv[1]).read()
at = page.index("const chartData = ") + len("const chartData = ")
print(page.index(";\n", at) - at)' "$work/long.html")
log_bytes=$(stat -c %s "$long/sc1.csv")
check "the 30 s run's chart data is at most 1 MB ($data_bytes bytes; the log $log_bytes)" \
  test "$data_bytes" -le 1000000
check "the summary records the log's units" \
  python3 -c 'import json, sys; u = json.load(open(sys.argv[1]))["log"]["units"]; sys.exit(u.get("cstr-dist-rightarm-shoulder-ee.value") != "M")' "$long/sc1.json"
check "the largest platform force of the log is on the page" python3 -c '
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
col = "base-force-distribution.fx"
peak = max((float(r[col]) for r in rows), key=abs)
page = open(sys.argv[2]).read()
at = page.index("const charts = ") + len("const charts = ")
charts = json.loads(page[at:page.index(";\n", at)])
at = page.index("const chartData = ") + len("const chartData = ")
data = json.loads(page[at:page.index(";\n", at)])
for c, d in zip(charts, data):
    if col in c["labels"]:
        k = c["labels"].index(col)
        drawn = max((row[k] for row in d if row[k] is not None), key=abs)
        sys.exit(abs(drawn - peak) > 1e-5 * max(1, abs(peak)))
sys.exit(1)' "$long/sc1.csv" "$work/long.html"
browse "$work/long.html"
long_charts=$(grep -o '<div class="chart" id="chart-[0-9]*"' "$work/long.html" | wc -l)
check "the 30 s run's charts are drawn" grep -q "data-charts=\"$long_charts\"" "$work/dom.html"
check "no console error (30 s run)" bash -c "! grep -Eiq 'CONSOLE.*(error|uncaught)|Uncaught' '$work/console.txt'"

# `mospec plot` draws any app's run by default: the lift example's (neither
# SC1 nor SC2) constraint values with their setpoints, one unit an axis.
expect "the lift example runs" 0 "" -- "$mospec" run models/examples/lift.json --sim --interpret \
  --duration 1 --log "$work/lift.csv" --summary "$work/lift.json"
expect "its plot, without flags" 0 "wrote" -- "$mospec" plot "$work/lift.csv" -o "$work/lift.svg"
check "the plot draws its constraints' values" grep -q '\.value' "$work/lift.svg"
check "and their setpoints or thresholds" grep -Eq '\.(setpoint|lower|upper)' "$work/lift.svg"

# Trials: the mean and one standard deviation over the runs of a directory.
trials="$work/trials"
mkdir -p "$trials"
for seed in 1 2 3; do
  expect "trial $seed" 0 "" -- "$mospec" run models/sc0a.json --sim --interpret --duration 0.5 \
    --seed "$seed" --log "$trials/trial-$seed.csv" --summary "$trials/trial-$seed.json"
done
expect "the trials' report" 0 "\\(3 runs\\)" -- "$mospec" report "$trials" -o "$work/trials.html"
check "each trial's verdict is listed" test "$(grep -c 'class="verdict" id="verdict-trial-' "$work/trials.html")" -eq 3
browse "$work/trials.html"
check "the trials' charts are drawn" grep -Eq 'data-charts="[1-9][0-9]*"' "$work/dom.html"
check "no console error (trials)" bash -c "! grep -Eiq 'CONSOLE.*(error|uncaught)|Uncaught' '$work/console.txt'"

# A hostile run directory: every field of the summary, the log's column names
# and the run's name carry markup and script. The page must draw every chart
# and run none of it (an injected script would set data-pwned on the body).
hostile="$work/hostile"
mkdir -p "$hostile"
payload='</script><script>document.body.dataset.pwned=1</script><!--<script><img src=x onerror=document.body.dataset.pwned=1>'
name="h<img src=x onerror=document.body.dataset.pwned=1>"
python3 - "$run_dir/sc0a.json" "$hostile/$name.json" "$payload" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
p = sys.argv[3]
s["scenario"] = p
s["controller"] = p
v = s["verdict"]
v["status"] = p
v["why"] = [p, p]
for m in v["motions"]:
    m["name"] = p; m["ended_by"] = p
for c in v["constraints"]:
    c["name"] = p; c["relation"] = p
s["events"] = [{"tick": 1, "event": p, "edge": p}]
# A unit lands in a chart's title and its axis label (which dygraphs writes
# as HTML); a constraint's name is looked up, never shown.
s["log"]["units"] = {k: p for k in s["log"]["units"]}
s["log"]["constraints"] = {p: {"relation": p, "reference": 1, "tolerance": 0.5}}
json.dump(s, open(sys.argv[2], "w"))
PY
{ head -1 "$run_dir/sc0a.csv" | sed "s|^t,\([^,]*\),\([^,]*\),|t,\1,${payload//|/\|}.value,|"; tail -n +2 "$run_dir/sc0a.csv"; } > "$hostile/$name.csv"
check "the hostile log has the payload as a column" grep -q 'pwned=1>.value' "$hostile/$name.csv"
expect "the hostile run's report is written" 0 "" -- "$mospec" report "$hostile" -o "$work/hostile.html"
browse "$work/hostile.html"
hostile_charts=$(grep -o '<div class="chart" id="chart-[0-9]*"' "$work/hostile.html" | wc -l)
check "the hostile page has its charts ($hostile_charts)" test "$hostile_charts" -ge 4
check "every chart of the hostile page is drawn" grep -q "data-charts=\"$hostile_charts\"" "$work/dom.html"
check "no script from the data ran" bash -c "! grep -q 'data-pwned' '$work/dom.html'"
check "no element from the data exists" bash -c "! grep -q '<img src=\"x\"' '$work/dom.html'"
check "no console error (hostile)" bash -c "! grep -Eiq 'CONSOLE.*(error|uncaught)|Uncaught' '$work/console.txt'"
check "the payload is shown as text" grep -q 'document.body.dataset.pwned=1&lt;/script&gt;' "$work/dom.html"
cp "$work/dom.html" "$work/hostile-dom.html"

# A video is inlined only from inside the run's directory and only when its
# header says GIF or MP4.
linked="$work/linked"
mkdir -p "$linked"
cp "$run_dir/sc0a.json" "$run_dir/sc0a.csv" "$linked/"
echo "GIF89a the author's private notes" > "$work/private.gif"
ln -s "$work/private.gif" "$linked/sc0a.gif"
expect "a video linked out of the run's directory" 2 "the run's video .*sc0a.gif resolves to '.*private.gif', outside the run's directory" -- \
  "$mospec" report "$linked" -o "$work/none.html"
check "the linked file's content is not quoted" bash -c "! grep -q 'private notes' '$work/stderr.txt'"
expect "--no-video leaves it out" 0 "" -- "$mospec" report "$linked" -o "$work/novideo.html" --no-video
check "no video on that page" bash -c "! grep -q 'data:image/gif' '$work/novideo.html'"
rm "$linked/sc0a.gif"
echo "not a video at all" > "$linked/sc0a.mp4"
expect "a video whose header is not MP4" 2 "sc0a.mp4 is not an MP4 \(its first bytes say neither\)" -- \
  "$mospec" report "$linked" -o "$work/none.html"
rm "$linked/sc0a.mp4"
python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); s["duration"]="ten"; json.dump(s, open(sys.argv[1],"w"))' "$linked/sc0a.json"
expect "a summary field of the wrong type" 2 "sc0a.json:1:[0-9]+: error: \"duration\" is a string" -- \
  "$mospec" report "$linked" -o "$work/none.html"
printf '{"verdict": {"why": %s' "$(head -c 100000 /dev/zero | tr '\0' '[')" > "$linked/sc0a.json"
expect "a deeply nested summary" 2 "sc0a.json:1:[0-9]+: error: .*nesting deeper than 512 levels" -- \
  "$mospec" report "$linked" -o "$work/none.html"

# Bad input: refused, named, nothing written.
mkdir -p "$work/empty"
expect "a directory without runs" 2 "holds no run" -- "$mospec" report "$work/empty" -o "$work/none.html"
echo '{}' > "$work/lonely.json"
expect "a summary without its log" 2 "has no log beside it" -- "$mospec" report "$work/lonely.json" -o "$work/none.html"
cp "$run_dir/sc0a.csv" "$work/lonely.csv"
expect "a JSON that is not a run summary" 2 "lonely.json:1:1: error: not a run summary" -- "$mospec" report "$work/lonely.json" -o "$work/none.html"
expect "... as [report] (MOSPEC_DIAGNOSTIC_CODES=1)" 2 "lonely.json:1:1: error\[report\]: not a run summary" -- env MOSPEC_DIAGNOSTIC_CODES=1 "$mospec" report "$work/lonely.json" -o "$work/none.html"
check "nothing was written for them" test ! -e "$work/none.html"

check "a hostile unit reaches an axis label as text" grep -q 'dygraph-ylabel[^>]*>\[&lt;/script&gt;' "$work/hostile-dom.html"
finish report
