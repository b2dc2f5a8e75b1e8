#!/usr/bin/python3
"""The console's display in a real browser (headless Chromium over the DevTools protocol,
tests/live_cdp.py), at a projector's 1024 x 768: no text under 13 px; a field shows the
value in force (a refused value put back, a change in force shown in a focused field,
unsent text kept and marked stale; the setpoint in % as the scene writes it, nm beside it); two pages are two instruments (a gain changed on one
does not reach the other, nor its exported scene); an image's colour range (1 to 99 %, frame, manual) and line flatten
(offset, slope) give the pixels they say, read back from the canvas; the scope's hold,
cursor read-out, zoom, time axis and stored reference, whose legend names the gains its line ran
with (a line under way at a change arrives after it).

usage: live_display.py CHROMIUM URL SHOTS_DIR
Prints 'ok ...' / 'FAIL ...' lines; exits 1 on the first failure."""
import json
import sys
import time

from live_cdp import run, shot, wait_for

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]
KI = '[data-name="feedback.integral_gain"]'
SP = '[data-name="feedback.setpoint"]'
TOP = (255, 250, 220)  # the height map's ends (web/live.js)
BOTTOM = (0, 0, 0)


def js(b, expr, session=True):
    """expr's value, carried as JSON (NaN as null)."""
    return json.loads(b.eval("JSON.stringify(%s)" % expr, session))


def field(b, sel, session=True):
    return b.eval("document.querySelector('%s').value" % sel, session)


def in_force(b, name, session=True):
    return b.eval("tiptapLive.controls.find(c => c.name === '%s').value" % name, session)


def choose(b, sel, value):
    """A select or text field set as a user does: the value, then its change event."""
    b.eval("(() => { const e = document.querySelector('%s'); e.value = %s; "
           "e.dispatchEvent(new Event('change')); })()" % (sel, json.dumps(value)))


def readable(b):
    # every visible element with text of its own, and every field, at its computed size
    small = js(b, """(() => {
      const out = [];
      for (const e of document.querySelectorAll('body *')) {
        if (!e.getClientRects().length || getComputedStyle(e).visibility === 'hidden') continue;
        const own = Array.from(e.childNodes).some(n => n.nodeType === 3 && n.textContent.trim());
        if (!own && !/^(INPUT|SELECT|BUTTON)$/.test(e.tagName)) continue;
        const px = parseFloat(getComputedStyle(e).fontSize);
        out.push([px, e.tagName + (e.id ? '#' + e.id : '') + ' ' + (e.textContent || e.value || '').trim().slice(0, 30)]);
      }
      out.sort((a, b) => a[0] - b[0]);
      return {n: out.length, smallest: out.slice(0, 3), scope: tiptapLive.scopeTextPx};
    })()""")
    assert small["n"] > 50, small
    assert small["smallest"][0][0] >= 13, "text under 13 px at 1024 x 768: %s" % small["smallest"]
    assert small["scope"] >= 13, "the scope's labels at %.1f px" % small["scope"]
    print("ok no text under 13 px at 1024 x 768 (%d elements; smallest %s px; the scope's labels %.1f px)"
          % (small["n"], small["smallest"][0][0], small["scope"]))


