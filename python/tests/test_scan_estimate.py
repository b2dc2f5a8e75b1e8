"""The error estimate (tt_scan_estimate_error) reads at or above the error measured
against a reference run, where the image's error is largest away from its largest
height step."""

import os
import warnings

import numpy as np

import tiptap
from conftest import QUICK

# the README's main job on two lines through the disks' centres, trace and retrace:
# every cycle at 1e-8 errs 0.28 pm where the tip leaves the soft matrix for a stiff disk,
# while the image's largest height step is where it leaves the disk (0.013 pm there)
LINES = {"scan.lines": "2", "scan.retrace": "yes", "scan.channels": "height, phase",
         "scan.fast_axis": "x", "solver.tier": "every", "solver.method": "dopri5"}


def run(tolerance, estimate):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return tiptap.scan(QUICK, set={**LINES, "solver.tolerance": tolerance}, threads=2,
                           progress=False, error_estimate=estimate)


def test_the_estimate_is_not_below_the_measured_error():
    ref = run("1e-10", False)
    r = run("1e-8", True)
    for name, key in (("height", "height_max_m"), ("phase", "phase_max_deg")):
        measured = max(np.nanmax(np.abs(r[name, d] - ref[name, d])) for d in ("trace", "retrace"))
        assert measured > 0
        assert r.error[key] >= measured, (name, r.error[key], measured, r.error)
    # it ran where the error is: more than the largest height step's stretch, or the line
    assert r.error["stretches"] > 1 or r.error["pixels"] == r.error["pixels_line"]


NOISE = {"noise.temperature": "300 K", "noise.detector": "100 fm/sqrt(Hz)"}


def noisy(surface, lines):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return tiptap.scan([QUICK[0], surface], set={**NOISE, "scan.lines": str(lines)}, threads=1,
                           progress=False, error_estimate=True)


def test_a_noisy_scan_holds_its_share_or_says_it_is_over():
    # with noise the companion runs whole lines (part of a line reads low: the errors
    # gather along it). 4 lines of the blend at 300 K: a fifth of their work holds no
    # whole line at the tight setting, so the hardest one ran over the share and says so
    r = noisy(QUICK[1], 4)
    e = r.error
    assert e["over_share"] and e["pixels"] == e["pixels_line"] and e["lines_whole"] == 1, e
    assert e["work"] > 0.2 * e["scan_work"], e
    assert 0 < e["cpu_s"] < e["run_cpu_s"], e
    # 24 lines: a fifth holds whole lines, the hardest ones, within it
    e = noisy(QUICK[1], 24).error
    assert not e["over_share"] and e["lines_whole"] >= 1 and e["pixels"] == e["lines_whole"] * e["pixels_line"], e
    assert 0 < e["work"] <= 0.2 * e["scan_work"], e
