"""Debian's headless Chromium driven over the DevTools protocol on a pipe (fds 3 and 4,
NUL-terminated JSON), the standard library only: shared by the browser tests of tiptap
live (tests/live_browser.py, tests/live_display.py)."""
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

WAIT = float(os.environ.get("TT_LIVE_WAIT", "180"))  # s for each step (sanitizer builds)


class Browser:
    def __init__(self, chromium):
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
        self.targets = {}  # session: its page's target

    def call(self, method, params=None, session=True, timeout=60):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if isinstance(session, str):  # another page's session
            msg["sessionId"] = session
        elif session and self.session:
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

    def open_page(self, url, width, height, background=False):
        """A new page at url, width x height CSS pixels at one device pixel each; its
        session becomes the default one, and is returned. background: a tab behind the
        others, hidden to the page (document.hidden) until Target.activateTarget."""
        target = self.call("Target.createTarget", {"url": "about:blank", "background": background},
                           session=False)["targetId"]
        self.session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True},
                                 session=False)["sessionId"]
        self.call("Page.enable")
        self.call("Runtime.enable")
        self.call("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
        # focus as in a window in front, so that a field keeps the focus it is given (a
        # tab in the background: not, since the emulated focus also shows it)
        if not background:
            self.call("Emulation.setFocusEmulationEnabled", {"enabled": True})
        self.call("Page.navigate", {"url": url})
        self.targets[self.session] = target
        return self.session

    def eval(self, expr, session=True):
        r = self.call("Runtime.evaluate", {"expression": expr, "returnByValue": True}, session)
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


def shot(b, shots, name):
    data = b.call("Page.captureScreenshot", {"format": "png"})["data"]
    path = os.path.join(shots, name)
    with open(path, "wb") as f:
        f.write(base64.b64decode(data))
    print("ok screenshot %s" % path)


def run(test, chromium, url, width, height):
    """Opens the console at url in a new browser, width x height, waits for its first
    scope and rows, then runs test(b); a failed check prints FAIL and exits 1."""
    try:
        b = Browser(chromium)
        try:
            b.open_page(url, width, height)
            wait_for(b, "window.tiptapLive && tiptapLive.controls.length > 0 && tiptapLive.scopes > 1 "
                        "&& tiptapLive.rows > 1 && tiptapLive.status != null", "the page's first scope")
            print("ok the page loaded its controls, a scope and the first rows")
            test(b)
        finally:
            b.close()
    except (AssertionError, RuntimeError) as e:
        print("FAIL %s" % e)
        sys.exit(1)
