"""Ctrl-C stops a run and raises KeyboardInterrupt with what it finished; a progress
callback that raises stops it too; other Python threads run while the library works."""

import os
import re
import signal
import subprocess
import sys
import threading
import time

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


# Ctrl-C as a terminal sends it: SIGINT from outside to a Python process running a long
# scan (2000 lines: minutes), once its first line is done.
CHILD = r"""
import sys, tiptap
from conftest import QUICK, QUICK_SET

def progress(done, total):
    if done == 1:
        print("first line", flush=True)

try:
    tiptap.scan(QUICK, set={**QUICK_SET, "scan.pixels": "32", "scan.lines": "2000"},
                threads=2, progress=progress)
except KeyboardInterrupt as e:
    if sys.argv[1] == "raise":
        raise
    r = e.result
    print("interrupted", r.run["lines_finished"], r.run["lines_total"], flush=True)
    sys.exit(0)
print("finished", flush=True)
sys.exit(3)
"""


def interrupt_child(mode):
    """Start the child, SIGINT it after its first line; (returncode, stdout lines after
    the first, stderr, seconds from SIGINT to exit)."""
    p = subprocess.Popen([sys.executable, "-c", CHILD, mode], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, cwd=os.path.dirname(__file__))
    try:
        first = p.stdout.readline()
        assert first == "first line\n", (first, p.stderr.read() if p.poll() is not None else "")
        t0 = time.monotonic()
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
        return p.returncode, out.split("\n"), err, time.monotonic() - t0
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()


def test_sigint_from_outside_stops_a_long_scan_within_seconds():
    rc, out, err, seconds = interrupt_child("catch")
    assert rc == 0, err
    words = out[0].split()
    assert words[0] == "interrupted" and 1 <= int(words[1]) < 2000 and words[2] == "2000", out
    # the run checks the cancellation every few cycles: well under a second on this
    # scene, a few seconds allowed for a loaded machine and the sanitizers
    assert seconds < 5, f"{seconds:.1f} s from SIGINT to exit"
    assert "Sanitizer" not in err and "Traceback" not in err, err


def test_an_uncaught_ctrl_c_ends_the_script_with_its_traceback():
    rc, out, err, seconds = interrupt_child("raise")
    # exit status 1 (Python dies by SIGINT for KeyboardInterrupt itself only), the last
    # line the exception with what the run had done
    assert rc == 1 and out == [""], (rc, out, err)
    last = err.rstrip().split("\n")[-1]
    assert re.fullmatch(r"tiptap\.Interrupted: scan: interrupted \(interrupted after \d+ of "
                        r"2000 lines\)", last), err[-400:]
    assert "Sanitizer" not in err and seconds < 5, (seconds, err[-400:])
