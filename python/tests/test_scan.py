"""tiptap.scan() gives the images `tiptap scan` writes, bit for bit, with their units and
the same metadata."""

import os

import numpy as np
import pytest

import tiptap
from conftest import QUICK, QUICK_SET, read_gsf


@pytest.fixture(scope="module")
def quick():
    return tiptap.scan(QUICK, set=QUICK_SET, progress=False)


def test_every_channel_equals_the_programs_gsf_bit_for_bit(quick, quick_cli):
    files = sorted(f for f in os.listdir(quick_cli) if f.endswith(".gsf"))
    assert len(files) == 2 * len(quick.channels) == 14
    for name in quick.channels:
        for direction in ("trace", "retrace"):
            header, data = read_gsf(quick_cli / f"{name}_{direction}.gsf")
            image = quick[name, direction]
            assert image.dtype == np.float64 and image.shape == data.shape == (4, 16)
            # GSF stores float32: the program's cast of the same doubles, bit for bit
            assert image.astype("<f4").tobytes() == data.tobytes(), (name, direction)
            assert header["ZUnits"] == quick.units[name]
            assert header["XYUnits"] == "m"
            assert float(header["XReal"]) == pytest.approx(quick.size[0], rel=1e-9)


def test_metadata_is_the_gsf_header(quick, quick_cli):
    header, _ = read_gsf(quick_cli / "height_trace.gsf")
    extra = {k: v for k, v in header.items()
             if k not in ("XRes", "YRes", "XReal", "YReal", "XOffset", "YOffset", "XYUnits",
                          "ZUnits", "Title")}
    assert extra == quick.meta
    assert quick.meta["tiptap_version"] == tiptap.version
    assert quick.meta["scan.pixels"] == "16"
    assert quick.meta["lines_finished"] == quick.meta["lines_total"] == "4"


def test_geometry_and_run_figures(quick):
    # the library's order: 'error' is the error signal (amplitude - setpoint), 'amplitude'
    # the lock-in amplitude itself
    assert quick.channels == ["height", "error", "phase", "peak_force", "indentation",
                              "dissipation", "amplitude"]
    assert quick.units == {"height": "m", "error": "m", "phase": "deg", "peak_force": "N",
                           "indentation": "m", "dissipation": "J", "amplitude": "m"}
    assert quick.x.shape == (16,) and quick.y.shape == (4,)
    assert quick.x[0] == pytest.approx(quick.size[0] / 32)
    assert quick.run["lines_finished"] == quick.run["lines_total"] == 4
    assert quick.run["materials"] == ["matrix", "disk"]
    assert 0 < quick.run["cycles_integrated"] <= quick.run["cycles"]
    assert 0 <= quick.run["energy_balance"] < 1e-3
    assert np.isfinite(quick["height"]).all() and np.isfinite(quick["phase", "retrace"]).all()
    assert "[scan]" in quick.scene and "pixels = 16" in quick.scene


def test_channels_follow_the_librarys_table():
    table = tiptap.channel_table()
    names = [n for n, _, _ in table]
    assert names[:3] == ["height", "error", "phase"] and names[7] == "amplitude"
    assert len(table) == 30 and names[22] == "artefact" and names[26:28] == ["dilation", "certainty"]
    assert names[28:] == ["amplitude_2", "phase_2"] and table[29][1] == "deg"
    i = names.index("dissipation_hysteresis")
    assert names[i:i + 3] == ["dissipation_hysteresis", "dissipation_damping", "dissipation_viscous"]
    assert all(table[j][1] == "J" for j in range(i, i + 3))
    assert len(set(names)) == len(names)
    r = tiptap.scan(QUICK, set={**QUICK_SET, "scan.lines": "1", "lockin.harmonics": "3",
                                "scan.channels": "height, harmonic3, harmonic2_phase"},
                    progress=False)
    assert r.channels == ["height", "harmonic3", "harmonic2_phase"]
    assert r.units == {"height": "m", "harmonic3": "m", "harmonic2_phase": "deg"}
    assert r.harmonics == {"height": 0, "harmonic3": 3, "harmonic2_phase": 2}


def test_images_do_not_depend_on_threads(quick):
    one = tiptap.scan(QUICK, set=QUICK_SET, threads=1, progress=False)
    for name in quick.channels:
        for d in ("trace", "retrace"):
            assert one[name, d].tobytes() == quick[name, d].tobytes()


def test_scene_object_is_left_unchanged_by_overrides():
    s = tiptap.Scene(*QUICK, set=QUICK_SET)
    r = tiptap.scan(s, scan__lines=2, progress=False)
    assert r.run["lines_total"] == 2 and s["scan.lines"] == "4"


def test_progress_callback_sees_every_line():
    seen = []
    tiptap.scan(QUICK, set=QUICK_SET, threads=2, progress=lambda d, t: seen.append((d, t)))
    assert sorted(seen) == [(1, 4), (2, 4), (3, 4), (4, 4)]


def test_error_estimate_as_the_program_reports_it(quick_cli):
    r = tiptap.scan(QUICK, set=QUICK_SET, progress=False, error_estimate=True)
    # the image's hardest line (the profile line on a flat image), checked on at most a
    # fifth of the cycles the scan integrated
    assert 0 <= r.error["line"] < 4
    assert 0 < r.error["pixels"] <= r.error["pixels_line"]
    assert r.error["cycles"] > 0 and r.error["cpu_s"] >= 0
    assert 0 <= r.error["height_rms_m"] <= r.error["height_max_m"] < 1e-9
    assert r.error["tolerance"] > 0


def test_output_writes_the_programs_files_byte_for_byte(quick_cli, tmp_path):
    out = tmp_path / "py"
    tiptap.scan(QUICK, set=QUICK_SET, progress=False, output=str(out))
    written = sorted(os.listdir(out))
    # the images' files: scan.gwy, each channel's GSF and PNG, profile.csv (the program
    # adds scene.ini and the scope's files)
    assert "scan.gwy" in written and "height_trace.gsf" in written and "profile.csv" in written
    assert len(written) == 1 + 4 * 7 + 1
    for name in written:
        assert (out / name).read_bytes() == (quick_cli / name).read_bytes(), name
