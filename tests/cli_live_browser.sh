#!/usr/bin/env bash
# tiptap live in a real browser: Debian's headless Chromium driven over the DevTools
# protocol (tests/live_browser.py): the page loads, a gain moves, the scope changes, the
# oscillation warning appears at a high gain and clears at a good one. Skipped (exit 77)
# only where Chromium is not installed; CI installs it (.ci/run). With TT_LIVE_SHOTS=DIR
# the screenshots are kept there (docs/live.md says how the committed ones were made).
# usage: cli_live_browser.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ] || [ ! -x /usr/bin/python3 ]; then
  echo "skip: the browser test needs Debian's chromium and python3 (apt-get install chromium python3)"
  exit 77
fi
shots=${TT_LIVE_SHOTS:-$tmp}
mkdir -p "$shots"
# the teaching scene: the 20 nm grating, 64 pixels, 16 lines at 4 Hz, thermal and
# detector noise
live_start "$src/examples/feedback-tuning/common.ini" "$src/surfaces/grating.ini" \
  --set scan.lines=16 --set scan.line_rate=4Hz
if [ -z "$port" ]; then
  bad "the server did not start: $(cat "$tmp/err")"
  exit 1
fi
/usr/bin/python3 "$(dirname "$0")/live_browser.py" "$chromium" "http://127.0.0.1:$port/" "$shots" || fail=1
kill -INT "$pid"
wait "$pid"
rc=$?
[ $rc -eq 130 ] && ok "the server stopped on Ctrl-C" || bad "the server's exit: $rc; $(cat "$tmp/err")"
exit $fail