def fields(b, url):
    # before any change: no latency shown; P gain with its unit; the every tier's hint
    status = b.eval("document.getElementById('status').textContent")
    assert "last change" not in status, status
    unit = b.eval("document.querySelector('[data-name=\"feedback.proportional_gain\"]')"
                  ".parentNode.querySelector('.unit').textContent")
    assert unit == "m/m", unit
    every = b.eval("document.querySelector('[data-name=\"solver.tier\"] option[value=every]').title")
    assert "slower than real time" in every, every
    # the tier menu is the server's table (the controls message), in its order, each with its
    # hint as its tooltip; the line under the menu gives the hint of the tier in force
    menu = b.eval("[...document.querySelectorAll('[data-name=\"solver.tier\"] option')]"
                  ".map(o => [o.value, o.title])")
    table = b.eval("tiptapLive.tierTable")
    assert [t["name"] for t in table] == ["every", "envelope", "averaged"], table
    assert menu == [[t["name"], t["hint"]] for t in table], (menu, table)
    setpoint(b)
    line = b.eval("document.getElementById('c-solver-tier-hint').textContent")
    tier = in_force(b, "solver.tier")
    assert line == tier + ": " + next(t["hint"] for t in table if t["name"] == tier), line
    icon = b.eval("document.querySelector('link[rel=icon]').href")
    code = b.call("Runtime.evaluate", {"expression": "fetch('%s').then(r => r.status)" % icon,
                                       "awaitPromise": True, "returnByValue": True})["result"]["value"]
    assert code == 200, (icon, code)
    print("ok before any change: no 'last change'; P gain in %s; '%s'; the icon %s served (%d)"
          % (unit, every, icon, code))

    sp0 = in_force(b, "feedback.setpoint")
    # a refused value typed into the field and sent with Enter, the field keeping the focus:
    # it returns to the value in force (the issue's -5 left in the field)
    ki0 = in_force(b, "feedback.integral_gain")
    assert field(b, KI) == ki0, (field(b, KI), ki0)
    replies = b.eval("tiptapLive.replies")
    b.eval("(() => { const e = document.querySelector('%s'); e.focus(); e.select(); })()" % KI)
    b.call("Input.insertText", {"text": "-5"})
    assert field(b, KI) == "-5", field(b, KI)
    b.call("Input.dispatchKeyEvent", {"type": "keyDown", "key": "Enter", "code": "Enter",
                                      "windowsVirtualKeyCode": 13, "text": "\r"})
    b.call("Input.dispatchKeyEvent", {"type": "keyUp", "key": "Enter", "code": "Enter",
                                      "windowsVirtualKeyCode": 13})
    msg = wait_for(b, "tiptapLive.replies > %d && !tiptapLive.lastReply.ok && "
                      "document.getElementById('reply').textContent" % replies, "the refusal")
    assert b.eval("document.activeElement === document.querySelector('%s')" % KI), "the field lost the focus"
    assert field(b, KI) == ki0, "the field holds %r after '%s'; in force: %s" % (field(b, KI), msg, ki0)
    print("ok -5 Hz typed and sent with Enter is refused (%s); the focused field shows the value in "
          "force again, %s" % (msg, ki0))

    # two pages are two instruments: a gain changed on the second does not reach the first
    a = b.session
    other = b.open_page(url, 1024, 768)
    wait_for(b, "window.tiptapLive && tiptapLive.controls.length > 0 && tiptapLive.status", "the second page's controls")
    mine, theirs = b.eval("tiptapLive.instrument", a), b.eval("tiptapLive.instrument", other)
    assert mine and theirs and mine != theirs, (mine, theirs)
    b.eval("tiptapSet('feedback.integral_gain', '1500')", other)
    wait_for(b, "tiptapLive.lastReply && tiptapLive.lastReply.ok && tiptapLive.controls.find(c => "
                "c.name === 'feedback.integral_gain').value === '1500'", "1500 Hz in force on the second page")
    # a line run on the second page since: its engine took the change (an export is
    # written between two lines, of the scene the image was made at)
    new_scope(b, "a line at 1500 Hz on the second page")
    b.session = a
    frame_a = b.eval("tiptapLive.status.frame * 1e6 + tiptapLive.status.line")
    # (!==: the line after a pass's last is line 0 of the next pass, in the same frame)
    wait_for(b, "tiptapLive.status.frame * 1e6 + tiptapLive.status.line !== %d" % frame_a, "a line more on the first page")
    assert in_force(b, "feedback.integral_gain") == ki0 and field(b, KI) == ki0, (in_force(b, "feedback.integral_gain"), field(b, KI))
    scenes = [b.call("Runtime.evaluate", {"expression": "fetch('/export/%d/scene.ini').then(r => r.text())" % n,
                                          "awaitPromise": True, "returnByValue": True})["result"]["value"]
              for n in (mine, theirs)]
    gains = [[l for l in t.splitlines() if l.startswith("integral_gain")] for t in scenes]
    assert gains == [["integral_gain = %s Hz" % ki0], ["integral_gain = 1500 Hz"]], gains
    print("ok two pages, two instruments (%d and %d): 1500 Hz on the second; the first keeps %s Hz "
          "in force, in its field and in its exported scene (%s against %s)" % (mine, theirs, ki0, gains[0], gains[1]))

    # a focused field whose value changes in force (here a message sent on the page's own
    # socket, not through the field) shows the new value
    b.eval("document.querySelector('%s').focus()" % KI)
    b.eval("tiptapLive.ws.send('set feedback.integral_gain = 1200 Hz')")
    wait_for(b, "document.activeElement === document.querySelector('%s') && "
                "document.querySelector('%s').value === '1200'" % (KI, KI), "the focused field updated")
    print("ok a change in force shows in the focused I gain field: 1200")

    # text typed and not yet sent is kept while the value in force changes under it, marked
    # stale with the value in force, then put back on leaving
    b.eval("(() => { const e = document.querySelector('%s'); e.focus(); e.value = '85'; "
           "e.dispatchEvent(new Event('input')); })()" % SP)
    b.eval("tiptapLive.ws.send('set feedback.setpoint = 18 nm')")
    wait_for(b, "tiptapLive.controls.find(c => c.name === 'feedback.setpoint').value === '90'", "18 nm (90 %) in force")
    assert field(b, SP) == "85", field(b, SP)
    stale = b.eval("(() => { const e = document.querySelector('%s'); return e.classList.contains('stale') + ' ' + e.title; })()" % SP)
    assert stale.startswith("true") and "90" in stale, stale
    b.eval("document.querySelector('%s').blur()" % SP)
    assert field(b, SP) == "90" and not b.eval("document.querySelector('%s').classList.contains('stale')" % SP), field(b, SP)
    print("ok unsent text (setpoint 85) kept and marked stale ('%s') while 18 nm (90 %%) came into force; "
          "put back to 90 on leaving the field" % stale[5:])
    b.eval("tiptapLive.ws.send('set feedback.integral_gain = %s Hz\\nset feedback.setpoint = %s %%')" % (ki0, sp0))
    wait_for(b, "tiptapLive.controls.find(c => c.name === 'feedback.setpoint').value === '%s'" % sp0, "the setpoint back")
    b.call("Target.closeTarget", {"targetId": b.targets[other]}, session=False)
    wait_for(b, "tiptapLive.status && tiptapLive.status.preview_ms > 0 && "
                "document.getElementById('status').textContent.includes('last change')",
             "the latency shown after a change")
    print("ok after a change: %s" % b.eval("document.getElementById('status').textContent"))


def exported_setpoint(b):
    text = b.call("Runtime.evaluate", {"expression": "fetch('/export/' + tiptapLive.instrument + '/scene.ini')"
                                       ".then(r => r.text())", "awaitPromise": True, "returnByValue": True})["result"]["value"]
    return [l for l in text.splitlines() if l.startswith("setpoint")]


