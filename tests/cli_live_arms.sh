#!/usr/bin/env bash
# The console's averaged preview on examples/viscoelastic-blend/arms.ini (a standard
# linear solid's disks, the envelope tier, noise on) in headless Chromium
# (tests/live_arms.py): after a change the preview row exists, marked and captioned as
# the averaged preview. Skipped (exit 77) only where Chromium is not installed.
# usage: cli_live_arms.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
live_in_browser live_arms.py "$src/scans/quick.ini" "$src/examples/viscoelastic-blend/scene.ini" \
  "$src/examples/viscoelastic-blend/arms.ini"
