#!/usr/bin/python3
"""The console's loop panel in a real browser (headless Chromium over the DevTools
protocol, tests/live_cdp.py), at 1024 x 768: the phase margin the panel shows at
ki = 1.18 kHz, 4 kHz and 10 kHz against the model of docs/imaging.md (53 deg, 12 deg,
none), computed here again in Python; the Bode plot redrawn when the gain changes; the
P and I suggestions' margins; auto-tune's steps in its log and its end at a gain whose
model margin is 55 to 65 deg.

usage: live_loop.py CHROMIUM URL SHOTS_DIR
Prints 'ok ...' / 'FAIL ...' lines; exits 1 on the first failure."""
import cmath
import hashlib
import json
import math
import sys

from live_cdp import run, shot, wait_for

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]

# the standard cantilever and lock-in (scans/standard.ini): f0 = fd = 300 kHz, Q 400,
# 2 sections of 100 us, 4 periods a block
F0, Q, TF, N, D = 300e3, 400.0, 100e-6, 2, 4 / 300e3
TAU_A = Q / (math.pi * F0)


def margin(kp, ki, g=1.0):
    """The open loop's phase margin (deg), as tt_loop_phase_margin computes it: NaN where
    it has no crossover."""
    def mag(w):
        s = 1j * w
        L = g * (kp + ki / s) * cmath.exp(-s * D) / (1 + s * TAU_A) / (1 + s * TF) ** N
        return abs(L)
    lo, hi = 1e-9, 1e10
    if mag(hi) >= 1 or mag(lo) <= 1:
        return float("nan")
    for _ in range(200):
        w = math.sqrt(lo * hi)
        if mag(w) > 1:
            lo = w
        else:
            hi = w
    w = math.sqrt(lo * hi)
    ph = math.atan2(-ki / w, kp) - math.atan(w * TAU_A) - w * D - N * math.atan(w * TF)
    return 180 + math.degrees(ph)


def js(b, expr):
    return json.loads(b.eval("JSON.stringify(%s)" % expr))


def in_force(b, name):
    return b.eval("tiptapLive.controls.find(c => c.name === '%s').value" % name)


def set_gain(b, ki):
    b.eval("tiptapSet('feedback.integral_gain', '%s')" % ki)
    wait_for(b, "parseFloat(tiptapLive.controls.find(c => c.name === 'feedback.integral_gain').value) === %s "
                "&& tiptapLive.loop.now && tiptapLive.loop.now.ki === %s" % (ki, ki), "I gain %s in force" % ki)


def bode_hash(b):
    data = b.eval("document.getElementById('bode').toDataURL()")
    return hashlib.sha1(data.encode()).hexdigest()


def margins(b):
    wait_for(b, "tiptapLive.loop.p.from === 'scene'", "the scene's cantilever read by the page")
    p = js(b, "tiptapLive.loop.p")
    assert abs(p["f0"] - F0) < 1 and p["Q"] == Q and abs(p["tau_f"] - TF) < 1e-9 and p["n"] == N \
        and p["P"] == 4, "the page's loop: %s" % p
    print("ok the page read f0 %.0f Hz, Q %g, lock-in %d x %g s, %d periods a block from the scene"
          % (p["f0"], p["Q"], p["n"], p["tau_f"], p["P"]))
    h0 = None
    for ki, want in ((1180, 53), (4000, 12), (10000, None)):
        set_gain(b, ki)
        shown = js(b, "tiptapLive.loop.now.margin")
        text = b.eval("document.getElementById('loopsummary').textContent")
        ref = margin(0, ki)
        if want is None:
            assert ref < 0 and (shown is None or shown < 0) and "margin none" in text or \
                ("margin -" in text and shown < 0), \
                "at %d Hz: the panel says %r (%s), the model %.2f" % (ki, text, shown, ref)
            print("ok at ki = %d Hz the panel's margin is %.1f deg (the model %.2f): the loop oscillates"
                  % (ki, shown, ref))
        else:
            assert abs(shown - ref) < 0.05 and abs(shown - want) < 1, \
                "at %d Hz the panel's margin %.2f deg, the model's %.2f, the docs' %d" % (ki, shown, ref, want)
            assert ("phase margin %.1f deg" % shown) in text, "the panel's text: %r" % text
            print("ok at ki = %d Hz the panel shows a %.1f deg margin (the model %.2f, the docs %d)"
                  % (ki, shown, ref, want))
        h = bode_hash(b)
        assert h != h0, "the Bode plot was not redrawn for ki = %d Hz" % ki
        h0 = h
    print("ok the Bode plot's pixels differ at each of the three gains")
    s = js(b, "({ki60: tiptapLive.loop.now.ki60, kp: tiptapLive.loop.now.kp60pi, ki: tiptapLive.loop.now.ki60pi})")
    m1, m2 = margin(0, s["ki60"]), margin(s["kp"], s["ki"])
    assert abs(m1 - 60) < 0.1 and abs(m2 - 60) < 0.1 and abs(s["kp"] - s["ki"] * TAU_A) < 1e-9, \
        "the suggestions %s give %.2f and %.2f deg" % (s, m1, m2)
    print("ok the suggestions: I %.0f Hz (P 0) and P %.2f with I %.0f Hz, each 60 deg on the model"
          % (s["ki60"], s["kp"], s["ki"]))


