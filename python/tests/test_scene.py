"""Scenes from Python go through the library's configuration layer: the same keys,
defaults and checks as the program's, and its one-line messages as exceptions."""

import math

import pytest

import tiptap
from conftest import QUICK, cli, src


def program_error(*args):
    """The program's one line for a refused command, without its 'tiptap: '."""
    p = cli(*args, check=False)
    assert p.returncode == 1
    line = p.stderr.strip()
    assert "\n" not in line and line.startswith("tiptap: ")
    return line[len("tiptap: "):]


@pytest.mark.parametrize("assignment", ["scan.pixels=-3", "cantilever.spring_constant=4 N",
                                        "cantilever.free_amplitude=12", "scan.pixls=8",
                                        "material.matrix.youngs_modulus=nan GPa"])
def test_a_bad_override_raises_the_programs_message(assignment, tmp_path):
    key, value = assignment.split("=", 1)
    want = program_error("scan", *QUICK, "--set", assignment, "-o", tmp_path / "out")
    with pytest.raises(tiptap.SceneError) as e:
        tiptap.scan(QUICK, set={key: value}, progress=False)
    assert str(e.value) == want
    assert e.value.status == 1 and e.value.code == "TT_EINVAL"
    assert isinstance(e.value, ValueError) and isinstance(e.value, tiptap.TiptapError)
    assert not (tmp_path / "out").exists()


def test_a_bad_file_raises_the_programs_message(tmp_path):
    bad = tmp_path / "bad.ini"
    bad.write_text("[cantilever]\nspring_constnt = 3 N/m\n")
    want = program_error("scan", bad, "-o", tmp_path / "out")
    with pytest.raises(tiptap.SceneError, match="spring_constnt: unknown key") as e:
        tiptap.Scene(bad)
    assert str(e.value) == want
    missing = tmp_path / "missing.ini"
    with pytest.raises(tiptap.TiptapError) as e:
        tiptap.Scene(missing)
    assert str(e.value) == program_error("scan", missing, "-o", tmp_path / "out")


def test_keyword_and_dict_overrides():
    s = tiptap.Scene(*QUICK, feedback__setpoint="70 %", set={"material.disk.youngs_modulus": "4 GPa"})
    assert s["feedback.setpoint"] == "70 %"
    assert s["material.disk.youngs_modulus"] == "4 GPa"
    s.set(material__matrix__poisson_ratio=0.45, scan__retrace=False)
    assert s["material.matrix.poisson_ratio"] == "0.45"
    assert s["scan.retrace"] == "no"


def test_numbers_are_read_in_the_keys_si_unit():
    s = tiptap.Scene(*QUICK, cantilever__free_amplitude=12.5e-9, scan__pixels=8,
                     cantilever__resonance_frequency=3.1e5)
    assert s["cantilever.free_amplitude"] == "1.25e-08 m"
    assert s["cantilever.resonance_frequency"] == "310000.0 Hz"
    assert s["scan.pixels"] == "8"
    # a length or a percentage: a bare number would be a guess
    with pytest.raises(tiptap.SceneError, match="ambiguous"):
        tiptap.Scene(*QUICK, feedback__setpoint=0.7)
    with pytest.raises(tiptap.SceneError, match="not a finite number"):
        tiptap.Scene(*QUICK, cantilever__free_amplitude=math.nan)


def test_keys_list_every_key_with_unit_and_default():
    keys = tiptap.keys()
    listing = cli("keys").stdout
    # every key of `tiptap keys`, the same defaults
    for k in keys:
        assert f"  {k.key} " in listing
    by = {(k.section, k.key): k for k in keys}
    k = by["cantilever", "spring_constant"]
    assert (k.kind, k.unit, k.default) == ("quantity", "N/m", "40 N/m")
    assert by["cantilever", "quality_factor"].unit == ""
    sp = by["feedback", "setpoint"]
    assert sp.unit is None and set(sp.units) == {"m", ""}
    assert by["material", "model"].choices == ("maugis", "hertz", "dmt", "jkr")
    assert by["material", "model"].named
    assert by["surface", "png"].path
    assert len({k.section for k in keys}) >= 10


def test_the_effective_scene_is_the_programs(quick_cli):
    s = tiptap.Scene(*QUICK, set={"scan.pixels": "16", "scan.lines": "4"})
    assert s.text() == (quick_cli / "scene.ini").read_text()
    assert s.origin.endswith("quick.ini")
    assert tiptap.Scene(text="[cantilever]\nquality_factor = 30\n")["cantilever.quality_factor"] == "30"


def test_a_copy_is_independent():
    s = tiptap.Scene(src("scans", "quick.ini"))
    c = s.copy().set(scan__lines=3)
    assert s["scan.lines"] != "3" and c["scan.lines"] == "3"
