#!/usr/bin/env bash
# tiptap live's lessons, pause, step and idle (docs/live.md, "Lessons", "Pause, step and
# idle"): bad lesson input refused in one line before anything runs; over the WebSocket
# (tests/live_pause.py) no CPU with no page open or paused, one line a step, the status
# before a line is judged, amplitude and peak-force images; a lesson's locks held by the
# server and its save read back (tests/live_lesson.py); the lesson's page in headless
# Chromium at 1024 x 768 (tests/live_lesson_page.py; that part skipped where Chromium is
# missing). With TT_LIVE_SHOTS=DIR the page's screenshot is kept there.
# usage: cli_live_lesson.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
[ -x /usr/bin/python3 ] || { echo "skip: needs python3"; exit 77; }
here=$(dirname "$(realpath "$0")")
scene="$src/scans/standard.ini $src/surfaces/grating.ini $src/examples/feedback-tuning/common.ini"

# bad input: one line naming the file, its line and key, and what is expected; nothing runs
lesson_err() { # name, fragment, lesson text, extra args...
  local name=$1 frag=$2 text=$3; shift 3
  printf '%b' "$text" >"$tmp/bad.ini"
  expect_error "$name" "$frag" "$tiptap" live --port 0 "$@"
}
lesson_err "an unknown control" "bad.ini:3: [lesson] hide: 'frobnicate' is not a control; expected sample" \
  "[lesson]\ntitle = t\nhide = noise, frobnicate\nscene = $src/scans/standard.ini\n" --lesson "$tmp/bad.ini"
lesson_err "an unknown key" "bad.ini:3: [lesson] colour: unknown key; expected title, instructions" \
  "[lesson]\ntitle = t\ncolour = red\n" --lesson "$tmp/bad.ini" $scene
lesson_err "no title" "bad.ini: [lesson] title: missing" "[lesson]\nhide = noise\n" --lesson "$tmp/bad.ini" $scene
lesson_err "a missing scene file" "bad.ini:3: [lesson] scene: cannot read $tmp/nothere.ini" \
  "[lesson]\ntitle = t\nscene = nothere.ini\n" --lesson "$tmp/bad.ini"
lesson_err "a bad lock as a scene argument" "bad.ini:2: [lesson] lock: 'sizes' is not a control" \
  "[lesson]\nlock = sizes\ntitle = t\n" "$tmp/bad.ini" $scene
expect_error "a missing lesson" "$tmp/none.ini: cannot read the lesson: No such file" \
  "$tiptap" live --port 0 --lesson "$tmp/none.ini" $scene

# pause, step, idle, the status and the images
live_start $scene --set scan.lines=16 --set scan.line_rate=8Hz
[ -n "$port" ] || { bad "the server did not start: $(cat "$tmp/err")"; exit 1; }
/usr/bin/python3 "$here/live_pause.py" "$port" "$pid" || fail=1
kill -INT "$pid"; wait "$pid"
[ $? -eq 130 ] && ok "the server stopped on Ctrl-C" || bad "the server's exit; $(cat "$tmp/err")"

# a lesson: its locks on the server, its save
cat >"$tmp/lesson.ini" <<LESSON
[lesson]
title = Tuning the I gain
instructions = Raise the I gain until the scope rings.
    Then take the warning's suggestion.
scene = $scene
hide = noise, tier
lock = scan_size, pixels
LESSON
live_start --lesson "$tmp/lesson.ini" --set scan.lines=16 --set scan.line_rate=8Hz
[ -n "$port" ] || { bad "the lesson's server did not start: $(cat "$tmp/err")"; exit 1; }
/usr/bin/python3 "$here/live_lesson.py" "$port" "$tmp/saved.ini" || fail=1
kill -INT "$pid"; wait "$pid"
# the saved lesson, as a scene argument: the same lesson at the gain it was saved with
live_start "$tmp/saved.ini"
if [ -z "$port" ]; then
  bad "the saved lesson did not start: $(cat "$tmp/err")"
else
  /usr/bin/python3 - "$port" "$here" <<'PY' || fail=1
import sys
sys.path.insert(0, sys.argv[2])
from live_ws import WS
ws = WS(int(sys.argv[1]))
m = ws.recv_type("controls")
c = {k["name"]: k for k in m["controls"]}
good = (m["lesson"]["title"] == "Tuning the I gain" and c["feedback.integral_gain"]["value"] == "2000"
        and c["scan.size"]["locked"] and c["noise"]["hidden"])
print(("ok " if good else "FAIL ") + "the saved lesson read back: %s, I gain %s, size locked, noise hidden"
      % (m["lesson"]["title"], c["feedback.integral_gain"]["value"]))
sys.exit(0 if good else 1)
PY
  kill -INT "$pid"; wait "$pid"
fi

# the lesson's page
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
  echo "skip: the page's part needs Debian's chromium"
else
  live_start --lesson "$tmp/lesson.ini" --set scan.lines=16 --set scan.line_rate=1Hz
  shots=${TT_LIVE_SHOTS:-$tmp}
  mkdir -p "$shots"
  shots=$(realpath "$shots")
  (cd "$here" && /usr/bin/python3 live_lesson_page.py "$chromium" "http://127.0.0.1:$port/" "$shots") || fail=1
  kill -INT "$pid"; wait "$pid"
fi
exit $fail
