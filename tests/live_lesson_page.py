#!/usr/bin/python3
"""A lesson's page in headless Chromium at 1024 x 768 (tests/cli_live_lesson.sh): the
title and instructions shown; the hidden controls not drawn, the locked ones not
editable; the loop box saying "not judged yet" at the first status (judged 0) and
"steady" or "lags" only once a line was judged, naming it; amplitude and peak-force
images beside the others; pause stops the lines (the button then reads "resume"), step
runs one line, resume runs on, restart starts a new frame at line 0; at P = 5 the warning suggests a P with the I. With a shots folder, docs/live-lesson.png.

usage: live_lesson_page.py CHROMIUM URL SHOTS_DIR"""
import json
import sys
import time

from live_cdp import Browser, shot, wait_for

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]


def visible(b, sel):
    return b.eval("(() => { const e = document.querySelector('%s'); return !!(e && e.offsetParent); })()" % sel)


def main(b):
    wait_for(b, "window.tiptapLive && tiptapLive.status != null && tiptapLive.controls.length > 0",
             "the first status")
    first = b.eval("tiptapLive.firstLoopText")
    assert "not judged" in first, "the first status's loop text: %r" % first
    print("ok before the first line is judged the page says: %s" % first)
    assert b.eval("document.getElementById('lessontitle').textContent") == "Tuning the I gain"
    text = b.eval("document.getElementById('lessontext').innerText")
    assert "Raise the I gain" in text and "suggestion" in text, text
    assert visible(b, "#lesson"), "the lesson box is not shown"
    print("ok the lesson's title and instructions are shown")
    for name in ("noise", "solver.tier"):
        assert not visible(b, '[data-name="%s"]' % name), name + " is shown"
    for name in ("scan.size", "scan.pixels"):
        assert visible(b, '[data-name="%s"]' % name) and \
            b.eval('document.querySelector(\'[data-name="%s"]\').disabled' % name), name + " is editable"
    assert not b.eval('document.querySelector(\'[data-name="feedback.integral_gain"]\').disabled')
    print("ok noise and tier hidden, scan size and pixels shown and locked, I gain free")
    for ch in ("height", "error", "phase", "amplitude", "peak_force"):
        assert b.eval("!!document.getElementById('img-%s-trace')" % ch), ch + " image missing"
    print("ok height, error, phase, amplitude and peak-force images")
    wait_for(b, "tiptapLive.status.judged > 0 && tiptapLive.rows > 1", "a judged line")
    g = b.eval("document.getElementById('goodloop').hidden ? document.getElementById('warning').textContent"
               " : document.getElementById('goodloop').textContent")
    assert "line " in g and "not judged" not in g, g
    print("ok once judged: %s" % " ".join(g.split()))
    # pause: the line stays; step: one more; resume
    b.eval("document.getElementById('pause').click()")
    wait_for(b, "tiptapLive.status.paused && !tiptapLive.status.running && "
                "document.getElementById('pause').textContent == 'resume'",
             "paused, no line under way, the button reading resume")
    line = b.eval("tiptapLive.status.line")
    rows = b.eval("tiptapLive.rows")
    time.sleep(3)
    assert b.eval("tiptapLive.status.line") == line and b.eval("tiptapLive.rows") == rows, "lines ran while paused"
    print("ok paused: line %d and %d rows unchanged over 3 s" % (line, rows))
    b.eval("document.getElementById('stepline').click()")
    lines = b.eval("tiptapLive.frame.lines")
    wait_for(b, "tiptapLive.status.line == %d && !tiptapLive.status.running" % ((line + 1) % lines),
             "the step's line")
    time.sleep(3)
    assert b.eval("tiptapLive.status.line") == (line + 1) % lines, "more than one line for a step"
    print("ok step: one line, %d to %d" % (line, (line + 1) % lines))
    shot(b, shots, "live-lesson.png")
    b.eval("document.getElementById('pause').click()")
    wait_for(b, "!tiptapLive.status.paused && tiptapLive.status.line != %d" % ((line + 1) % lines),
             "lines again after resume")
    print("ok resumed")
    # restart: a new frame from line 0, engaged afresh (the button sends the protocol's restart)
    frame0 = b.eval("tiptapLive.status.frame")
    b.eval("document.getElementById('restart').click()")
    wait_for(b, "tiptapLive.frame.frame > %d && tiptapLive.status.frame > %d && tiptapLive.status.passes == 0 "
                "&& tiptapLive.status.lines_done < 3" % (frame0, frame0), "a new frame after restart")
    blank = b.eval("(() => { const r = tiptapLive.images.height_trace, n = tiptapLive.frame.pixels; "
                   "let k = 0; for (let l = 0; l < tiptapLive.frame.lines; l++) k += isFinite(r[l * n]) ? 0 : 1; "
                   "return k; })()")
    assert blank >= b.eval("tiptapLive.frame.lines") - 3, "the new frame holds %d blank lines" % blank
    print("ok restart: frame %d to %d, from line 0 (%d of %d lines blank)"
          % (frame0, b.eval("tiptapLive.status.frame"), blank, b.eval("tiptapLive.frame.lines")))
    # P as the cause: at P = 5 the loop rings and the warning offers a P with the I
    b.eval("tiptapSet('feedback.proportional_gain', '5')")
    wait_for(b, "tiptapLive.status.oscillating && !document.getElementById('usepgain').hidden",
             "the warning's P suggestion at P = 5")
    w = " ".join(b.eval("document.getElementById('warning').textContent").split())
    assert "P is too high for the model: use P" in w and "line " in w, w
    st = b.eval("JSON.stringify([tiptapLive.status.height_range, tiptapLive.status.surface_range])")
    print("ok at P = 5: %s (the judged line's pixels span %.3g nm over a relief of %.3g nm)"
          % ((w,) + tuple(x * 1e9 for x in json.loads(st))))


try:
    br = Browser(chromium)
    try:
        br.open_page(url, 1024, 768)
        main(br)
    finally:
        br.close()
except (AssertionError, RuntimeError) as e:
    print("FAIL %s" % e)
    sys.exit(1)
