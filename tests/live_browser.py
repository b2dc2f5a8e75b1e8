#!/usr/bin/python3
"""The live console in a real browser: Debian's headless Chromium, driven over the
DevTools protocol on a pipe (fds 3 and 4, NUL-terminated JSON), the standard library
only. Loads the page, moves the I gain, and asserts that the scope changes, that the
oscillation warning appears at a high gain and clears at a good one, and that a bad
value is refused on the page with the config layer's message.

usage: live_browser.py CHROMIUM URL SHOTS_DIR
Prints 'ok ...' / 'FAIL ...' lines; exits 1 on the first failure."""
import json
import sys
import time

from live_cdp import run, shot, wait_for

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]
HIGH_KI, GOOD_KI = "30000", "2000"  # Hz: far above pi f0 / Q (2.4 kHz), and below it


# the scope's trace of z, as numbers, for comparing one line's scope with another's
SCOPE_Z = "JSON.stringify(tiptapLive.scope && tiptapLive.scope.trace.z)"
SCOPE_LINE = "tiptapLive.scope ? tiptapLive.scope.line : -1"


def main(b):
    assert b.eval("document.querySelector('script[src^=\"http\"], link[href^=\"http\"]') == null"), \
        "the page loads something from elsewhere"

    # a bad value: the config layer's message on the page, nothing changed
    ki0 = b.eval("document.querySelector('[data-name=\"feedback.integral_gain\"]').value")
    b.eval("tiptapSet('feedback.integral_gain', '-5')")
    msg = wait_for(b, "!tiptapLive.lastReply || tiptapLive.lastReply.ok ? '' : "
                      "document.getElementById('reply').textContent", "a refusal on the page")
    assert "[feedback] integral_gain" in msg, msg
    print("ok a negative gain is refused on the page: %s" % msg)

    # a high gain: the scope changes, the warning comes
    before = b.eval(SCOPE_Z)
    line0 = b.eval(SCOPE_LINE)
    b.eval("tiptapSet('feedback.integral_gain', '%s')" % HIGH_KI)
    wait_for(b, "tiptapLive.lastReply && tiptapLive.lastReply.ok", "the high gain accepted")
    wait_for(b, "%s != %d && %s != %s" % (SCOPE_LINE, line0, SCOPE_Z, json.dumps(before)),
             "the scope after the gain change")
    print("ok the scope changed after the gain moved from %s Hz to %s Hz" % (ki0, HIGH_KI))
    wait_for(b, "tiptapLive.status.oscillating && !document.getElementById('warning').hidden",
             "the oscillation warning at ki = %s Hz" % HIGH_KI)
    text = b.eval("document.getElementById('warning').textContent")
    print("ok the warning shows at ki = %s Hz: %s" % (HIGH_KI, " ".join(text.split())))
    time.sleep(1.5)  # a few more lines into the images
    shot(b, shots, "live-oscillating.png")

    # a good gain: the warning clears
    b.eval("tiptapSet('feedback.integral_gain', '%s')" % GOOD_KI)
    wait_for(b, "!tiptapLive.status.oscillating && document.getElementById('warning').hidden",
             "the warning cleared at ki = %s Hz" % GOOD_KI)
    print("ok the warning clears at ki = %s Hz" % GOOD_KI)
    wait_for(b, "tiptapLive.status.lines_done >= 4 || tiptapLive.status.passes > 0",
             "a few lines at the good gain")
    time.sleep(1.5)
    shot(b, shots, "live-steady.png")


run(main, chromium, url, 1024, 768)  # a projector's size
