"""HDF5 files (docs/hdf5.md): the program's and Python's are the same bytes, and h5py
alone reads back every channel with its units, dimension scales and the metadata."""

import os

import h5py
import numpy as np
import pytest

import tiptap
from conftest import QUICK, QUICK_SET, cli, sets


@pytest.fixture(scope="module")
def both(tmp_path_factory):
    d = tmp_path_factory.mktemp("h5")
    cli("scan", *QUICK, *sets(QUICK_SET), "-o", d / "cli", "--hdf5", "-q")
    r = tiptap.scan(QUICK, set=QUICK_SET, progress=False, hdf5=d / "py.h5")
    return d, r


def test_python_writes_the_programs_file_byte_for_byte(both):
    d, _ = both
    assert (d / "py.h5").read_bytes() == (d / "cli" / "scan.h5").read_bytes()
    assert not [f for f in os.listdir(d) if ".tmp." in f]


def test_h5py_reads_every_channel_with_units_and_scales(both):
    d, r = both
    with h5py.File(d / "py.h5", "r") as f:
        assert f.attrs["file_kind"] == "tiptap scan"
        m = f["Measurement_000"]
        channels = [g for g in m if g.startswith("Channel_")]
        assert len(channels) == 2 * len(r.channels)
        seen = set()
        for g in (m[k] for k in m if k.startswith("Channel_")):
            (name,) = [k for k in g if k not in ("x", "y") and isinstance(g[k], h5py.Dataset)]
            data = g[name]
            q, direction = data.attrs["quantity"], data.attrs["direction"]
            seen.add((q, direction))
            assert name == f"{q}_{direction}"
            # float64, bit for bit the arrays Python returned
            assert data.dtype == np.float64
            assert data[()].tobytes() == r[q, direction].tobytes()
            assert data.attrs["units"] == r.units[q]
            assert data.attrs["data_type"] == "IMAGE"
            assert [dim.label for dim in data.dims] == ["y", "x"]
            y, x = data.dims[0][0], data.dims[1][0]
            assert x.attrs["units"] == y.attrs["units"] == "m"
            assert x.attrs["dimension_type"] == "SPATIAL"
            assert x[()].tobytes() == r.x.tobytes() and y[()].tobytes() == r.y.tobytes()
        assert seen == {(c, d) for c in r.channels for d in ("trace", "retrace")}


def test_metadata_and_scene_are_attributes(both):
    d, r = both
    with h5py.File(d / "py.h5", "r") as f:
        m = f["Measurement_000"]
        meta = {k: v for k, v in m.attrs.items() if not k.startswith("run.")}
        assert meta == r.meta
        assert list(meta)[:3] == ["tiptap_version", "lines_finished", "lines_total"]
        assert m.attrs["run.cycles"] == r.run["cycles"]
        assert m.attrs["run.instrument_time_s"] == r.run["instrument_time_s"]
        assert m.attrs["run.fast_axis"] == "x"
        assert m["scene"].asstr()[()] == r.scene


def test_an_unwritable_file_is_refused_before_the_run(tmp_path):
    calls = []
    with pytest.raises(tiptap.TiptapIOError, match="cannot write") as e:
        tiptap.scan(QUICK, set=QUICK_SET, hdf5=tmp_path / "missing" / "x.h5",
                    progress=lambda d, t: calls.append(d))
    assert calls == [] and str(tmp_path / "missing" / "x.h5") in str(e.value)


def test_an_interrupted_scan_writes_its_finished_lines(tmp_path):
    def stop(done, total):
        raise RuntimeError("stop")

    with pytest.raises(RuntimeError):
        tiptap.scan(QUICK, set={**QUICK_SET, "scan.lines": "20"}, threads=1, progress=stop,
                    hdf5=tmp_path / "part.h5")
    with h5py.File(tmp_path / "part.h5", "r") as f:
        m = f["Measurement_000"]
        assert m.attrs["lines_finished"] == "1" and m.attrs["lines_total"] == "20"
        h = m["Channel_000/height_trace"][()]
        assert np.isfinite(h[0]).all() and np.isnan(h[1:]).all()
    assert os.listdir(tmp_path) == ["part.h5"]


def test_a_rerun_without_hdf5_removes_the_stale_file(tmp_path):
    out = tmp_path / "scan"
    cli("scan", *QUICK, *sets({**QUICK_SET, "scan.lines": "1"}), "-o", out, "--hdf5", "-q")
    assert (out / "scan.h5").exists()
    p = cli("scan", *QUICK, *sets({**QUICK_SET, "scan.lines": "1"}), "-o", out, "-q")
    assert not (out / "scan.h5").exists()
    assert "scan.h5" in p.stderr and "earlier run" in p.stderr