def setpoint(b):
    """The setpoint in % of the free amplitude, as the scene writes it, with its nm beside
    it: a bare number is taken in %, a value in nm as such; a refusal in %, the field put
    back; the exported scene keeps the scene's form (75 %)."""
    readout = "document.getElementById('c-feedback-setpoint-hint').textContent"
    unit = b.eval("document.querySelector('%s').parentNode.querySelector('.unit').textContent" % SP)
    assert (field(b, SP), unit, b.eval(readout)) == ("80", "%", "= 16.0 nm"), (field(b, SP), unit, b.eval(readout))
    # the read-out on the field's row, to its right (not a line under it)
    rows = js(b, "[document.querySelector('%s'), document.getElementById('c-feedback-setpoint-hint')]"
                 ".map(e => { const r = e.getBoundingClientRect(); return [r.left, r.right, r.top, r.bottom]; })" % SP)
    assert rows[1][0] >= rows[0][1] and rows[1][2] < rows[0][3] and rows[1][3] > rows[0][2], rows
    # and whole, inside the controls' column
    fits = js(b, "(() => { const h = document.getElementById('c-feedback-setpoint-hint'), "
                 "f = document.getElementById('controls').getBoundingClientRect(); "
                 "return [h.scrollWidth, h.clientWidth, h.getBoundingClientRect().right, f.right]; })()")
    assert fits[0] <= fits[1] and fits[2] <= fits[3] + 0.5, "the read-out does not fit: %s" % fits
    b.eval("tiptapSet('feedback.setpoint', '75')")
    wait_for(b, "tiptapLive.controls.find(c => c.name === 'feedback.setpoint').value === '75' && %s === '= 15.0 nm'"
             % readout, "75 % in force, 15 nm")
    assert field(b, SP) == "75", field(b, SP)
    new_scope(b, "a line at 75 %")  # an export holds the scene its image was made at
    exported = exported_setpoint(b)
    assert exported == ["setpoint = 75 %"], exported
    # the setpoint stays a share of the free amplitude when that changes, as in the scene
    b.eval("tiptapSet('cantilever.free_amplitude', '24')")
    wait_for(b, "tiptapLive.controls.find(c => c.name === 'cantilever.free_amplitude').value === '24' && "
                "%s === '= 18.0 nm'" % readout, "75 % of 24 nm")
    assert field(b, SP) == "75", field(b, SP)
    b.eval("tiptapSet('cantilever.free_amplitude', '20')")
    wait_for(b, "tiptapLive.controls.find(c => c.name === 'cantilever.free_amplitude').value === '20' && "
                "%s === '= 15.0 nm'" % readout, "20 nm again")
    # refused in %: the reply gives the range in %, the field shows the value in force again
    replies = b.eval("tiptapLive.replies")
    b.eval("tiptapSet('feedback.setpoint', '120')")
    msg = wait_for(b, "tiptapLive.replies > %d && !tiptapLive.lastReply.ok && "
                      "document.getElementById('reply').textContent" % replies, "120 % refused")
    assert "100 %" in msg and "nm" not in msg, msg
    wait_for(b, "document.querySelector('%s').value === '75'" % SP, "the field back to 75")
    b.eval("tiptapSet('feedback.setpoint', '0')")
    msg0 = wait_for(b, "!tiptapLive.lastReply.ok && document.getElementById('reply').textContent !== %s && "
                       "document.getElementById('reply').textContent" % json.dumps(msg), "0 % refused")
    assert "expected above 0 %" in msg0, msg0
    wait_for(b, "document.querySelector('%s').value === '75'" % SP, "the field back to 75")
    # a value typed in nm is taken as such and shown in %
    b.eval("tiptapSet('feedback.setpoint', '16 nm')")
    wait_for(b, "tiptapLive.controls.find(c => c.name === 'feedback.setpoint').value === '80' && %s === '= 16.0 nm'"
             % readout, "16 nm in force, 80 %")
    print("ok the setpoint in %%: 80 %% (= 16.0 nm beside it), 75 typed came into force as 75 %% (15 nm; "
          "exported '%s'), 18 nm at a free amplitude of 24 nm; 120 refused ('%s'), 0 refused ('%s'), "
          "the field put back to 75; 16 nm typed shows 80" % (exported[0], msg, msg0))


def hidden_tab(b, url):
    """A tab behind another (the Page Visibility API: document.hidden) idles its instrument:
    no line runs while hidden; shown, it runs; put behind again, it idles again."""
    a = b.session
    other = b.open_page(url, 1024, 768, background=True)
    # the first tab brought to the front as well: a background target alone was seen
    # to stay visible to its page in 2 of 7 runs on a loaded machine
    b.call("Target.activateTarget", {"targetId": b.targets[a]}, session=False)
    # (the line under way when the page said so ends first)
    wait_for(b, "window.tiptapLive && tiptapLive.status && document.hidden && tiptapLive.status.idle "
                "&& !tiptapLive.status.running", "the hidden tab's instrument idle")
    at = lambda: b.eval("tiptapLive.status.frame * 1e6 + tiptapLive.status.line")
    line0, scopes0 = at(), b.eval("tiptapLive.scopes")
    time.sleep(3)  # 12 lines' time at 4 Hz
    assert at() == line0 and b.eval("tiptapLive.scopes") == scopes0, (line0, at())
    state = b.eval("document.getElementById('runstate').textContent")
    assert "hidden" in state, state
    print("ok a hidden tab's instrument idles: no line in 3 s (line %d); '%s'" % (line0 % 1e6, state))
    b.call("Target.activateTarget", {"targetId": b.targets[other]}, session=False)
    wait_for(b, "!document.hidden && !tiptapLive.status.idle && "
                "tiptapLive.status.frame * 1e6 + tiptapLive.status.line !== %d" % line0, "a line once shown")
    print("ok shown, it runs: line %d" % (at() % 1e6))
    b.call("Target.activateTarget", {"targetId": b.targets[a]}, session=False)
    wait_for(b, "document.hidden && tiptapLive.status.idle", "idle again once behind the first tab")
    print("ok behind the first tab again, idle again")
    b.call("Target.closeTarget", {"targetId": b.targets[other]}, session=False)
    b.session = a
    assert not b.eval("document.hidden"), "the first tab hidden"


