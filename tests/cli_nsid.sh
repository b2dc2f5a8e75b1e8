#!/usr/bin/env bash
# scan --hdf5 read by pycroscopy's own readers (pyNSID 0.0.7.2 and sidpy 0.12.8, their
# unchanged source in tests/vendor): every channel, trace and retrace, is an NSID main
# dataset that pyNSID's reader turns into a sidpy.Dataset with its units, quantity,
# spatial dimensions x and y in metres, the scene's keys as original_metadata and the
# run's figures as metadata. Exit 77 (skipped) where Debian's packages those readers
# import are missing (tests/vendor/README.md).
# usage: cli_nsid.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/tt_cli.sh"

need_python numpy h5py dask dask.distributed dill scipy matplotlib ipywidgets IPython ase

"$tiptap" scan "$src/scans/quick.ini" "$src/surfaces/polymer-blend.ini" --set scan.pixels=8 \
  --set scan.lines=3 -o "$tmp/s" --hdf5 -q 2>"$tmp/err" || { cat "$tmp/err"; bad "scan --hdf5 ran"; exit 1; }

cd "$tmp" && MPLBACKEND=Agg PYTHONPATH="$src/tests:$src/tests/vendor/pyNSID:$src/tests/vendor/sidpy" "$py" - "$tmp/s/scan.h5" <<'PY'
import sys

import h5py
import numpy as np
import sidpy
from pyNSID.io.hdf_utils import get_all_main, read_h5py_dataset

from tt_nsid import check, done


with h5py.File(sys.argv[1], "r") as f:
    m = f["Measurement_000"]
    images = [g[k] for g in (m[c] for c in m if c.startswith("Channel_")) for k in g if k not in ("x", "y")
              and isinstance(g[k], h5py.Dataset)]
    main = get_all_main(f)
    check(len(images) == 14 and sorted(d.name for d in main) == sorted(d.name for d in images),
          f"pyNSID finds every channel as a main dataset: {len(main)} of {len(images)}")
    scene = {k: v for k, v in m.attrs.items() if not k.startswith("run.")}
    figures = {k[4:]: v for k, v in m.attrs.items() if k.startswith("run.")}
    seen = set()
    for h in images:
        d = read_h5py_dataset(h)
        a = h.attrs
        what = h.name.split("/")[-1]
        seen.add(what)
        ok = isinstance(d, sidpy.Dataset) and np.array_equal(np.asarray(d), h[()], equal_nan=True)
        ok &= d.units == a["units"] and d.quantity == a["quantity"] and d.title == a["title"]
        ok &= d.data_type == sidpy.DataType.IMAGE and d.source == "tiptap scan"
        ok &= d.units == {"phase": "deg", "dissipation": "J", "peak_force": "N"}.get(a["quantity"], "m")
        check(ok, f"{what}: sidpy reads the image, {d.quantity} in {d.units}")
        y, x = d._axes[0], d._axes[1]
        xs, ys = h.dims[1][0][()], h.dims[0][0][()]
        ok = (x.name, y.name) == ("x", "y") and x.units == y.units == "m"
        ok &= x.dimension_type == y.dimension_type == sidpy.DimensionType.SPATIAL
        ok &= np.array_equal(x.values, xs) and np.array_equal(y.values, ys) and len(xs) == 8 and len(ys) == 3
        ok &= abs(xs[1] - xs[0] - (xs[-1] - xs[0]) / 7) < 1e-15 and xs[0] > 0
        check(ok, f"{what}: dimensions y, x in m, spatial, the pixel centres")
        check(d.original_metadata == scene and len(scene) > 40 and
              d.original_metadata["cantilever.spring_constant"] == m.attrs["cantilever.spring_constant"],
              f"{what}: the scene's {len(scene)} keys as original_metadata")
        check(d.metadata == figures and d.metadata["lines_finished"] == 3,
              f"{what}: the run's {len(figures)} figures as metadata")
    check(len(seen) == 14, f"the 7 channels trace and retrace read: {len(seen)}")
done()
PY
rc=$?
[ $rc -eq 0 ] && ok "pyNSID and sidpy read every channel" || bad "pyNSID/sidpy reading: exit $rc"
exit $fail
