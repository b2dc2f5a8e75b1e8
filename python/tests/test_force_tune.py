"""force(), tune() and force_volume(): the same run layer as `tiptap force` (and its
--volume) and `tiptap tune` (the program's CSV, figures and maps from the same calls),
and their physics: the largest adhesion on a slow ramp is each material's
Maugis-Dugdale least load (tiptap.contact's), on a curve and over a map, and the tune
recovers the lever's k, f0 and Q within three of its own stated errors."""

import csv

import numpy as np
import pytest

import tiptap
from conftest import cli, sets, src

BLEND = [src("surfaces", "polymer-blend.ini"), src("examples", "force-curves", "scene.ini")]
SOFT = {"cantilever.spring_constant": "0.1 N/m", "cantilever.resonance_frequency": "10 kHz",
        "cantilever.quality_factor": "20", "noise.temperature": "300 K", "tune.duration": "0.4 s"}


def figures(stdout):
    return {k: float(v) for k, v in (line.split(" = ", 1) for line in stdout.splitlines())}


@pytest.mark.parametrize("material", ["matrix", "disk"])
def test_force_adhesion_is_the_least_load(material):
    t = tiptap.force(BLEND, set={"force.material": material}, progress=False)
    least = -tiptap.contact(BLEND, material=material).meta["pulloff_load_N"]
    assert least > 1e-9
    assert t.meta["adhesion"] == pytest.approx(least, rel=2e-3)
    # the largest attraction of the retract's rows is the figure (rows are a subset)
    retract = t["leg"] == "retract"
    assert -t["force"][retract].min() <= t.meta["adhesion"] * (1 + 1e-12)
    assert -t["force"][retract].min() == pytest.approx(t.meta["adhesion"], rel=0.02)
    # the pull-off comes after the least load: no larger attraction there
    assert -t.meta["pulloff_force"] <= t.meta["adhesion"]
    assert t.units["z"] == "m" and t.units["force"] == "N" and set(t["leg"]) == {"approach", "retract"}


def test_force_is_the_programs(tmp_path):
    over = {"force.material": "disk", "noise.temperature": "300 K"}
    p = cli("force", *BLEND, *sets(over), "-o", tmp_path / "f.csv", "-q")
    t = tiptap.force(BLEND, set=over, progress=False)
    with open(tmp_path / "f.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert t.rows == len(rows)
    for col, name, scale in [("z", "z_nm", 1e9), ("force", "force_nN", 1e9), ("t", "t_ms", 1e3)]:
        assert [f"{v * scale:.9g}" for v in t[col]] == [r[name] for r in rows], col
    got = figures(p.stdout)
    for key, meta, scale in [("adhesion_nN", "adhesion", 1e9), ("jumpin_z_nm", "jumpin_z", 1e9),
                             ("pulloff_force_nN", "pulloff_force", 1e9), ("slope_N_per_m", "slope", 1),
                             ("indentation_nm", "indentation", 1e9), ("drive_periods", "cycles", 1)]:
        assert float(f"{t.meta[meta] * scale:.6g}") == got[key], key


def test_tune_recovers_the_lever_within_its_errors():
    t = tiptap.tune(BLEND[1], set=SOFT, progress=False)
    m = t.meta
    assert m["chi"] == 1 and m["k_err"] > 0 and m["f0_err"] > 0 and m["Q_err"] > 0
    assert abs(m["k"] - 0.1) < 3 * m["k_err"]
    assert abs(m["f0"] - 10e3) < 3 * m["f0_err"]
    assert abs(m["Q"] - 20) < 3 * m["Q_err"]
    # the stated error is the record's: a few percent for 0.4 s, not a blanket bound
    assert 0.005 < m["k_err"] / m["k"] < 0.1
    # the spectrum holds the resonance where the fit put it
    f, psd = t["f"], t["psd"]
    assert t.units["psd"] == "m^2/Hz"
    assert abs(f[np.argmax(psd[1:]) + 1] - m["f0"]) < 3 * m["f0"] / m["Q"]
    fitted = ~np.isnan(t["fit"])
    assert fitted.sum() > 20 and m["fit_low"] <= f[fitted].min()


def test_tune_is_the_programs(tmp_path):
    p = cli("tune", BLEND[1], *sets(SOFT), "-o", tmp_path / "t.csv", "-q")
    t = tiptap.tune(BLEND[1], set=SOFT, progress=False)
    got = figures(p.stdout)
    assert float(f"{t.meta['k']:.6g}") == got["k_N_per_m"]
    assert float(f"{t.meta['f0']:.6g}") == pytest.approx(got["f0_Hz"], rel=1e-5)


def test_refusals_name_the_key():
    with pytest.raises(tiptap.SceneError, match=r"\[force\] from"):
        tiptap.force(BLEND, set={"force.from": "-5 nm"})
    with pytest.raises(tiptap.SceneError, match=r"\[noise\] temperature"):
        tiptap.tune(BLEND[1], set={"cantilever.spring_constant": "0.1 N/m"})


def test_force_volume_is_the_programs_maps(tmp_path):
    """force_volume(): the program's GSF maps (the float32 of the same doubles), on any
    number of threads, and the folder it writes is the program's."""
    from conftest import read_gsf

    over = {"scan.size": "500 nm", "scan.pixels": "6", "scan.lines": "3", "noise.temperature": "300 K"}
    cli("force", *BLEND, *sets(over), "--volume", "-o", tmp_path / "cli", "-j", "2", "-q")
    v = tiptap.force_volume(BLEND, set=over, threads=1, output=tmp_path / "py", progress=False)
    assert v.meta["lines_finished"] == v.meta["lines_total"] == 3
    assert v["adhesion"].shape == (3, 6) and v.units["stiffness"] == "N/m" and v.x[0] == pytest.approx(500e-9 / 12)
    for name in v:
        header, data = read_gsf(tmp_path / "cli" / f"{name}.gsf")
        assert header["ZUnits"] == v.units[name] or not v.units[name]
        assert np.array_equal(data, v[name].astype("<f4")), name
        assert (tmp_path / "py" / f"{name}.gsf").read_bytes() == (tmp_path / "cli" / f"{name}.gsf").read_bytes()
    # on the blend's disks the adhesion is the disk's least load, elsewhere the matrix's
    for m, material in enumerate(["matrix", "disk"]):
        least = -tiptap.contact(BLEND, material=material).meta["pulloff_load_N"]
        here = v["material"] == m
        assert here.any()
        assert np.allclose(v["adhesion"][here], least, rtol=3e-3)
