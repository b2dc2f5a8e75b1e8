"""Bimodal AM-AM from Python (docs/physics.md, "Bimodal imaging"): mode 2's amplitude and
phase are channels of tiptap.scan() like the others, in its HDF5 file too, and they tell
the blend's stiff disks from its matrix as mode 1's phase does; and columns of
tiptap.approach()."""

import h5py
import numpy as np

import tiptap
from conftest import QUICK

BIMODAL = {"cantilever.modes": "2", "cantilever.mode2_free_amplitude": "0.5 nm",
           "solver.tier": "every", "scan.pixels": "8", "scan.lines": "2",
           "scan.size": "500 nm", "scan.line_rate": "40 Hz", "scan.retrace": "no",
           "scan.channels": "phase, amplitude_2, phase_2"}


def test_mode2_channels_in_python_and_hdf5(tmp_path):
    r = tiptap.scan(QUICK, set=BIMODAL, progress=False, hdf5=tmp_path / "b.h5")
    assert r.channels == ["phase", "amplitude_2", "phase_2"]
    assert r.units["amplitude_2"] == "m" and r.units["phase_2"] == "deg"
    a2, p2, p1 = r["amplitude_2"], r["phase_2"], r["phase"]
    assert a2.shape == (2, 8) and np.all(np.isfinite(a2)) and np.all(np.isfinite(p2))
    # the tip taps: mode 2 is damped below its free 0.5 nm, nowhere above it
    assert np.all(a2 > 0) and np.all(a2 < 0.5e-9)
    # line 0 crosses the matrix (mode 1 attractive, above 90 deg) and a disk (repulsive,
    # below): mode 2's lag falls with mode 1's, the disk stiffening mode 2
    disk, matrix = p1[0] < 90, p1[0] > 90
    assert disk.any() and matrix.any()
    assert p2[0][disk].max() < p2[0][matrix].min()
    with h5py.File(tmp_path / "b.h5", "r") as f:
        m = f["Measurement_000"]
        q = {g[k].attrs["quantity"] for g in (m[c] for c in m if c.startswith("Channel_"))
             for k in g if k not in ("x", "y") and isinstance(g[k], h5py.Dataset)}
    assert {"amplitude_2", "phase_2"} <= {v.decode() if isinstance(v, bytes) else v for v in q}


def test_mode2_columns_of_approach():
    far = {"cantilever.modes": "2", "cantilever.mode2_free_amplitude": "0.5 nm",
           "approach.from": "100 nm", "approach.to": "100 nm", "approach.points": "1"}
    t = tiptap.approach(QUICK, set=far, progress=False)
    assert t.units["amplitude_2"] == "m" and t.units["phase_2"] == "deg"
    # free: mode 2 at its drive's 0.5 nm, lagging 90 deg at resonance (0.0014 of it and
    # 0.3 deg: mode 1's share and the integration's error at the quick scene's tolerance)
    assert abs(t["amplitude_2"][0] / 0.5e-9 - 1) < 1.4e-3
    assert abs(t["phase_2"][0] - 90) < 0.3
    one = tiptap.approach(QUICK, set={"approach.points": "1"}, progress=False)
    assert "amplitude_2" not in one