IMG = "height_trace"


def image(b):
    """raw data, the data as shown with its range, the canvas's pixels: one moment."""
    return js(b, """(() => {
      const f = tiptapLive.frame, cv = document.getElementById('img-height-trace');
      const s = tiptapLive.shown['%s'];
      return {raw: Array.from(tiptapLive.images['%s']), shown: Array.from(s.data), lo: s.lo, hi: s.hi,
              pixels: f.pixels, lines: f.lines, fast_y: f.fast_y, w: cv.width,
              rgba: Array.from(cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data),
              ticks: Array.from(document.querySelectorAll('#ticks-height-trace .tick')).map(t => t.textContent)};
    })()""" % (IMG, IMG))


def rgb(im, k):
    l, i = divmod(k, im["pixels"])
    x, y = (l, i) if im["fast_y"] else (i, l)
    o = 4 * (y * im["w"] + x)
    return tuple(im["rgba"][o:o + 3])


def percentile(sorted_, q):
    x = q * (len(sorted_) - 1)
    i = int(x)
    return sorted_[i] + (sorted_[i + 1] - sorted_[i]) * (x - i) if i + 1 < len(sorted_) else sorted_[i]


def close(a, b, scale):
    return abs(a - b) <= 1e-9 * scale


def images(b):
    wait_for(b, "tiptapLive.status.lines_done >= 6 || tiptapLive.status.passes > 0", "six lines")
    sel = lambda what: "#%s-height-trace" % what
    choose(b, sel("flatten"), "none")
    choose(b, sel("range"), "frame")
    im = image(b)
    fin = sorted(v for v in im["raw"] if v is not None)
    assert len(fin) >= 6 * im["pixels"], len(fin)
    span = fin[-1] - fin[0]
    assert close(im["lo"], fin[0], span) and close(im["hi"], fin[-1], span), (im["lo"], im["hi"], fin[0], fin[-1])
    frame_px = im["rgba"]
    print("ok frame range: %.2f to %.2f nm, the data's extremes" % (im["lo"] * 1e9, im["hi"] * 1e9))

    # typical lines: the 20th percentile of the lines' lowest values to the 80th of their highest
    choose(b, sel("range"), "lines")
    im = image(b)
    n = im["pixels"]
    ext = [(min(r), max(r)) for r in ([v for v in im["raw"][l * n:(l + 1) * n] if v is not None]
                                      for l in range(im["lines"])) if r]
    lo, hi = percentile(sorted(e[0] for e in ext), 0.2), percentile(sorted(e[1] for e in ext), 0.8)
    assert close(im["lo"], lo, span) and close(im["hi"], hi, span), (im["lo"], im["hi"], lo, hi)
    print("ok typical lines: %.2f to %.2f nm, from %d lines' extremes" % (lo * 1e9, hi * 1e9, len(ext)))

    choose(b, sel("range"), "pct")
    im = image(b)
    fin = sorted(v for v in im["raw"] if v is not None)
    p1, p99 = percentile(fin, 0.01), percentile(fin, 0.99)
    assert close(im["lo"], p1, span) and close(im["hi"], p99, span), (im["lo"], im["hi"], p1, p99)
    above = [k for k, v in enumerate(im["raw"]) if v is not None and v > p99]
    below = [k for k, v in enumerate(im["raw"]) if v is not None and v < p1]
    assert above and below, "nothing beyond the 1 and 99 % points"
    assert all(rgb(im, k) == TOP for k in above) and all(rgb(im, k) == BOTTOM for k in below)
    assert im["rgba"] != frame_px, "1 to 99 % drew the frame range's pixels"
    print("ok 1 to 99 %%: %.2f to %.2f nm; the %d pixels above and %d below drawn at the map's ends"
          % (p1 * 1e9, p99 * 1e9, len(above), len(below)))

    # manual: 5 to 15 nm, the grating's walls in colour and its top and bottom at the ends
    choose(b, sel("range"), "manual")
    b.eval("(() => { const a = document.getElementById('min-height-trace'), "
           "c = document.getElementById('max-height-trace'); a.value = '5'; c.value = '15'; "
           "c.dispatchEvent(new Event('change')); })()")
    im = image(b)
    assert close(im["lo"], 5e-9, 1e-9) and close(im["hi"], 15e-9, 1e-9), (im["lo"], im["hi"])
    over = [k for k, v in enumerate(im["raw"]) if v is not None and v > 15e-9]
    under = [k for k, v in enumerate(im["raw"]) if v is not None and v < 5e-9]
    assert over and under
    assert all(rgb(im, k) == TOP for k in over) and all(rgb(im, k) == BOTTOM for k in under)
    assert "10" in im["ticks"], im["ticks"]
    print("ok manual 5 to 15 nm: %d pixels above at the top colour, %d below black; colour bar ticks %s nm"
          % (len(over), len(under), im["ticks"]))

    # flatten: each whole line's mean (offset) or least-squares line (slope) taken off
    choose(b, sel("range"), "frame")
    for how in ("offset", "slope"):
        choose(b, sel("flatten"), how)
        im = image(b)
        n, worst, lines = im["pixels"], 0.0, 0
        for l in range(im["lines"]):
            raw = im["raw"][l * n:(l + 1) * n]
            if any(v is None for v in raw):
                continue
            lines += 1
            mean = sum(raw) / n
            xm = (n - 1) / 2
            slope = sum((i - xm) * (v - mean) for i, v in enumerate(raw)) / sum((i - xm) ** 2 for i in range(n))
            for i, v in enumerate(raw):
                want = v - mean - (slope * (i - xm) if how == "slope" else 0)
                worst = max(worst, abs(im["shown"][l * n + i] - want))
        assert lines >= 6 and worst < 1e-6 * span, (lines, worst)
        assert im["rgba"] != frame_px, "%s flatten drew the unflattened pixels" % how
        print("ok flatten %s: %d whole lines as computed here (largest difference %.1e nm); the pixels changed"
              % (how, lines, worst * 1e9))
    choose(b, sel("flatten"), "none")
    choose(b, sel("range"), "lines")


