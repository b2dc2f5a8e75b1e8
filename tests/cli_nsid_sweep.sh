#!/usr/bin/env bash
# sweep --hdf5 read by pycroscopy's own readers (pyNSID 0.0.7.2 and sidpy 0.12.8, in
# tests/vendor) as tests/cli_nsid.sh reads a scan: every number column of the table is
# an NSID main dataset that pyNSID's reader turns into a sidpy.Dataset with its units,
# a dimension per varied key (a text key's levels numbered 0 .. n - 1, its texts kept
# as the dimension's first scale) and the approach's rows, the base scene's keys as
# original_metadata and the sweep's own as metadata; the text columns stay plain.
# Exit 77 (skipped) where Debian's packages those readers import are missing.
# usage: cli_nsid_sweep.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/tt_cli.sh"

need_python numpy h5py dask dask.distributed dill scipy matplotlib ipywidgets IPython ase

cd "$tmp" || exit 1
"$tiptap" sweep "$src/scans/quick.ini" --vary "feedback.setpoint=70 %,80 %,90 %" \
  --vary solver.method=dopri5,rk4 --hdf5 -o steady.csv -q 2>err || { cat err; bad "steady sweep ran"; exit 1; }
"$tiptap" sweep "$src/examples/seed-fig4a/scene.ini" --vary cantilever.quality_factor=20,40 --run approach \
  --set approach.points=6 --hdf5 -o approach.csv -q 2>err || { cat err; bad "approach sweep ran"; exit 1; }

MPLBACKEND=Agg PYTHONPATH="$src/tests:$src/tests/vendor/pyNSID:$src/tests/vendor/sidpy" "$py" - <<'PY'
import csv
import sys

import h5py
import numpy as np
import sidpy
from pyNSID.io.hdf_utils import get_all_main, read_h5py_dataset

from tt_nsid import check, done


for name, keys, shape in (("steady", ["feedback.setpoint", "solver.method"], (3, 2)),
                          ("approach", ["cantilever.quality_factor", "row"], (2, 12))):
    with h5py.File(name + ".h5", "r") as f:
        c = f["Measurement_000/Channel_000"]
        columns = [k for k in c if isinstance(c[k], h5py.Dataset) and k not in keys
                   and not k.endswith(".level")]
        numbers = [k for k in columns if c[k].dtype.kind == "f"]
        main = sorted(d.name.split("/")[-1] for d in get_all_main(f))
        check(main == sorted(numbers) and len(numbers) >= 10 and len(columns) > len(numbers),
              f"{name}: pyNSID finds the {len(numbers)} number columns as main datasets, "
              f"not the {len(columns) - len(numbers)} text ones")
        scene = dict(f["Measurement_000"].attrs)
        for k in numbers:
            h = c[k]
            d = read_h5py_dataset(h)
            ok = isinstance(d, sidpy.Dataset) and np.array_equal(np.asarray(d), h[()], equal_nan=True)
            ok &= d.shape == shape and d.units == h.attrs["units"] and d.quantity == k
            ok &= d.source == "tiptap sweep"
            axes = [d._axes[i] for i in range(len(shape))]
            ok &= [a.name for a in axes] == keys
            for i, a in enumerate(axes):
                s = h.dims[i][0]
                want = np.arange(len(s)) if s.dtype.kind == "O" else s[()]
                ok &= np.array_equal(a.values, want) and len(a.values) == shape[i]
            ok &= d.original_metadata == scene and d.metadata["sweep.run"] == name
            check(ok, f"{name}: {k} in {d.units or '(no unit)'} over {', '.join(keys)}")
        if name == "steady":
            amp = c["amplitude"]
            check(list(amp.dims[1][0].asstr()[()]) == ["dopri5", "rk4"],
                  "steady: the text key's values stay its dimension's first scale")
            rows = list(csv.DictReader(open("steady.csv")))
            flat = amp[()].reshape(-1)
            check(np.allclose(flat, [float(r["amplitude_nm"]) * 1e-9 for r in rows], rtol=1e-8),
                  "steady: the grid in C order is the table's combination order")
done()
PY
[ $? -eq 0 ] || fail=1
exit $fail
