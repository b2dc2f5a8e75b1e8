#!/usr/bin/env bash
# tiptap live's benches (docs/live.md, "Force curve and thermal tune"): over the WebSocket,
# a lesson that hides a bench's knobs hides its panel and the server refuses its run; in
# headless Chromium at 1024 x 768 (tests/live_bench.py) a refused ramp value restores its
# field, the force panel's pull-off and jump-in equal `tiptap force`'s on the same scene and
# ramp, the tune's k is within its stated uncertainty of the scene's and equals `tiptap
# tune`'s; on the same scene as a beam of two modes (tests/live_bench_modes.py) the tune
# sends and shows both, each mode's f, Q and k equal to `tiptap tune`'s. Skipped (77)
# where Chromium or python3 is missing. With TT_LIVE_SHOTS=DIR the screenshots are kept
# there.
# usage: cli_live_bench.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
[ -x /usr/bin/python3 ] || { echo "skip: needs python3"; exit 77; }
here=$(dirname "$(realpath "$0")")
scene="$src/examples/feedback-tuning/common.ini $src/surfaces/grating.ini"

# a lesson hiding the ramp's knobs: no force panel, its run refused; the tune still offered
cat >"$tmp/lesson.ini" <<LESSON
[lesson]
title = Tapping only
scene = $scene
hide = speed, range
LESSON
live_start --lesson "$tmp/lesson.ini" --set scan.lines=16 --set scan.line_rate=8Hz
[ -n "$port" ] || { bad "the lesson's server did not start: $(cat "$tmp/err")"; exit 1; }
/usr/bin/python3 - "$port" "$here" <<'PY' || fail=1
import sys
sys.path.insert(0, sys.argv[2])
from live_ws import WS
ws = WS(int(sys.argv[1]))
m = ws.recv_type("controls")
good = m["benches"] == {"force": False, "tune": True}
print(("ok " if good else "FAIL ") + "the lesson hides the force bench, not the tune: %s" % m["benches"])
ws.send("force")
r = ws.recv_type("reply")
refused = not r["ok"] and "hides the force curve" in r["error"]
print(("ok " if refused else "FAIL ") + "its run refused: %s" % r["error"])
sys.exit(0 if good and refused else 1)
PY
kill -INT "$pid"; wait "$pid"

# the figures the page must show: the command line's on the same scene and ramp
out=$("$tiptap" force $scene --set force.range=30nm -q -o "$tmp/force.csv") || bad "tiptap force failed"
pulloff=$(sed -n 's/^pulloff_force_nN = //p' <<<"$out")
jumpin=$(sed -n 's/^jumpin_force_nN = //p' <<<"$out")
k=$(sed -n 's/^spring_constant_N_per_m = //p' <<<"$out")
ktune=$("$tiptap" tune $scene -q -o "$tmp/tune.csv" | sed -n 's/^k_N_per_m = //p') || bad "tiptap tune failed"

chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
  echo "skip: the page's part needs Debian's chromium"
  exit 77
fi
live_start $scene --set scan.lines=16 --set scan.line_rate=8Hz
[ -n "$port" ] || { bad "the server did not start: $(cat "$tmp/err")"; exit 1; }
shots=${TT_LIVE_SHOTS:-$tmp}
mkdir -p "$shots"
shots=$(realpath "$shots")
(cd "$here" && /usr/bin/python3 live_bench.py "$chromium" "http://127.0.0.1:$port/" "$shots" \
  "${pulloff}e-9" "${jumpin}e-9" "$k" "$ktune") || fail=1
kill -INT "$pid"; wait "$pid"
[ $? -eq 130 ] && ok "the server stopped on Ctrl-C" || bad "the server's exit; $(cat "$tmp/err")"

# two modes (the every-cycle tier scans them, at 32 Hz lines so that the page's first
# two scopes come in time under the sanitizers: 97 s a line at 8 Hz there): Nyquist
# must clear mode 2's 1.88 MHz, 16 samples a 300 kHz period
two="--set cantilever.modes=2 --set tune.samples_per_cycle=16 --set solver.tier=every"
"$tiptap" tune $scene $two -q -o "$tmp/tune2.csv" >"$tmp/tune2.txt" || bad "tiptap tune of two modes failed"
live_start $scene $two --set scan.lines=16 --set scan.line_rate=32Hz
[ -n "$port" ] || { bad "the two-mode server did not start: $(cat "$tmp/err")"; exit 1; }
(cd "$here" && /usr/bin/python3 live_bench_modes.py "$chromium" "http://127.0.0.1:$port/" "$shots" \
  "$tmp/tune2.txt") || fail=1
kill -INT "$pid"; wait "$pid"
[ $? -eq 130 ] && ok "the two-mode server stopped on Ctrl-C" || bad "the server's exit; $(cat "$tmp/err")"
exit $fail
