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
check "the page has the model's entities with file:line" \
  grep -Eq '<a href="file://[^"]*/models/sc0a/05-constraint-handler.json">models/sc0a/05-constraint-handler.json:[0-9]+</a>' "$page"
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

# Bad input: refused, named, nothing written.
mkdir -p "$work/empty"
expect "a directory without runs" 2 "holds no run" -- "$mospec" report "$work/empty" -o "$work/none.html"
echo '{}' > "$work/lonely.json"
expect "a summary without its log" 2 "has no log beside it" -- "$mospec" report "$work/lonely.json" -o "$work/none.html"
cp "$run_dir/sc0a.csv" "$work/lonely.csv"
expect "a JSON that is not a run summary" 2 "not a run summary" -- "$mospec" report "$work/lonely.json" -o "$work/none.html"
check "nothing was written for them" test ! -e "$work/none.html"

finish report
