"""The program's warnings reach Python: each raised with warnings.warn as its
tiptap.TiptapWarning subclass and kept on the result as (category, message), with the
words the program prints after "tiptap CMD: warning: "."""

import os
import threading
import warnings

import pytest

import tiptap
from conftest import QUICK, QUICK_SET, cli, sets, src

EXTREME = src("examples", "extreme")

# a soft material under a 1 nm tip is pressed tens of nm deep (tests/cli_contact_validity.sh)
SOFT = """
[cantilever]
quality_factor = 100
[material soft]
youngs_modulus = 50 MPa
[tip]
radius = 1 nm
shape = sphere
[scan]
size = 1 um
pixels = 16
lines = 2
line_rate = 200 Hz
settle_cycles = 1000
channels = height, indentation
[feedback]
setpoint = 50 %
"""


def caught(call):
    """call()'s result and the tiptap warnings it raised, as (class, message)."""
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        r = call()
    return r, [(x.category, str(x.message)) for x in w if issubclass(x.category, tiptap.TiptapWarning)]


def program_warnings(stderr, cmd):
    prefix = f"tiptap {cmd}: warning: "
    return [line[len(prefix):] for line in stderr.splitlines() if line.startswith(prefix)]


def test_contact_validity_as_the_program_says(tmp_path):
    ini = tmp_path / "soft.ini"
    ini.write_text(SOFT)
    r, w = caught(lambda: tiptap.scan(str(ini), progress=False))
    assert [c for c, _ in w] == [tiptap.ValidityWarning]
    assert w[0][1].startswith("[material soft]: contact radius up to ")
    assert r.warnings == [("validity", w[0][1])]
    p = cli("scan", ini, "-o", tmp_path / "out", "-q")
    assert program_warnings(p.stderr, "scan") == [w[0][1]]


def test_a_stiff_material_gives_no_warning(tmp_path):
    ini = tmp_path / "stiff.ini"
    ini.write_text(SOFT.replace("50 MPa", "200 GPa").replace("radius = 1 nm", "radius = 10 nm"))
    r, w = caught(lambda: tiptap.scan(str(ini), progress=False))
    assert w == [] and r.warnings == []


def test_oscillating_loop():
    # docs/imaging.md, The scope: 10 nm steps at ki = 6 kHz ring at about 530 Hz
    r, w = caught(lambda: tiptap.scan(src("surfaces", "steps.ini"), progress=False,
                                      feedback__integral_gain="6 kHz", scan__pixels=64,
                                      scan__lines=1, scan__line_rate="4 Hz"))
    assert [c for c, _ in w] == [tiptap.OscillationWarning]
    assert w[0][1].startswith("the feedback loop oscillates: in line 0's trace, z rings at")
    assert r.warnings[0][0] == "oscillation"


def test_setpoint_not_reached_in_a_sweep():
    # at Q 1 the amplitude on the stiff disk never comes down to 5 % (cli_sweep_setpoint.sh)
    t, w = caught(lambda: tiptap.sweep(src("surfaces", "polymer-blend.ini"),
                                       {"cantilever.quality_factor": "1", "feedback.setpoint": "5%"},
                                       run="setpoint", approach__material="disk", progress=False))
    assert list(t["found"]) == ["unreachable"]
    assert w == [(tiptap.SetpointWarning, "the setpoint was not reached in 1 of 1 combinations "
                  "(found=unreachable; each row holds the closest point): 1")]
    assert t.warnings == [("setpoint", w[0][1])]


def test_points_not_settled(tmp_path):
    scene = os.path.join(EXTREME, "vacuum-q1e4.ini")
    keys = {"approach.points": 2, "approach.steady": "settle", "approach.max_cycles": 100}
    t, w = caught(lambda: tiptap.approach(scene, set=keys, progress=False))
    assert list(t["settled"]) == [0, 0]
    assert w == [(tiptap.SettleWarning, "2 of 2 points found no period up to 64 cycles within "
                  "max_cycles = 100 (z = 22, 2 nm): their rows are the means over their last 64 "
                  "cycles (period 0); chaos, or raise [approach] max_cycles")]
    # a file of its own: an output never replaces a device node such as /dev/null
    p = cli("approach", scene, *sets(keys), "-o", str(tmp_path / "approach.csv"))
    assert program_warnings(p.stderr, "approach") == [w[0][1]]


