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
# the teaching scene: the 20 nm grating, 64 pixels, 16 lines at 4 Hz, thermal and
# detector noise
live_in_browser live_browser.py "$src/examples/feedback-tuning/common.ini" "$src/surfaces/grating.ini" \
  --set scan.lines=16 --set scan.line_rate=4Hz