def tune(b):
    set_gain(b, 100)
    # the ring at 10 kHz must be gone before auto-tune starts from 100 Hz
    wait_for(b, "tiptapLive.status && !tiptapLive.status.oscillating", "the warning cleared at 100 Hz")
    b.eval("document.getElementById('autotune').click()")
    wait_for(b, "tiptapLive.loop.tune === null && tiptapLive.loop.tuned > 0", "auto-tune's end")
    ki = js(b, "tiptapLive.loop.tuned")
    wait_for(b, "parseFloat(tiptapLive.controls.find(c => c.name === 'feedback.integral_gain').value) === %d" % ki,
             "the tuned gain in force")
    log = js(b, "tiptapLive.loop.log")
    m = margin(0, ki)
    assert 55 <= m <= 65, "auto-tune ended at %d Hz, margin %.1f deg" % (ki, m)
    steps = [x for x in log if x.startswith("step ")]
    assert len(steps) >= 3 and "backed off" in steps[-1], "the log: %s" % log
    shown = b.eval("document.getElementById('looplog').textContent")
    assert all(x in shown for x in log), "the page's log does not show every line"
    for x in log:
        print("  log: " + x)
    print("ok auto-tune: %d steps, ended at I %d Hz, model margin %.1f deg" % (len(steps), ki, m))


def ring(b):
    """At 4 kHz the scene rings after its walls: the server's warning and the model's
    prediction side by side (up to 12 lines for the warning; a line without one checks
    the text that says so)."""
    set_gain(b, 4000)
    n0 = js(b, "tiptapLive.scopes")
    wait_for(b, "tiptapLive.status.oscillating || tiptapLive.scopes >= %d" % (n0 + 12),
             "a ring or 12 lines at 4 kHz")
    st = js(b, "tiptapLive.status")
    text = b.eval("document.getElementById('loopring').textContent")
    model = js(b, "tiptapLive.loop.now.ring")
    assert model and 300 < model["hz"] < 600 and model["damping"] < 0.2, "the model's ring at 4 kHz: %s" % model
    if st["oscillating"]:
        hz = b.eval("fmt(%r, 'Hz')" % st["ring_hz"])
        nm = b.eval("fmt(%r, 'nm')" % (st["ring_m"] * 1e9))
        assert text.startswith("Measured: the loop rings at %s, %s peak to peak" % (hz, nm)) and \
            "the model rings at" in text, text
        # the measured ring's damping ratio, as tt_scan_oscillation reads it from the record
        assert 0 < st["ring_damping"] < 1, st
        assert ", damping ratio %.2f (the server's warning)" % st["ring_damping"] in text, text
        print("ok at 4 kHz the server's ring (%.0f Hz) beside the model's: %s" % (st["ring_hz"], text))
    else:
        assert text.startswith("No ring measured") and "the model rings at" in text, text
        print("ok at 4 kHz no ring in 12 lines; the panel: %s" % text)


def screenshot(b):
    b.eval("document.getElementById('loop').scrollIntoView({block: 'end'})")
    wait_for(b, "document.getElementById('bode').width > 0", "the loop panel drawn")
    shot(b, shots, "live-loop.png")


def main(b):
    margins(b)
    tune(b)
    ring(b)
    screenshot(b)


run(main, chromium, url, 1024, 768)
