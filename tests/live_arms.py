#!/usr/bin/python3
"""The console's averaged preview on a sample with relaxation arms
(examples/viscoelastic-blend/arms.ini, on the envelope tier with noise; tests/cli_live_arms.sh
starts the server): a change's next line comes first from the averaged preview, whose
tables now take the arm's periodic cycle (src/solver/averaged_arms.c): the preview row
exists, is marked as one, and its caption says so.

usage: live_arms.py CHROMIUM URL SHOTS_DIR
Prints 'ok ...' / 'FAIL ...' lines; exits 1 on the first failure."""
import sys

from live_cdp import run, wait_for

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]


def main(b):
    tier = b.eval("tiptapLive.status.tier")
    assert tier == "envelope", tier
    # the captions as they are drawn: the scan's own line follows the preview's soon
    b.eval("window.capsSeen = []; new MutationObserver(() => { for (const e of "
           "document.querySelectorAll('[id^=cap-]')) if (e.textContent.includes('preview')) "
           "window.capsSeen.push(e.textContent); }).observe(document.body, "
           "{subtree: true, childList: true, characterData: true}); 0")
    n = b.eval("tiptapLive.previewRows")
    b.eval("tiptapSet('feedback.integral_gain', '1100')")
    wait_for(b, "tiptapLive.previewRows > %d" % n, "a preview row after a change on the arms' scene")
    wait_for(b, "window.capsSeen.length > 0", "a caption naming the averaged preview")
    cap = b.eval("window.capsSeen[0]")
    assert "from the averaged preview" in cap, cap
    print("ok on the envelope tier with an arm a change's first line came from the averaged "
          "preview (%d preview rows); caption: %s" % (b.eval("tiptapLive.previewRows"), cap))
    wait_for(b, "tiptapLive.status.preview_ms > 0", "the preview's latency")
    print("ok the preview's latency %.0f ms" % b.eval("tiptapLive.status.preview_ms"))


run(main, chromium, url, 1024, 768)