def test_error_estimate_too_high():
    # Q 1e5 at tolerance 1e-4 (tests/cli_estimate_warning.sh)
    r, w = caught(lambda: tiptap.scan(os.path.join(EXTREME, "vacuum-q1e4.ini"), progress=False,
                                      error_estimate=True, cantilever__quality_factor=1e5,
                                      solver__tolerance=1e-4, scan__pixels=8, scan__lines=1,
                                      scan__line_rate="50Hz"))
    assert [c for c, _ in w] == [tiptap.EstimateWarning]
    assert w[0][1].startswith("the run's own error estimate is ")
    assert w[0][1].endswith("(above 1e-3 of the free amplitude or 0.1 deg): tighten [solver] "
                            "tolerance (now 0.0001)")
    assert r.warnings == [("estimate", w[0][1])]


def test_unused_material():
    r, w = caught(lambda: tiptap.scan(tiptap.Scene(*QUICK, text="[material silcon]\n"
                                                   "reduced_modulus = 50 GPa\n", set=QUICK_SET),
                                      progress=False))
    assert (tiptap.InputWarning, "[material silcon] is not used: [surface] map_materials names "
            "two others") in w
    assert ("input", "[material silcon] is not used: [surface] map_materials names two others") \
        in r.warnings


def test_long_run_warned_before_it_runs(tmp_path):
    # a drive 10 times below the resonance (tests/cli_reliability.sh); the bad output
    # path stops the run after the warning, as the program's folder does
    with pytest.warns(tiptap.RunWarning, match=r"^this run takes about \d+ min by estimate; the "
                      r"drive at 30 kHz is 10 times below"):
        with pytest.raises(tiptap.TiptapIOError):
            tiptap.scan(QUICK, set=QUICK_SET, progress=False, hdf5=str(tmp_path / "no" / "x.h5"),
                        cantilever__drive_frequency="30 kHz", scan__lines=128,
                        scan__settle_cycles=3000, scan__line_rate="1 Hz")


def test_warnings_as_errors_still_keep_the_run_safe(tmp_path):
    ini = tmp_path / "soft.ini"
    ini.write_text(SOFT)
    with warnings.catch_warnings():
        warnings.simplefilter("error", tiptap.TiptapWarning)
        with pytest.raises(tiptap.ValidityWarning):
            tiptap.scan(str(ini), progress=False)


def test_each_thread_hears_its_own_run(tmp_path):
    """Two runs at once on two threads: each result holds its own warnings only."""
    ini = tmp_path / "soft.ini"
    ini.write_text(SOFT)
    stiff = tmp_path / "stiff.ini"
    stiff.write_text(SOFT.replace("50 MPa", "200 GPa").replace("radius = 1 nm", "radius = 10 nm"))
    out = {}

    def soft():
        out["soft"] = tiptap.scan(str(ini), progress=False)

    def quiet():
        out["quiet"] = tiptap.scan(str(stiff), progress=False)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        threads = [threading.Thread(target=f) for f in (soft, quiet)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    assert [c for c, _ in out["soft"].warnings] == ["validity"]
    assert out["quiet"].warnings == []


def test_categories():
    names = {c.category: c for c in (tiptap.ValidityWarning, tiptap.OscillationWarning,
                                     tiptap.SetpointWarning, tiptap.SettleWarning,
                                     tiptap.EstimateWarning, tiptap.InputWarning,
                                     tiptap.RunWarning)}
    assert set(names) == {"validity", "oscillation", "setpoint", "settle", "estimate", "input", "run"}
    assert all(issubclass(c, tiptap.TiptapWarning) for c in names.values())
    assert issubclass(tiptap.TiptapWarning, UserWarning)