def new_scope(b, what):
    """Waits for the scope of a line that started after the change just accepted, on the
    scan's own tier (the line under way, if any, ran at the settings before). The console
    runs its lines over and over in one frame, so the line after the last is line 0 of the
    next pass: a new line is one of a later frame, or one neither the line under way nor
    the one before it (whose scope may still be on its way)."""
    s = js(b, "({frame: tiptapLive.status.frame, line: tiptapLive.status.line, "
              "lines: tiptapLive.frame ? tiptapLive.frame.lines : 0, n: tiptapLive.scopes})")
    before = (s["line"] - 1) % s["lines"] if s["lines"] else s["line"] - 1
    wait_for(b, "tiptapLive.scopes > %d && tiptapLive.scope.tier !== 'averaged' && "
                "(tiptapLive.scope.frame > %d || (tiptapLive.scope.line !== %d && tiptapLive.scope.line !== %d))"
             % (s["n"], s["frame"], s["line"], before), what)


def orange(b):
    """Pixels of the reference trace's colour on the scope."""
    return b.eval("""(() => { const cv = document.getElementById('scope');
      const d = cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data; let n = 0;
      for (let i = 0; i < d.length; i += 4)
        if (Math.abs(d[i] - 239) < 24 && Math.abs(d[i + 1] - 108) < 24 && d[i + 2] < 40) n++;
      return n; })()""")


def scope_hash(b):
    return b.eval("""(() => { const cv = document.getElementById('scope');
      const d = cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data; let h = 0;
      for (let i = 0; i < d.length; i += 7) h = (h * 31 + d[i]) | 0; return h; })()""")


def mouse(b, kind, x, y, buttons=0):
    b.call("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": "left" if kind != "mouseMoved" or buttons else "none",
                                        "buttons": buttons, "clickCount": 1})


