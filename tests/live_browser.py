#!/usr/bin/python3
"""The live console in a real browser: Debian's headless Chromium, driven over the
DevTools protocol on a pipe (fds 3 and 4, NUL-terminated JSON), the standard library
only. Loads the page, moves the I gain, and asserts that the scope changes, that the
oscillation warning appears at a high gain and clears at a good one, and that a bad
value is refused on the page with the config layer's message.

usage: live_browser.py CHROMIUM URL SHOTS_DIR
Prints 'ok ...' / 'FAIL ...' lines; exits 1 on the first failure."""
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

chromium, url, shots = sys.argv[1], sys.argv[2], sys.argv[3]
HIGH_KI, GOOD_KI = "30000", "2000"  # Hz: far above pi f0 / Q (2.4 kHz), and below it
WAIT = float(os.environ.get("TT_LIVE_WAIT", "180"))  # s for each step (sanitizer builds)


class Browser:
    def __init__(self):
        self.profile = tempfile.mkdtemp(prefix="tt-chromium-")
        self.log = open(os.path.join(self.profile, "stderr"), "w+")
        to_browser, self.w = os.pipe()
        self.r, from_browser = os.pipe()

        def fds():  # the browser reads commands on fd 3 and answers on fd 4
            os.dup2(to_browser, 3)
            os.dup2(from_browser, 4)

        self.proc = subprocess.Popen(
            [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
             "--no-first-run", "--disable-background-networking", "--disable-component-update",
             "--disable-sync", "--disable-dev-shm-usage", "--mute-audio",
             "--user-data-dir=" + self.profile, "--remote-debugging-pipe", "about:blank"],
            # the fds are put in place after the fork; close_fds would close them again
            close_fds=False, preexec_fn=fds,
            stdout=subprocess.DEVNULL, stderr=self.log)
        os.close(to_browser)
        os.close(from_browser)
        self.buf = b""
        self.next_id = 0
        self.session = None

    def call(self, method, params=None, session=True, timeout=60):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self.w, json.dumps(msg).encode() + b"\0")
        end = time.time() + timeout
        while time.time() < end:
            while b"\0" in self.buf:
                raw, self.buf = self.buf.split(b"\0", 1)
                m = json.loads(raw)
                if m.get("id") == self.next_id:
                    if "error" in m:
                        raise RuntimeError("%s: %s" % (method, m["error"]))
                    return m.get("result", {})
            chunk = os.read(self.r, 1 << 20)
            if not chunk:
                self.log.seek(0)
                raise RuntimeError("the browser closed its pipe: " + self.log.read()[-600:])
            self.buf += chunk
        raise RuntimeError("%s: no answer in %d s" % (method, timeout))

    def eval(self, expr):
        r = self.call("Runtime.evaluate", {"expression": expr, "returnByValue": True})
        return r.get("result", {}).get("value")

    def close(self):
        try:
            self.call("Browser.close", session=False, timeout=10)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        self.log.close()
        shutil.rmtree(self.profile, ignore_errors=True)


def wait_for(b, expr, what):
    end = time.time() + WAIT
    while time.time() < end:
        v = b.eval(expr)
        if v:
            return v
        time.sleep(0.2)
    state = b.eval("JSON.stringify({status: tiptapLive.status, scopes: tiptapLive.scopes, "
                   "rows: tiptapLive.rows, reply: tiptapLive.lastReply})")
    raise AssertionError("%s: not within %.0f s; page state: %s" % (what, WAIT, state))


def shot(b, name):
    data = b.call("Page.captureScreenshot", {"format": "png"})["data"]
    path = os.path.join(shots, name)
    with open(path, "wb") as f:
        f.write(base64.b64decode(data))
    print("ok screenshot %s" % path)


# the scope's trace of z, as numbers, for comparing one line's scope with another's
SCOPE_Z = "JSON.stringify(tiptapLive.scope && tiptapLive.scope.trace.z)"
SCOPE_LINE = "tiptapLive.scope ? tiptapLive.scope.line : -1"


def main():
    b = Browser()
    try:
        target = b.call("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        b.session = b.call("Target.attachToTarget", {"targetId": target, "flatten": True},
                           session=False)["sessionId"]
        b.call("Page.enable")
        b.call("Runtime.enable")
        b.call("Emulation.setDeviceMetricsOverride",
               {"width": 1320, "height": 1320, "deviceScaleFactor": 1, "mobile": False})
        b.call("Page.navigate", {"url": url})
        wait_for(b, "window.tiptapLive && tiptapLive.controls.length > 0 && tiptapLive.scopes > 1 "
                    "&& tiptapLive.rows > 1 && tiptapLive.status != null", "the page's first scope")
        print("ok the page loaded its controls, a scope and the first rows")
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
        shot(b, "live-oscillating.png")

        # a good gain: the warning clears
        b.eval("tiptapSet('feedback.integral_gain', '%s')" % GOOD_KI)
        wait_for(b, "!tiptapLive.status.oscillating && document.getElementById('warning').hidden",
                 "the warning cleared at ki = %s Hz" % GOOD_KI)
        print("ok the warning clears at ki = %s Hz" % GOOD_KI)
        wait_for(b, "tiptapLive.status.lines_done >= 4 || tiptapLive.status.passes > 0",
                 "a few lines at the good gain")
        time.sleep(1.5)
        shot(b, "live-steady.png")
    finally:
        b.close()


try:
    main()
except (AssertionError, RuntimeError) as e:
    print("FAIL %s" % e)
    sys.exit(1)
