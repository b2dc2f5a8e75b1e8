"""What a Python caller may rely on beyond the numbers: a run works on its own copy of
the scene, a Scene may be shared between threads, the program's memory estimate and its
refusals hold (an empty scene list, a NUL byte, an unknown keyword), an interrupted
sweep keeps its finished combinations in its HDF5 file, progress bars fit notebooks."""

import os
import subprocess
import sys
import textwrap
import threading
import types

import h5py
import numpy as np
import pytest

import tiptap
from conftest import QUICK, QUICK_SET, src


def child(code, **env):
    """code run by a fresh interpreter with this one's environment (a crash there is an
    exit status here, not the end of the tests)."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, env={**os.environ, **env}, timeout=600)


def test_a_scene_changed_during_a_run_reaches_neither_run_nor_result():
    s = tiptap.Scene(*QUICK, set=QUICK_SET)
    before = s["feedback.setpoint"]

    def change(done, total):
        s.set({"feedback.setpoint": "37 %", "scan.pixels": "8"})

    r = tiptap.scan(s, progress=change, threads=1)
    assert s["feedback.setpoint"] == "37 %"
    assert not r.meta["feedback.setpoint"].startswith("37")
    assert "setpoint = " + before in r.scene and "37 %" not in r.scene
    assert r["height"].shape == (4, 16) and r.meta["scan.pixels"] == "16"


def test_one_scene_from_many_threads():
    """Threads that grow, read, copy and run one Scene at once (before the scene's lock,
    a double free or a segmentation fault in 3 of 5 tries)."""
    p = child(f"""
        import threading, tiptap
        s = tiptap.Scene(*{QUICK!r})
        errors = []
        def guard(f, *a):
            try:
                f(*a)
            except BaseException as e:
                errors.append(repr(e))
        def setter(k):
            for i in range(800):
                s.load_string(f"[material m{{k}}x{{i}}]\\nreduced_modulus = 3 GPa\\n")
                s.set({{"cantilever.free_amplitude": f"{{20 + i % 7}} nm"}})
        def reader():
            for i in range(100):
                s.text(); s.copy()
        def runner():
            for i in range(3):
                tiptap.trace(s, progress=False, trace__cycles=2, trace__settle_cycles=0)
        ts = [threading.Thread(target=guard, args=a) for a in
              ((setter, 0), (setter, 1), (reader,), (reader,), (runner,))]
        for t in ts: t.start()
        for t in ts: t.join()
        text = s.text()
        print("ok", errors, text.count("[material m0x") + text.count("[material m1x"))
    """)
    assert p.returncode == 0 and p.stdout.strip() == "ok [] 1600", (p.returncode, p.stdout,
                                                                    p.stderr[-2000:])


def test_a_scene_call_waits_for_another_threads():
    """Each call on a Scene holds its lock: a set() from another thread waits until the
    holder is done, then goes through."""
    s = tiptap.Scene(*QUICK)
    done = threading.Event()

    def other():
        s.set(feedback__setpoint="41 %")
        done.set()

    with s._lock:
        t = threading.Thread(target=other)
        t.start()
        assert not done.wait(0.3)
        assert s["feedback.setpoint"] != "41 %"
    t.join()
    assert done.is_set() and s["feedback.setpoint"] == "41 %"


def test_scan_refuses_what_the_program_would_not_hold():
    # the program's estimate (tests/cli_reliability.sh) under a 1 GB data limit, which
    # a sanitizer build cannot start under (its shadow memory)
    limit = "import resource; resource.setrlimit(resource.RLIMIT_DATA, (1 << 30, -1)); import tiptap"
    if child(limit).returncode != 0:
        pytest.skip("the interpreter cannot start under a 1 GB data limit here")
    p = child(f"""
        import resource, tiptap
        resource.setrlimit(resource.RLIMIT_DATA, (1 << 30, resource.RLIM_INFINITY))
        try:
            tiptap.scan({QUICK!r}, progress=False, scan__pixels=16384, scan__lines=16384,
                        scan__line_rate="0.001 Hz", scan__channels="height")
        except MemoryError as e:
            print(type(e).__name__, "|", e)
    """)
    assert p.returncode == 0, p.stderr[-2000:]
    assert p.stdout.startswith("TiptapMemoryError | 16384 x 16384 pixels need about "), p.stdout
    assert "of memory (" in p.stdout and "more than the 1.1 GB available" in p.stdout


def test_an_empty_scene_list_is_refused():
    for run in (tiptap.approach, tiptap.trace, tiptap.scan):
        with pytest.raises(tiptap.SceneError, match="needs a scene file"):
            run([], progress=False)
    with pytest.raises(tiptap.SceneError, match="needs a scene file"):
        tiptap.sweep([], {"approach.from": "10nm,20nm"}, progress=False)


def test_a_nul_byte_is_refused_naming_the_argument(tmp_path):
    with pytest.raises(ValueError, match="^path: .* contains a NUL byte"):
        tiptap.Scene(QUICK[0] + "\0ignored")
    s = tiptap.Scene(*QUICK)
    with pytest.raises(ValueError, match="^feedback.setpoint: .* contains a NUL byte"):
        s.set(feedback__setpoint="70 %\0 junk")
    with pytest.raises(ValueError, match="^key: .* contains a NUL byte"):
        s.set({"feedback.setpoint\0x": "70 %"})
    with pytest.raises(ValueError, match="^text: "):
        s.load_string("[tip]\nradius = 10 nm\0\n")
    with pytest.raises(ValueError, match="^hdf5: "):
        tiptap.scan(s, set=QUICK_SET, hdf5=str(tmp_path / "a\0b.h5"), progress=False)
    with pytest.raises(ValueError, match="^material: "):
        tiptap.contact(s, material="disk\0")
    with pytest.raises(ValueError, match="^vary: "):
        tiptap.sweep(s, ["approach.from=10nm\0,20nm"], progress=False)
    assert os.listdir(tmp_path) == []


def test_an_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError, match=r"^scan\(\) got an unexpected keyword argument 'treads'$"):
        tiptap.scan(QUICK, treads=2, progress=False)
    with pytest.raises(TypeError, match=r"^approach\(\) got an unexpected keyword argument "
                                        r"'approach__piont'"):
        tiptap.approach(QUICK, approach__piont=3, progress=False)
    with pytest.raises(TypeError, match=r"^Scene\(\) got an unexpected keyword argument 'fiels'"):
        tiptap.Scene(*QUICK, fiels=2)
    with pytest.raises(TypeError, match=r"^sweep\(\) got an unexpected keyword argument 'thread'"):
        tiptap.sweep(QUICK, {"approach.from": "10nm,20nm"}, thread=1, progress=False)
    # named sections still take their keys
    s = tiptap.Scene(*QUICK, material__disk__youngs_modulus="3 GPa")
    assert s["material.disk.youngs_modulus"].startswith("3")


def test_an_interrupted_sweep_writes_its_finished_combinations(tmp_path):
    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop

    with pytest.raises(Stop):
        tiptap.sweep(src("surfaces", "polymer-blend.ini"), {"approach.from": "10nm:20nm:3"},
                     threads=1, progress=stop, hdf5=tmp_path / "part.h5")
    with h5py.File(tmp_path / "part.h5", "r") as f:
        a = f["Measurement_000/Channel_000/amplitude"][()]
        assert a.shape == (3,) and np.isfinite(a[0]) and np.isnan(a[1:]).all()
    assert os.listdir(tmp_path) == ["part.h5"]


def test_the_progress_bar_is_tqdm_auto(monkeypatch):
    made = []

    class Bar:
        def __init__(self, total, desc, unit):
            made.append(desc)
            self.n = 0

        def update(self, k):
            self.n += k

        def close(self):
            pass

    class Wrong(Bar):
        def __init__(self, *a, **k):
            raise AssertionError("tqdm.tqdm: a text bar in notebooks")

    fake = types.ModuleType("tqdm")
    fake.tqdm = Wrong
    fake.auto = types.ModuleType("tqdm.auto")
    fake.auto.tqdm = Bar
    monkeypatch.setitem(sys.modules, "tqdm", fake)
    monkeypatch.setitem(sys.modules, "tqdm.auto", fake.auto)
    tiptap.contact(lam=1.0)  # no progress
    tiptap.trace(QUICK, trace__cycles=2, trace__settle_cycles=0)
    assert made == ["trace"]
