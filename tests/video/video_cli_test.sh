#!/usr/bin/env bash
# `mospec run --video` from the outside (issue #17 item 1): an .mp4 and a .gif
# that ffmpeg decodes, 30 frames per simulated second, not blank, the robot
# moving between the first and the last frame, the same frames from the same
# run; and the failures (unknown format, a directory that does not exist, no
# ffmpeg, ffmpeg failing, a bad --video-size) exit 2 with a message naming the
# fix, before anything is simulated, and leave no file behind.
# Usage: video_cli_test.sh MOSPEC SOURCE_DIR
SRC="$2"
source "$SRC/tests/support/cli_lib.sh"
cd "$SRC" || exit 1
command -v ffprobe >/dev/null || { echo "SKIP: needs ffmpeg's ffprobe (scripts/install-deps)"; exit 77; }

# One simulated second of SC1 (the base turns towards the table's edge), small.
run() { "$mospec" run models/sc1.json --sim --interpret --duration 1 --video-size 160x120 "$@"; }
frames() { ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1"; }
# Frame N (0-based) of a video as 32x24 grey bytes, one decimal number per line.
grey() { ffmpeg -v error -i "$1" -vf "select=eq(n\,$2),scale=32:24" -frames:v 1 -f rawvideo -pix_fmt gray - | od -An -v -tu1 | tr -s ' ' '\n' | grep -v '^$'; }
variance() { awk '{ s += $1; s2 += $1 * $1; n++ } END { printf "%d\n", s2 / n - (s / n) ^ 2 }'; }
# How many of the 768 grey pixels differ by more than 8 levels.
changed() { paste <(grey "$1" "$2") <(grey "$1" "$3") | awk '{ d = $1 - $2; if (d > 8 || d < -8) c++ } END { print c + 0 }'; }

for ext in mp4 gif; do
  out="$work/sc1.$ext"
  expect "--video .$ext" 0 "^mospec: wrote 31 frames to .*sc1\.$ext" -- run --video "$out"
  n=$(frames "$out")
  # 1 s at 30 frames per second, from t = 0: 31 frames (a GIF may merge two identical ones).
  check ".$ext decodes with 31 frames (got $n)" test "${n:-0}" -ge 30 -a "${n:-0}" -le 31
  v=$(grey "$out" 0 | variance)
  check ".$ext: the first frame is not blank (grey variance $v)" test "${v:-0}" -gt 100
  c=$(changed "$out" 0 $((n - 1)))
  check ".$ext: the robot moved between the first and the last frame ($c of 768 pixels changed)" \
    test "${c:-0}" -gt 8
  check ".$ext: no temporary left" test -z "$(find "$work" -name '.sc1.*.tmp.*')"
done
codec=$(ffprobe -v error -select_streams v:0 -show_entries stream=codec_name,width,height -of csv=p=0 "$work/sc1.mp4")
check ".mp4 is H.264 at 160x120 (got $codec)" test "$codec" = "h264,160,120"

# Rendering does not touch the simulation: the same log with and without a video.
expect "--log with --video" 0 "" -- run --video "$work/logged.mp4" --log "$work/with.csv"
expect "--log without --video" 0 "" -- \
  "$mospec" run models/sc1.json --interpret --duration 1 --log "$work/without.csv"
# --video-size and --video-camera act only on a video: alone they are refused,
# not ignored (issue #33 item 10).
expect "--video-size without --video" 2 "^mospec: --video-size requires --video" -- \
  "$mospec" run models/sc1.json --interpret --duration 1 --video-size 160x120
check "the log is the same with and without a video" cmp -s "$work/with.csv" "$work/without.csv"

# The second camera, from above.
expect "--video-camera top" 0 "^mospec: wrote 31 frames" -- run --video "$work/top.mp4" --video-camera top
check "the top camera shows another picture" \
  test "$(paste <(grey "$work/top.mp4" 0) <(grey "$work/sc1.mp4" 0) | awk '{ d = $1 - $2; if (d > 8 || d < -8) c++ } END { print c + 0 }')" -gt 100
expect "--video-camera side" 2 "^mospec: --video-camera: side not in \{corner,top\}" -- \
  run --video "$work/out.mp4" --video-camera side

# The same run, the same frames (decoded, frame by frame).
expect "--video again" 0 "" -- run --video "$work/again.mp4"
check "the same run gives the same frames" \
  cmp -s <(ffmpeg -v error -i "$work/sc1.mp4" -f framemd5 -) <(ffmpeg -v error -i "$work/again.mp4" -f framemd5 -)

# Failures: exit 2, named fix, nothing simulated, nothing written.
expect "--video .avi" 2 "^mospec: error: --video '.*run\.avi': unknown video format '\.avi'; name the file \.mp4 \(H\.264\) or \.gif" -- \
  run --video "$work/run.avi"
check ".avi: nothing simulated" test "$(grep -c 'mospec: ran' "$work/stderr.txt")" -eq 0
expect "--video in a missing directory" 2 \
  "^mospec: error: cannot write the video '.*/missing/run\.mp4': No such file or directory \(its directory '.*/missing' must exist and be writable\)" -- \
  run --video "$work/missing/run.mp4"
mkdir "$work/dir.mp4"
expect "--video a directory" 2 "^mospec: error: cannot write the video '.*dir\.mp4': it is a directory" -- \
  run --video "$work/dir.mp4"
expect "--video without an extension" 2 "^mospec: error: --video '.*/run': the file name has no extension; name the file \.mp4" -- \
  run --video "$work/run"
mkdir -p "$work/empty-path" "$work/out"
expect "no ffmpeg on PATH" 2 \
  "^mospec: error: --video needs ffmpeg, and 'ffmpeg' cannot be started \(No such file or directory\): install Debian's ffmpeg package \(scripts/install-deps\) or set MOSPEC_FFMPEG to its path" -- \
  env PATH="$work/empty-path" "$mospec" run models/sc1.json --sim --interpret --duration 1 --video "$work/out/run.mp4"
check "no ffmpeg: nothing simulated" test "$(grep -c 'mospec: ran' "$work/stderr.txt")" -eq 0
expect "MOSPEC_FFMPEG that does not exist" 2 "'$work/none/ffmpeg' cannot be started" -- \
  env MOSPEC_FFMPEG="$work/none/ffmpeg" "$mospec" run models/sc1.json --sim --interpret --duration 1 --video "$work/out/run.mp4"
# ffmpeg that fails (exits at once): the previous video is left as it was.
echo "previous" > "$work/out/kept.mp4"
expect "ffmpeg fails" 2 "^mospec: error: encoding the video '.*kept\.mp4' failed: ffmpeg exited with status 1" -- \
  env MOSPEC_FFMPEG=false "$mospec" run models/sc1.json --sim --interpret --duration 1 --video "$work/out/kept.mp4"
check "ffmpeg fails: the old file is untouched" test "$(cat "$work/out/kept.mp4")" = previous
check "failures leave nothing behind" test "$(ls -A "$work/out")" = kept.mp4
for size in 640x481 15x16 8192x480 640 axb 640x480x2; do
  expect "--video-size $size" 2 "^mospec: --video-size" -- run --video "$work/out/x.mp4" --video-size "$size"
done

finish video-cli
