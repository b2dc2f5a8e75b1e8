"""sweep(): the program's sweep table from the same library rows; the HDF5 file of a
sweep over its grid, from the program and from Python."""

import csv

import h5py
import numpy as np
import pytest

import tiptap
from conftest import QUICK, cli, sets, src
from test_tables import check_columns, g

BLEND = [src("surfaces", "polymer-blend.ini"), src("examples", "material-contrast", "scene.ini")]
VARY = {"cantilever.free_amplitude": "10nm,40nm", "approach.material": "matrix,disk",
        "feedback.setpoint": "30%:90%:3"}
POINT = {"z_nm": ("z", 1e9, 9), "amplitude_nm": ("amplitude", 1e9, 9), "phase_deg": ("phase", 1, 9),
         "dissipated_aJ": ("dissipated", 1e18, 9), "energy_residual": ("energy_residual", 1, 3),
         "regime": ("regime", 1, "s"), "settled": ("settled", 1, "d"), "found": ("found", 1, "s"),
         "setpoint_nm": ("setpoint", 1e9, 9), "approach.material": ("approach.material", 1, "s"),
         "cantilever.free_amplitude[m]": ("cantilever.free_amplitude", 1, 9),
         "combination": ("combination", 1, "d")}


def vary_args(vary):
    out = []
    for k, v in vary.items():
        out += ["--vary", f"{k}={v}"]
    return out


@pytest.fixture(scope="module")
def setpoint(tmp_path_factory):
    d = tmp_path_factory.mktemp("sweep")
    cli("sweep", *BLEND, *vary_args(VARY), "--run", "setpoint", "-o", d / "s.csv", "--hdf5", "-q")
    t = tiptap.sweep(BLEND, VARY, run="setpoint", progress=False, hdf5=d / "py.h5")
    return d, t


def test_setpoint_sweep_is_the_programs_table(setpoint):
    d, t = setpoint
    with open(d / "s.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == t.rows == 12
    check_columns(t, rows, POINT)
    assert t.units["cantilever.free_amplitude"] == "m" and t.units["z"] == "m"
    assert t.meta["run"] == "setpoint" and t.meta["combinations"] == 12


def test_the_sweeps_hdf5_spans_its_grid(setpoint):
    d, t = setpoint
    for name in ("s.h5", "py.h5"):
        with h5py.File(d / name, "r") as f:
            assert f.attrs["file_kind"] == "tiptap sweep"
            m = f["Measurement_000"]
            assert m.attrs["sweep.run"] == "setpoint" and m.attrs["sweep.combinations"] == "12"
            assert m.attrs["cantilever.spring_constant"] == "40 N/m"
            c = m["Channel_000"]
            amp = c["amplitude"]
            assert amp.shape == (2, 2, 3) and amp.attrs["units"] == "m"
            assert [dim.label for dim in amp.dims] == ["cantilever.free_amplitude",
                                                       "approach.material", "feedback.setpoint"]
            assert list(amp.dims[0][0][()]) == pytest.approx([10e-9, 40e-9])
            assert list(amp.dims[1][0].asstr()[()]) == ["matrix", "disk"]
            assert list(amp.dims[2][0][()]) == pytest.approx([0.3, 0.6, 0.9])
            # the grid in C order is the table's combination order
            flat = amp[()].reshape(-1)
            tol = 1e-8 if name == "s.h5" else 0  # the program's file: its CSV's 9 digits
            assert np.allclose(flat, t["amplitude"], rtol=tol, atol=0)
            assert list(c["regime"].asstr()[()].reshape(-1)) == list(t["regime"])
    with h5py.File(d / "py.h5", "r") as f:
        assert f["Measurement_000/Channel_000/z"][()].reshape(-1).tobytes() == t["z"].tobytes()


def test_an_approach_sweep_has_a_row_dimension(tmp_path):
    over = {"approach.points": "6"}
    t = tiptap.sweep(src("examples", "seed-fig4a", "scene.ini"),
                     {"cantilever.quality_factor": [20, 40]}, run="approach", set=over,
                     progress=False, hdf5=tmp_path / "a.h5")
    assert t.rows == 2 * 12 and list(np.unique(t["combination"])) == [1, 2]
    with h5py.File(tmp_path / "a.h5", "r") as f:
        z = f["Measurement_000/Channel_000/z"]
        assert z.shape == (2, 12) and [d.label for d in z.dims] == ["cantilever.quality_factor", "row"]
        assert z[()].reshape(-1).tobytes() == t["z"].tobytes()


def test_a_scan_sweep_summarises_each_material(tmp_path):
    over = {"scan.pixels": "8", "scan.lines": "2"}
    t = tiptap.sweep(QUICK, {"feedback.setpoint": "70%,85%"}, run="scan", set=over, progress=False)
    assert list(t["material"]) == ["all", "matrix", "disk"] * 2
    assert list(t["folder"]) == ["0001"] * 3 + ["0002"] * 3
    assert t.units["height_mean"] == "m" and t.units["phase_mean"] == "deg"
    cli("sweep", *QUICK, *sets(over), "--vary", "feedback.setpoint=70%,85%", "--run", "scan",
        "-o", tmp_path / "s.csv", "--hdf5", "-q")
    with open(tmp_path / "s.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    check_columns(t, rows, {"height_mean_nm": ("height_mean", 1e9, 9), "pixels": ("pixels", 1, "d"),
                            "phase_contrast_deg": ("phase_contrast", 1, 9),
                            "material": ("material", 1, "s")})
    # each combination's folder has its scan.h5
    for k in ("0001", "0002"):
        with h5py.File(tmp_path / "s" / k / "scan.h5", "r") as f:
            assert f["Measurement_000"].attrs["feedback.setpoint"] in ("70%", "85%", "70 %", "85 %")


def test_a_bad_vary_is_the_programs_message(tmp_path):
    p = cli("sweep", *BLEND, "--vary", "feedback.setpoint=10 Hz,20 Hz", "-o", tmp_path / "x.csv",
            check=False)
    with pytest.raises(tiptap.SceneError) as e:
        tiptap.sweep(BLEND, {"feedback.setpoint": "10 Hz,20 Hz"}, progress=False)
    assert "tiptap: " + str(e.value) == p.stderr.strip()
    with pytest.raises(tiptap.SceneError, match="is not steady, setpoint"):
        tiptap.sweep(BLEND, {"feedback.setpoint": "50%"}, run="steadyish")
