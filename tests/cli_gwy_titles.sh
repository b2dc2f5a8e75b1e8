#!/usr/bin/env bash
# scan.gwy read by AFMReader's own .gwy reader (AFMReader 0.0.7, its unchanged source in
# tests/vendor), which TopoStats loads .gwy files with: a channel is selected by its
# exact title (AFMReader/gwy.py, gwy_get_channels), and TopoStats' default channel is
# "Height". Every channel, trace and retrace, loads by the title tiptap gives it, with
# the image and pixel size tiptap wrote. Exit 77 (skipped) where Debian's python3-loguru
# or python3-ruamel.yaml, which AFMReader imports, is missing.
# usage: cli_gwy_titles.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/tt_cli.sh"

need_python numpy h5py loguru ruamel.yaml
# what pip would write beside an installed AFMReader: its __init__ asks for its version
mkdir -p "$tmp/site/AFMReader-0.0.7.dist-info"
printf 'Metadata-Version: 2.1\nName: AFMReader\nVersion: 0.0.7\n' >"$tmp/site/AFMReader-0.0.7.dist-info/METADATA"

# square images: AFMReader shapes the data (xres, yres)
"$tiptap" scan "$src/scans/quick.ini" "$src/surfaces/polymer-blend.ini" --set scan.pixels=8 \
  --set scan.lines=8 -o "$tmp/s" --hdf5 -q 2>"$tmp/err" || { cat "$tmp/err"; bad "scan ran"; exit 1; }

cd "$tmp" && PYTHONPATH="$src/tests/vendor/AFMReader:$tmp/site" "$py" - "$tmp/s" <<'PY'
import sys

import h5py
import numpy as np
from loguru import logger

from AFMReader.gwy import load_gwy

logger.remove()  # AFMReader logs every component it reads
fail = 0


def check(ok, what):
    global fail
    print(("ok   " if ok else "FAIL ") + what)
    fail |= not ok


d = sys.argv[1]
with h5py.File(f"{d}/scan.h5", "r") as f:
    m = f["Measurement_000"]
    images = {}
    for g in (m[c] for c in m if c.startswith("Channel_")):
        for k in g:
            if k not in ("x", "y") and isinstance(g[k], h5py.Dataset):
                images[(g[k].attrs["quantity"], g[k].attrs["direction"])] = (g[k][()], g[k].attrs["units"])
    pixel = 1e9 * (m["Channel_000/x"][1] - m["Channel_000/x"][0])

image, px = load_gwy(f"{d}/scan.gwy", channel="Height")
h = images[("height", "trace")][0]
check(np.array_equal(image, h * 1e9) and abs(px - pixel) < 1e-9 * pixel,
      f"channel 'Height' (TopoStats' default) is the height trace, in nm, {px:.4g} nm a pixel")
titles = {"height": "Height", "error": "Error", "phase": "Phase", "peak_force": "Peak force",
          "indentation": "Indentation", "dissipation": "Dissipation", "amplitude": "Amplitude"}
for (q, r), (data, units) in sorted(images.items()):
    title = titles[q] + (" (retrace)" if r == "retrace" else "")
    try:
        image, _ = load_gwy(f"{d}/scan.gwy", channel=title)
        check(np.array_equal(image, data * 1e9), f"'{title}': {q} {r}")
    except ValueError as e:
        check(False, f"'{title}': {e}")
check(len(images) == 14, f"{len(images)} images, 7 channels trace and retrace")
sys.exit(fail)
PY
rc=$?
[ $rc -eq 0 ] && ok "AFMReader selects every channel by its title" || bad "AFMReader: exit $rc"
exit $fail
