"""Ctrl-C stops a run and raises KeyboardInterrupt with what it finished; a progress
callback that raises stops it too; other Python threads run while the library works."""

import os
import signal
import threading

import numpy as np
import pytest

import tiptap
from conftest import QUICK, QUICK_SET

LONG = {**QUICK_SET, "scan.lines": "40"}


def test_ctrl_c_stops_a_scan_and_keeps_the_finished_lines():
    def progress(done, total):
        if done == 2:  # Ctrl-C, as the terminal sends it, once two lines are done
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt) as e:
        tiptap.scan(QUICK, set=LONG, threads=1, progress=progress)
    assert isinstance(e.value, tiptap.Interrupted)
    r = e.value.result
    done = r.run["lines_finished"]
    assert 2 <= done < 40 and r.run["lines_total"] == 40
    assert r.meta["lines_finished"] == str(done)
    # the finished lines hold numbers, the others NaN (as the program's files)
    h = r["height"]
    finished = np.isfinite(h).all(axis=1)
    assert finished.sum() == done and np.isnan(h[~finished]).all()
    # the cancellation was for that run only: the next one runs to its end
    again = tiptap.scan(QUICK, set={**QUICK_SET, "scan.lines": "2"}, progress=False)
    assert again.run["lines_finished"] == 2


def test_a_progress_callback_that_raises_stops_the_run():
    calls = []

    def progress(done, total):
        calls.append(done)
        raise ValueError("enough")

    with pytest.raises(ValueError, match="enough"):
        tiptap.scan(QUICK, set=LONG, threads=1, progress=progress)
    assert calls == [1]
    assert tiptap.scan(QUICK, set={**QUICK_SET, "scan.lines": "1"}, progress=False).run[
        "lines_finished"] == 1


def test_other_threads_run_during_a_scan():
    """A scan called from a second thread releases the GIL: the main thread counts on."""
    state = {"done": False, "result": None}

    def work():
        state["result"] = tiptap.scan(QUICK, set=QUICK_SET, threads=1, progress=False)
        state["done"] = True

    t = threading.Thread(target=work)
    t.start()
    count = 0
    while not state["done"]:
        count += 1
    t.join()
    assert state["result"].run["lines_finished"] == 4
    # a loop that held no GIL would count millions; one starved by it, nearly none
    assert count > 100000
