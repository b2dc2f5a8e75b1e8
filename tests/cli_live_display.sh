#!/usr/bin/env bash
# The console's display in headless Chromium (tests/live_display.py, over the DevTools
# protocol) at a projector's 1024 x 768: text size, fields that show the value in force,
# the images' colour range and line flatten read back from their pixels, the scope's
# hold, cursor, zoom, time axis and reference. Skipped (exit 77) only where Chromium is
# not installed; CI installs it (.ci/run). With TT_LIVE_SHOTS=DIR the screenshots are kept
# there (docs/live.md, "The display").
# usage: cli_live_display.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
# the teaching scene: the 20 nm grating, 64 pixels, 32 lines at 4 Hz (room for a band of
# ringing lines and steady ones after it in one frame), thermal and detector noise; on the
# envelope tier (common.ini gives the averaged one): the checks tell the scan's own lines
# from the averaged preview's by their tier, and a change's preview needs a tier above it
live_in_browser live_display.py "$src/scans/standard.ini" "$src/surfaces/grating.ini" \
  "$src/examples/feedback-tuning/common.ini" --set scan.lines=32 --set scan.line_rate=4Hz \
  --set solver.tier=envelope
