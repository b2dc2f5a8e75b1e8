"""Viscous samples from Python (docs/physics.md, Viscoelastic samples): the approach and
the sweep carry the loss per mechanism, the same numbers as the program's CSV; a zero
viscosity leaves the elastic table as it was; trace and scan run the blend example, the
scan's loss all in its dissipation_viscous channel."""

import numpy as np

import tiptap
from conftest import QUICK_SET, cli, sets, src
from test_tables import check_columns, csv_rows

BLEND = [src("scans", "quick.ini"), src("examples", "viscoelastic-blend", "scene.ini")]
POINTS = {"approach.material": "domain", "approach.from": "14 nm", "approach.to": "10 nm",
          "approach.points": "3"}


def test_approach_books_the_viscous_loss(tmp_path):
    cli("approach", *BLEND, *sets(POINTS), "-o", tmp_path / "a.csv", "-q")
    t = tiptap.approach(BLEND, set=POINTS, progress=False)
    assert t.units["dissipated_viscous"] == "J"
    check_columns(t, csv_rows(tmp_path / "a.csv"), {
        "dissipated_aJ": ("dissipated", 1e18, 9),
        "dissipated_hysteresis_aJ": ("dissipated_hysteresis", 1e18, 9),
        "dissipated_damping_aJ": ("dissipated_damping", 1e18, 9),
        "dissipated_viscous_aJ": ("dissipated_viscous", 1e18, 9)})
    assert np.all(t["dissipated_viscous"] > 0)
    np.testing.assert_allclose(t["dissipated_hysteresis"] + t["dissipated_damping"] +
                               t["dissipated_viscous"], t["dissipated"], rtol=1e-12)


def test_zero_viscosity_keeps_the_elastic_table():
    zero = dict(POINTS, **{"material.domain.viscosity": "0 Pa s", "material.matrix.viscosity": "0 Pa s"})
    t = tiptap.approach(BLEND, set=zero, progress=False)
    assert "dissipated_viscous" not in t
    assert np.all(t["dissipated"] == 0)


def test_sweep_and_trace_and_scan_run_the_blend():
    s = tiptap.sweep(BLEND, {"material.domain.viscosity": "0 Pa s,300 Pa s"}, set=POINTS,
                     progress=False)
    v = s["dissipated_viscous"]
    assert v[0] == 0 and v[-1] > 0
    tr = tiptap.trace(BLEND, set={"trace.material": "domain", "trace.separation": "12 nm",
                                  "trace.cycles": "3"}, progress=False)
    assert tr.rows == 300
    r = tiptap.scan(BLEND, set=dict(QUICK_SET, **{"scan.profile_line": "0"}), progress=False)
    d = r["dissipation"]
    assert d.max() > 5e-18 and d.min() == 0
    # the loss per mechanism: all of it viscous (no adhesion, no interaction damping)
    assert r.units["dissipation_viscous"] == "J"
    assert np.all(r["dissipation_hysteresis"] == 0) and np.all(r["dissipation_damping"] == 0)
    np.testing.assert_array_equal(r["dissipation_viscous"], d)
