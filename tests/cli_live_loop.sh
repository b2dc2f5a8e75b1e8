#!/usr/bin/env bash
# The console's loop panel in headless Chromium (tests/live_loop.py, over the DevTools
# protocol) at 1024 x 768: the model's phase margin at three gains, the Bode plot redrawn,
# the suggestions, auto-tune's end at a 55 to 65 deg margin and its log. Skipped (exit 77)
# only where Chromium is not installed; CI installs it (.ci/run). With TT_LIVE_SHOTS=DIR
# the screenshot is kept there (docs/live.md, "The loop").
# usage: cli_live_loop.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
# the teaching scene, 16 lines at 8 Hz (auto-tune waits two lines a step)
live_in_browser live_loop.py "$src/scans/standard.ini" "$src/surfaces/grating.ini" \
  "$src/examples/feedback-tuning/common.ini" --set scan.lines=16 --set scan.line_rate=8Hz
