#!/usr/bin/env bash
# tiptap live's pause, step and idle, its status before a line is judged, and its
# amplitude and peak-force images (tests/live_pause.py over the WebSocket).
# usage: cli_live_lesson.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
[ -x /usr/bin/python3 ] || { echo "skip: needs python3"; exit 77; }
live_start "$src/scans/standard.ini" "$src/surfaces/grating.ini" \
  "$src/examples/feedback-tuning/common.ini" --set scan.lines=16 --set scan.line_rate=8Hz
[ -n "$port" ] || { bad "the server did not start: $(cat "$tmp/err")"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/live_pause.py" "$port" "$pid" || fail=1
kill -INT "$pid"
wait "$pid"
rc=$?
[ $rc -eq 130 ] && ok "the server stopped on Ctrl-C" || bad "the server's exit: $rc; $(cat "$tmp/err")"
exit $fail
