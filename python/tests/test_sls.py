"""A standard linear solid from Python, through the scene alone (docs/physics.md, the
generalised Maxwell sample; examples/sls-surface): the trace's sample column is the
surface where it is, pressed in by each tap and recovering between them, and the
approach books the arm's loss as viscous."""

import numpy as np

import tiptap
from conftest import src

SLS = [src("examples", "sls-surface", "scene.ini")]


def test_the_surface_lags_behind_the_tip():
    tr = tiptap.trace(SLS, set={"trace.settle_cycles": "300", "trace.cycles": "2"}, progress=False)
    s, c = tr["sample"], tr["contact"]
    rest = 16e-9
    # between taps the surface stays pressed in, and rises back towards its rest
    free = s[c == 0]
    assert free.min() > rest + 0.2e-9
    out = np.flatnonzero((c[:-1] == 1) & (c[1:] == 0))
    back = np.flatnonzero((c[:-1] == 0) & (c[1:] == 1))
    assert len(out) >= 1 and len(back) >= 1
    after, before = s[out[0] + 1], s[back[back > out[0]][0]]
    assert after > before > rest


def test_the_approach_books_the_arm_loss():
    t = tiptap.approach(SLS, set={"approach.from": "17 nm", "approach.to": "15 nm",
                                  "approach.points": "3"}, progress=False)
    assert np.all(t["dissipated_viscous"] > 0)
    np.testing.assert_allclose(t["dissipated_viscous"] + t["dissipated_damping"] +
                               t["dissipated_hysteresis"], t["dissipated"], rtol=1e-9)
