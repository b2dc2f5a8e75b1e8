#!/usr/bin/python3
"""The console's benches in headless Chromium at 1024 x 768 (tests/cli_live_bench.sh):

  * a refused ramp value (a speed of 0) shows the config layer's line and its field
    returns to the value in force; an accepted range shows in its field;
  * the force panel's curve, run at the page's request, has the pull-off force and the
    jump-in that `tiptap force` gives on the same scene and ramp (the same seed: equal to
    the 6 digits tiptap force prints), both marked and read out;
  * the thermal tune runs beside the scan (its lines go on), and its k is within its stated uncertainty (two standard errors: the band
    holding 95 % of seeds) of the scene's k, and equals `tiptap tune`'s on the same scene;
    a lever of one mode sends one mode and draws one zoom (tests/live_bench_modes.py:
    several).
With a shots folder, docs/live-force.png (docs/live-tune.png: tests/live_bench_modes.py).

usage: live_bench.py CHROMIUM URL SHOTS_DIR PULLOFF_N JUMPIN_N K_SCENE K_TUNE"""
import sys

from live_cdp import run, shot, wait_for

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]
pulloff, jumpin, k_scene, k_tune = (float(x) for x in sys.argv[4:8])


def close(a, b, rel=1e-5):
    return a is not None and abs(a - b) <= rel * abs(b)


def field(b, name):
    return b.eval("document.querySelector('[data-name=\"%s\"]').value" % name)


def main(b):
    for panel in ("forcepanel", "tunepanel"):
        assert b.eval("!!document.getElementById('%s').offsetParent" % panel), panel + " is not shown"
    print("ok the force and tune panels are shown, with their knobs: speed %s um/s, range %s nm, record %s s"
          % (field(b, "force.speed"), field(b, "force.range"), field(b, "tune.duration")))

    # a refused ramp value: the layer's line, the field back at the value in force
    b.eval("tiptapSet('force.speed', '0')")
    msg = wait_for(b, "!tiptapLive.lastReply || tiptapLive.lastReply.ok ? '' : "
                      "document.getElementById('reply').textContent", "the refusal of a speed of 0")
    assert "[force] speed" in msg, msg
    wait_for(b, "document.querySelector('[data-name=\"force.speed\"]').value === '1'", "the speed field restored")
    print("ok a ramp speed of 0 is refused (%s) and the field shows 1 um/s again" % msg)
    n = b.eval("tiptapLive.replies")
    b.eval("tiptapSet('force.range', '30')")
    wait_for(b, "tiptapLive.replies > %d && tiptapLive.lastReply.ok" % n, "the range accepted")
    wait_for(b, "tiptapLive.controls.find((c) => c.name === 'force.range').value === '30'", "the range in force")
    print("ok a ramp range of 30 nm accepted")

    # the force curve
    b.eval("document.getElementById('runforce').click()")
    wait_for(b, "tiptapLive.bench.forces > 0", "the force curve")
    m = b.eval("tiptapLive.bench.force")
    assert close(m["pulloff_force"], pulloff), "pull-off %s N, tiptap force's %s N" % (m["pulloff_force"], pulloff)
    assert close(m["jumpin_force"], jumpin), "jump-in %s N, tiptap force's %s N" % (m["jumpin_force"], jumpin)
    assert m["pulloff_separation"] is not None and m["jumpin_separation"] is not None, m
    assert len(m["z"]) == len(m["force"]) == len(m["separation"]) > 1000, len(m["z"])
    read = b.eval("document.getElementById('forceread').textContent")
    assert ("%.3g nN" % (pulloff * 1e9)) in read and ("%.3g nN" % (jumpin * 1e9)) in read, read
    print("ok the force panel's pull-off %.6g nN and jump-in %.6g nN equal tiptap force's (%.6g, %.6g); read out: %s"
          % (m["pulloff_force"] * 1e9, m["jumpin_force"] * 1e9, pulloff * 1e9, jumpin * 1e9, read))
    b.eval("document.getElementById('forcepanel').scrollIntoView()")
    shot(b, shots, "live-force.png")

    # the thermal tune, on its own thread: the scan's lines go on meanwhile
    # lines run, counted over the passes (lines_done stops at the frame's lines after the
    # first pass, which the averaged tier's lines finish before the tune)
    run = "tiptapLive.status.passes * tiptapLive.frame.lines + tiptapLive.status.line"
    lines0 = b.eval(run)
    b.eval("document.getElementById('runtune').click()")
    wait_for(b, "document.getElementById('runtune').disabled", "the tune under way")
    wait_for(b, "tiptapLive.bench.tunes > 0", "the thermal tune")
    lines1 = b.eval(run)
    assert lines1 > lines0, "no line ran during the tune (%s, then %s)" % (lines0, lines1)
    print("ok the scan ran %d lines while the tune ran beside it" % (lines1 - lines0))
    t = b.eval("tiptapLive.bench.tune")
    off = abs(t["k"] - k_scene) / t["k_err"]
    assert t["k_scene"] == k_scene, "the tune's scene k %s, the scene's %s" % (t["k_scene"], k_scene)
    assert off <= 2, "k = %s +- %s N/m, %.2f standard errors from the scene's %s" % (t["k"], t["k_err"], off, k_scene)
    assert close(t["k"], k_tune), "k %s, tiptap tune's %s" % (t["k"], k_tune)
    assert len(t["f"]) > 50 and t["f0"] > 0 and t["Q_err"] > 0, t
    assert len(t["modes"]) == 1 and t["modes"][0]["k"] == t["k"], t["modes"]
    assert not b.eval("!!document.getElementById('tunezoom2')"), "a second zoom for one mode"
    read = b.eval("document.getElementById('tuneread').textContent")
    assert "k = " in read and "Q = " in read and "\u00b1" in read, read
    print("ok the tune's k = %.4g +- %.2g N/m is %.2f standard errors from the scene's %g N/m and equals "
          "tiptap tune's %.6g; read out: %s" % (t["k"], t["k_err"], off, k_scene, k_tune, read))


run(main, chromium, url, 1024, 768)