def scope(b):
    b.eval("document.getElementById('scope').scrollIntoView()")
    geo = lambda: js(b, "(() => { const r = document.getElementById('scope').getBoundingClientRect(), "
                        "g = tiptapLive.scopeGeom; return {left: r.left, top: r.top, x0: g.x0, x1: g.x1, "
                        "gl: g.g.left, pw: g.g.pw, p0: g.panels[0].y0, ph: g.g.ph}; })()")
    # ticks at 1, 2 or 5 times a power of ten across each axis, a grid line at each
    t = js(b, """(() => { const g = tiptapLive.scopeGeom, cv = document.getElementById('scope');
      const d = cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data, W = cv.width;
      const X = (x) => g.g.left + (x - g.x0) / (g.x1 - g.x0) * g.g.pw;
      const p = g.panels[0], Y = (v) => p.y0 + g.g.ph - (v - p.lo) / (p.hi - p.lo) * g.g.ph;
      const grey = (i) => d[i] === 227 && d[i + 1] === 227 && d[i + 2] === 227;
      // along each grid line inside the first panel, the share of its pixels in the grid's grey
      const col = g.xticks.map((x) => { let n = 0, k = 0; const c = Math.round(X(x));
        for (let y = Math.ceil(p.y0) + 2; y < p.y0 + g.g.ph - 2; y++, k++) n += grey(4 * (y * W + c)); return n / k; });
      const row = p.yticks.map((v) => { let n = 0, k = 0; const r = Math.round(Y(v));
        for (let x = Math.ceil(g.g.left) + 2; x < g.g.left + g.g.pw - 2; x++, k++) n += grey(4 * (r * W + x)); return n / k; });
      return {x: g.xticks, xstep: g.xstep, y: p.yticks, ystep: p.ystep, x0: g.x0, x1: g.x1, lo: p.lo, hi: p.hi,
              col, row, panels: g.panels.map((q) => q.yticks.length)}; })()""")
    nice = lambda step: any(abs(step / (m * 10 ** round(__import__("math").log10(step / m))) - 1) < 1e-9 for m in (1, 2, 5))
    assert len(t["x"]) >= 3 and nice(t["xstep"]) and t["x0"] <= t["x"][0] and t["x"][-1] <= t["x1"], t
    assert all(abs(b_ - a_ - t["xstep"]) < 1e-9 * t["xstep"] for a_, b_ in zip(t["x"], t["x"][1:])), t
    assert len(t["y"]) >= 2 and nice(t["ystep"]) and t["lo"] <= t["y"][0] and t["y"][-1] <= t["hi"], t
    assert min(t["panels"]) >= 2, t["panels"]
    # (a line on the panel's border, or under the grating's walls drawn on it, is covered)
    lines = sorted(t["col"] + t["row"])
    assert lines[len(lines) // 2] > 0.8 and sum(v > 0.3 for v in t["row"]) >= 2, (t["col"], t["row"])
    print("ok scope ticks: x every %g nm (%d), z every %g nm (%d), %s ticks on the panels; the median grid "
          "line %.0f %% grey" % (t["xstep"], len(t["x"]), t["ystep"], len(t["y"]), t["panels"],
                                 100 * lines[len(lines) // 2]))

    # hold: new scopes come, the one shown stays
    b.eval("document.getElementById('hold').click()")
    line, n = b.eval("tiptapLive.scopeShown.line"), b.eval("tiptapLive.scopes")
    h = scope_hash(b)
    wait_for(b, "tiptapLive.scopes >= %d && tiptapLive.scope.line !== %d" % (n + 2, line), "two more scopes")
    assert b.eval("tiptapLive.scopeShown.line") == line and scope_hash(b) == h
    print("ok hold: line %d stays on the scope while lines %d and on arrive" % (line, b.eval("tiptapLive.scope.line")))

    # the cursor: the values of each line's point nearest to it
    g = geo()
    px, py = g["left"] + 1 + g["gl"] + 0.37 * g["pw"], g["top"] + 1 + g["p0"] + g["ph"] / 2
    mouse(b, "mouseMoved", px, py)
    cur = b.eval("tiptapLive.cursor")
    want_x = g["x0"] + 0.37 * (g["x1"] - g["x0"])
    assert cur is not None and abs(cur - want_x) < 0.01 * (g["x1"] - g["x0"]), (cur, want_x)
    s = js(b, "tiptapLive.scopeShown")
    vals = js(b, "tiptapLive.cursorValues")
    got = {v["series"]: v for v in vals}
    for d in ("trace", "retrace"):
        pos = [p * 1e9 if p is not None else None for p in s[d]["position"]]
        i = min((k for k in range(len(pos)) if pos[k] is not None), key=lambda k: abs(pos[k] - cur))
        assert got[d]["index"] == i and abs(got[d]["z"] - s[d]["z"][i] * 1e9) < 1e-9, (d, got[d], i)
    text = b.eval("document.getElementById('readout').textContent")
    assert ("%.3f" % got["trace"]["z"]) in text, text
    print("ok cursor at %.1f nm: z trace %.3f nm, retrace %.3f nm, as the scope's nearest points"
          % (cur, got["trace"]["z"], got["retrace"]["z"]))

    # zoom: a drag from 20 % to 45 % of the width, + halves, reset
    x0, x1 = g["x0"], g["x1"]
    a, c = g["left"] + 1 + g["gl"] + 0.2 * g["pw"], g["left"] + 1 + g["gl"] + 0.45 * g["pw"]
    mouse(b, "mousePressed", a, py, 1)
    mouse(b, "mouseMoved", (a + c) / 2, py, 1)
    mouse(b, "mouseMoved", c, py, 1)
    mouse(b, "mouseReleased", c, py, 0)
    z = js(b, "tiptapLive.zoom")
    wa, wc = x0 + 0.2 * (x1 - x0), x0 + 0.45 * (x1 - x0)
    assert z and abs(z[0] - wa) < 0.01 * (x1 - x0) and abs(z[1] - wc) < 0.01 * (x1 - x0), (z, wa, wc)
    g2 = geo()
    assert abs(g2["x0"] - z[0]) < 1e-9 * (x1 - x0) and abs(g2["x1"] - z[1]) < 1e-9 * (x1 - x0), g2
    b.eval("document.getElementById('zoomin').click()")
    g3 = geo()
    assert abs((g3["x1"] - g3["x0"]) - (z[1] - z[0]) / 2) < 1e-6 * (x1 - x0), (g3, z)
    b.eval("document.getElementById('zoomreset').click()")
    g4 = geo()
    assert b.eval("tiptapLive.zoom") is None and abs(g4["x0"] - x0) < 1e-9 and abs(g4["x1"] - x1) < 1e-9
    print("ok zoom: the drag showed %.0f to %.0f nm, + halved it, reset: %.0f to %.0f nm" % (z[0], z[1], x0, x1))

    # time: the trace's start to the retrace's end, in ms
    choose(b, "#xmode", "time")
    g5 = geo()
    want = (s["retrace"]["t1"] - s["trace"]["t0"]) * 1e3
    assert abs(g5["x0"]) < 1e-9 and abs(g5["x1"] - want) < 1e-6 * want, (g5, want)
    print("ok time axis: 0 to %.1f ms (the trace's start to the retrace's end)" % want)
    choose(b, "#xmode", "position")

    # reference: the scope shown stored, drawn in orange beside the lines after it, cleared
    assert orange(b) == 0
    b.eval("document.getElementById('storeref').click()")
    stored = b.eval("tiptapLive.reference.line")
    assert stored == line, (stored, line)
    b.eval("document.getElementById('hold').click()")  # released
    # the change sent while a line runs: that line arrives after 2 kHz is in force, and a
    # legend must name the gains it ran with (the scope message's), not those in force
    ki_old = in_force(b, "feedback.integral_gain")
    b.eval("window.scopeLog = []; window.scopeWas = scope; window.scope = (m) => { "
           "scopeWas(m); scopeLog.push([m.line, m.tier, m.ki, m.gains]); }")
    wait_for(b, "tiptapLive.status.running", "a line under way")
    b.eval("tiptapSet('feedback.integral_gain', '2000')")
    wait_for(b, "tiptapLive.lastReply.ok", "2 kHz accepted")
    new_scope(b, "a scope at 2 kHz")
    log = js(b, "scopeLog")
    b.eval("window.scope = scopeWas")
    own = [l for l in log if l[1] != "averaged"]
    new = next(i for i, l in enumerate(own) if l[2] == 2000)
    old = own[:new]
    assert old and all(l[2] == float(ki_old) and l[3].startswith("I gain %s Hz," % ki_old) for l in old), (ki_old, log)
    assert all(l[2] == 2000 and l[3] == "I gain 2000 Hz, P gain 0" for l in own[new:]), log
    assert all(l[2] == 2000 for l in log if l[1] == "averaged"), log
    print("ok a scope's gains are the line's: line %d, under way at the change, came as '%s' with 2 kHz "
          "in force; line %d as '%s'" % (old[0][0], old[0][3], own[new][0], own[new][3]))
    n0 = orange(b)
    assert b.eval("tiptapLive.reference.line") == stored and n0 > 100, n0
    mouse(b, "mouseMoved", px, py)
    rows = [v["series"] for v in js(b, "tiptapLive.cursorValues")]
    assert "reftrace" in rows and "refretrace" in rows, rows
    print("ok reference of line %d (%s) drawn in orange (%d pixels) beside line %d at 2 kHz; "
          "the read-out has its rows" % (stored, b.eval("tiptapLive.referenceNote"), n0, b.eval("tiptapLive.scopeShown.line")))
    b.eval("document.getElementById('clearref').click()")
    assert orange(b) == 0
    print("ok reference cleared")


def ring(b):
    """The issue's case: a few lines rung at 30 kHz make the frame's range ten times the
    grating's; the default range, typical lines', keeps the grating in colour."""
    # early in a pass after the first: every line holds data, and steady lines follow the band
    wait_for(b, "tiptapLive.status.passes > 0 && tiptapLive.status.line >= 2 && tiptapLive.status.line <= 8",
             "an early line of the second pass")
    b.eval("tiptapSet('feedback.integral_gain', '30000')")
    wait_for(b, "tiptapLive.status.oscillating", "the ring at 30 kHz")
    # the warning names the line it judged, and a ring of 100 nm and more is in plain view
    w = " ".join(b.eval("document.getElementById('warning').textContent").split())
    jl = b.eval("tiptapLive.status.judged_line")
    assert ("on line %d:" % jl) in w and "in plain view" in w and "hide it" not in w, w
    print("ok the warning at 30 kHz: %s" % w[:160])
    b.eval("tiptapSet('feedback.integral_gain', '1000')")
    wait_for(b, "(() => { const r = tiptapLive.images.height_trace, s = tiptapLive.shown.height_trace; "
                "return Math.max(...Array.from(r).filter(isFinite)) > 100e-9 && s.hi - s.lo < 40e-9; })()",
             "the ringing band and the grating's range beside it")
    assert b.eval("tiptapLive.view.height_trace.range") == "lines"
    im = image(b)
    fin = [v for v in im["raw"] if v is not None]
    n = im["pixels"]
    rung = sum(1 for l in range(im["lines"]) if any(v is not None and v > 60e-9 for v in im["raw"][l * n:(l + 1) * n]))
    # the grating's 20 nm within a range under twice it, the band's 100 nm and more beyond
    assert -5e-9 < im["lo"] < 5e-9 and 15e-9 < im["hi"] < im["lo"] + 40e-9, (im["lo"], im["hi"])
    fin.sort()
    print("ok a ringing band (%d of %d lines, z up to %.0f nm): the frame's range %.1f to %.1f nm, "
          "1 to 99 %% %.1f to %.1f nm, the default (typical lines') %.2f to %.2f nm"
          % (rung, len(fin) // n, fin[-1] * 1e9, fin[0] * 1e9, fin[-1] * 1e9, percentile(fin, 0.01) * 1e9,
             percentile(fin, 0.99) * 1e9, im["lo"] * 1e9, im["hi"] * 1e9))
    # the figure: the trace at the default range, the retrace at the frame's, the error flattened
    choose(b, "#range-height-retrace", "frame")
    b.eval("document.getElementById('images').scrollIntoView()")
    time.sleep(0.3)
    shot(b, shots, "live-images.png")
    choose(b, "#range-height-retrace", "lines")


def lag(b):
    """At ki = 100 Hz the loop lags (z strays from the surface): the loop box says so,
    naming the judged line, never "steady"."""
    b.eval("tiptapSet('feedback.integral_gain', '100')")
    wait_for(b, "tiptapLive.lastReply.ok && tiptapLive.controls.find(c => c.name === "
                "'feedback.integral_gain').value === '100'", "100 Hz accepted")
    new_scope(b, "a line at 100 Hz")
    wait_for(b, "tiptapLive.status.lagging && tiptapLive.status.judged_line >= tiptapLive.status.first_line_as_set",
             "a lagging line judged at 100 Hz")
    g = b.eval("document.getElementById('goodloop').textContent")
    st = js(b, "tiptapLive.status")
    assert g.startswith("The loop lags (line %d)" % st["judged_line"]) and "steady" not in g, g
    assert st["track_rms"] > 0.35 * st["surface_range"], st
    print("ok at 100 Hz: %s" % g)
    b.eval("tiptapSet('feedback.integral_gain', '1000')")
    wait_for(b, "tiptapLive.lastReply.ok && tiptapLive.controls.find(c => c.name === "
                "'feedback.integral_gain').value === '1000'", "1 kHz again")


def screenshots(b):
    # the figure for docs/live.md: a reference at 1 kHz, the scope at 2 kHz, zoomed on an edge
    b.eval("window.scrollTo(0, 0)")
    # (a line that started at 1 kHz: the one under way at the change ran at 100 Hz)
    new_scope(b, "a scope at 1 kHz")
    wait_for(b, "!tiptapLive.status.oscillating", "no ring")
    b.eval("document.getElementById('storeref').click()")
    assert b.eval("tiptapLive.reference.gains").startswith("I gain 1000 Hz,"), b.eval("tiptapLive.reference.gains")
    b.eval("tiptapSet('feedback.integral_gain', '2000')")
    wait_for(b, "tiptapLive.lastReply.ok && tiptapLive.controls.find(c => c.name === "
                "'feedback.integral_gain').value === '2000'", "2 kHz accepted")
    new_scope(b, "a scope at 2 kHz")
    b.eval("document.getElementById('hold').click()")
    g = js(b, "(() => { const r = document.getElementById('scope').getBoundingClientRect(), "
              "g = tiptapLive.scopeGeom; return {left: r.left + 1 + g.g.left, top: r.top + 1 + g.panels[0].y0, "
              "pw: g.g.pw, ph: g.g.ph, x0: g.x0, x1: g.x1}; })()")
    # the first rising wall of the grating: zoomed to an eighth of the line around it
    s = js(b, "tiptapLive.scopeShown.trace")
    z = [v for v in s["z"] if v is not None]
    mid = (min(z) + max(z)) / 2
    k = next(i for i in range(1, len(s["z"])) if s["z"][i - 1] is not None and s["z"][i] is not None
             and s["z"][i - 1] < mid <= s["z"][i])
    edge = s["position"][k] * 1e9
    f = lambda x: g["left"] + (x - g["x0"]) / (g["x1"] - g["x0"]) * g["pw"]
    w = 0.06 * (g["x1"] - g["x0"])
    y = g["top"] + g["ph"] / 2
    mouse(b, "mousePressed", f(edge - w), y, 1)
    mouse(b, "mouseMoved", f(edge + w), y, 1)
    mouse(b, "mouseReleased", f(edge + w), y, 0)
    mouse(b, "mouseMoved", g["left"] + 0.55 * g["pw"], y)
    shot(b, shots, "live-scope.png")
    b.eval("document.getElementById('hold').click()")
    b.eval("document.getElementById('zoomreset').click()")


def previews(b):
    """A change's next line comes first from the averaged preview: its row is marked as one
    and its caption says so; a scan on the averaged tier is no preview, and no caption says
    it is (the issue's "every averaged line captioned as a preview")."""
    n = b.eval("tiptapLive.previewRows")
    b.eval("tiptapSet('feedback.integral_gain', '1100')")
    wait_for(b, "tiptapLive.previewRows > %d" % n, "a preview row after a change")
    print("ok a change's first line came from the averaged preview, marked as one (%d preview rows)"
          % b.eval("tiptapLive.previewRows"))
    frame = b.eval("tiptapLive.frame.frame")
    b.eval("tiptapSet('solver.tier', 'averaged')")
    wait_for(b, "tiptapLive.frame.frame > %d && tiptapLive.status.tier === 'averaged' && "
                "tiptapLive.status.lines_done >= 3" % frame, "three lines on the averaged tier")
    caps = b.eval("[...document.querySelectorAll('[id^=cap-]')].map(e => e.textContent)")
    tiers = b.eval("tiptapLive.tiers.filter(t => t)")
    assert caps and not any("preview" in c for c in caps), caps
    assert tiers and all(t == "averaged" for t in tiers), tiers
    print("ok on the averaged tier %d lines, none a preview; captions: %s" % (len(tiers), caps[0]))
    frame = b.eval("tiptapLive.frame.frame")
    b.eval("tiptapSet('solver.tier', 'envelope')")
    b.eval("tiptapSet('feedback.integral_gain', '1000')")
    wait_for(b, "tiptapLive.frame.frame > %d && tiptapLive.status.tier === 'envelope'" % frame,
             "the envelope tier again")


def slow_axis(b):
    """The grating scanned along y: each line runs along a ridge or a trench, flat, and
    the default range still spans the ridges' height."""
    frame = b.eval("tiptapLive.frame.frame")
    b.eval("tiptapSet('scan.fast_axis', 'y')")
    # half the frame: a ridge's lines, a trench's and the walls' (fewer of either before)
    wait_for(b, "tiptapLive.frame.frame > %d && tiptapLive.frame.fast_y && Array.from("
                "tiptapLive.images.height_trace).filter(isFinite).length >= 16 * tiptapLive.frame.pixels"
             % frame, "sixteen lines along y")
    im = image(b)
    n = im["pixels"]
    spans = sorted(max(r) - min(r) for r in ([v for v in im["raw"][l * n:(l + 1) * n] if v is not None]
                                             for l in range(im["lines"])) if r)
    assert spans[len(spans) // 2] < 1e-9 and im["hi"] - im["lo"] > 15e-9, (spans, im["lo"], im["hi"])
    print("ok along y: the median line spans %.3f nm (%d lines); the default range %.2f to %.2f nm"
          % (spans[len(spans) // 2] * 1e9, len(spans), im["lo"] * 1e9, im["hi"] * 1e9))


def main(b):
    readable(b)
    fields(b, url)
    hidden_tab(b, url)
    images(b)
    scope(b)
    ring(b)
    lag(b)
    screenshots(b)
    previews(b)
    slow_axis(b)


run(main, chromium, url, 1024, 768)
