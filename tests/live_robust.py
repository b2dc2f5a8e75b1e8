#!/usr/bin/python3
"""tiptap live under abuse and in use, over its WebSocket and HTTP (no browser): bad
messages get a clear reply and change nothing, in UTF-8 whatever the page sent; a page or
a request from another origin or Host is refused (DNS rebinding), and only GET and HEAD
are served; refused handshakes do not lift the 16-page limit; each page has an instrument
of its own, four at most (a fifth page is told so, and takes an instrument, reset, when a
page closes); 300 idle connections hold a bounded number of the server's descriptors;
four pages at once, one closed mid-stream, one flooding and one never reading: the
others keep their updates and the server's memory stays bounded; the exports of a page's
instrument (/export/N/NAME, after the page closed) are what tiptap scan writes for the
exported scene, byte for byte.

usage: live_robust.py PORT SERVER_PID TIPTAP WORKDIR"""
import filecmp
import http.client
import os
import socket
import subprocess
import sys
import time
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_ws import WS, Refused, ask, control  # noqa: E402

port, pid, tiptap, work = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
fails = 0


def ok(cond, what):
    global fails
    print(("ok " if cond else "FAIL ") + what)
    fails += not cond


def rss_kb():
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


# ---- one page: the first messages, then bad messages
a = WS(port)
first = a.recv_type("controls")
ki0 = control(first, "feedback.integral_gain")
frame = a.recv_type("frame")
a.recv_type("row")
ok(frame["pixels"] > 0 and frame["lines"] > 0, "a page gets the controls, the frame (%d x %d) "
   "and rows" % (frame["pixels"], frame["lines"]))
bad = [
    ("set feedback.integral_gain = abc", "console: [feedback] integral_gain:"),
    ("set feedback.integral_gain = -3 kHz", "console: [feedback] integral_gain:"),
    ("set feedback.integral_gain = 6", "console: [feedback] integral_gain:"),
    ("set scan.pixels = 0", "console: [scan] pixels:"),
    ("set cantilever.spring_constant = 2 N/m", "no such control"),
    ("set sample = ../../etc/passwd", "not a bundled sample"),
    ("{\"set\": 1}", "expected set NAME = VALUE or restart"),
    ("set feedback.integral_gain = 5 kHz\nset noise = loud", "expected on or off"),
    ("x" * 20000, "more than 16384 bytes"),
]
for text, want in bad:
    r = ask(a, text)
    ok(not r["ok"] and want in r["error"] and "\n" not in r["error"],
       "refused %r: %s" % (text[:40], r["error"][:110]))
r = ask(a, b"\xff\xfe\x00binary")
ok(not r["ok"], "a binary message is refused: %s" % r["error"][:80])
# every text the server sends is UTF-8 (a browser drops the socket otherwise): a reply
# that quotes the page's text cuts it on a character's boundary, and bytes that are not
# UTF-8 are refused, not echoed (WS.recv decodes strictly)
for text in ["set x" + "\u00e9" * 40 + " = 1", "set sample = x" + "\u00e9" * 40,
             "set noise = " + "\u20ac" * 60, "set feedback.integral_gain = x" + "\u00fc" * 90,
             b"set f\xff\xfeo = 1", b"set feedback.integral_gain = \xc3", "x\u00e9" * 5000]:
    try:
        r = ask(a, text)
        ok(not r["ok"] and "\ufffd" not in r["error"],
           "the reply to %r is UTF-8: %s" % (text[:24], r["error"][:60]))
    except UnicodeDecodeError as e:
        ok(False, "the reply to %r is UTF-8 (%s)" % (text[:24], e))
        a = WS(port)
b = WS(port)
ok(control(b.recv_type("controls"), "feedback.integral_gain") == ki0,
   "after the refusals the I gain is still %s Hz" % ki0)
b.close()

# ---- another origin (a web page elsewhere) and another Host (DNS rebinding) are refused,
# for a WebSocket as for a plain request (the page, an export); this server's names pass
foreign = ({"origin": "http://example.com"}, {"host": "evil.example:%d" % port},
           {"origin": "null"}, {"host": "127.0.0.1"}, {"origin": "http://127.0.0.1:%d.evil" % port})
for kw in foreign:
    try:
        WS(port, **kw).close()
        ok(False, "a WebSocket with %s is refused" % kw)
    except (Refused, ConnectionError, OSError) as e:
        ok(True, "a WebSocket with %s is refused (%s)" % (kw, str(e)[:40]))


def request(method, path, headers=None):
    """status, headers and body of one plain request"""
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=300)
    c.putrequest(method, path, skip_host="Host" in (headers or {}))
    for k, v in (headers or {}).items():
        c.putheader(k, v)
    c.endheaders()
    r = c.getresponse()
    body = r.read()
    c.close()
    return r.status, r, body


for path in ("/", "/export/scene.ini", "/export/scan.gwy"):
    for kw in foreign:
        h = {"Host": kw["host"]} if "host" in kw else {"Origin": kw["origin"]}
        st, _, body = request("GET", path, h)
        ok(st == 403 and b"[scan]" not in body, "GET %s with %s: %d" % (path, h, st))
for h in ({"Host": "localhost:%d" % port}, {"Host": "[::1]:%d" % port},
          {"Origin": "http://localhost:%d" % port}):
    st, _, body = request("GET", "/export/scene.ini", h)
    ok(st == 200 and b"[scan]" in body, "GET /export/scene.ini with %s: %d" % (h, st))
# ---- only GET and HEAD: the others are told 405 and change nothing
for method in ("DELETE", "PUT", "POST", "OPTIONS", "PATCH"):
    for path in ("/", "/export/scene.ini"):
        st, r, _ = request(method, path)
        ok(st == 405 and "GET" in (r.getheader("allow") or ""), "%s %s: %d, allow %s"
           % (method, path, st, r.getheader("allow")))
st, r, body = request("HEAD", "/")
ok(st == 200 and body == b"" and int(r.getheader("content-length")) > 0,
   "HEAD /: %d, %s bytes said, none sent" % (st, r.getheader("content-length")))

# ---- refused handshakes never count as pages: after 40 of them, 16 pages are let in and
# the 17th is not, and the count the pages are told is 16
a.close()
for i in range(40):
    try:
        WS(port, **foreign[i % len(foreign)]).close()
    except (Refused, ConnectionError, OSError):
        pass
many, why = [], ""
for _ in range(100):  # the closed pages' ends may take the server a moment
    try:
        while len(many) < 16:
            many.append(WS(port))
        break
    except (Refused, ConnectionError, OSError) as e:
        why = str(e)
        time.sleep(0.1)
ok(len(many) == 16, "16 pages let in after 40 refused handshakes (%d; %s)" % (len(many), why))
try:
    WS(port).close()
    ok(False, "a 17th page is refused")
except (Refused, ConnectionError, OSError):
    ok(True, "a 17th page is refused")
# each page its own instrument, four at most (the default): the fifth is told so and waits
first = [w.recv() for w in many[:5]]
counts = set()
for _ in range(200):
    m = many[0].recv()
    if m["type"] == "status":
        counts.add(m["clients"])
        if m["clients"] == 16:
            break
ok(16 in counts and min(counts) > 0, "the pages are told %s pages" % sorted(counts))
numbers = [m.get("instrument") for m in first[:4]]
r = first[4]
ok(sorted(numbers) == [1, 2, 3, 4] and r["type"] == "reply" and not r["ok"]
   and "all 4 instruments are in use" in r["error"],
   "pages 1 to 4 have instruments %s; the fifth is told: %s" % (numbers, r["error"][:90]))
r = ask(many[4], "set feedback.integral_gain = 2 kHz")
ok(not r["ok"] and "no instrument" in r["error"], "a change from it is refused: %s" % r["error"])
ok(ask(many[1], "set feedback.integral_gain = 2 kHz")["ok"], "page 2 sets 2 kHz on its instrument")
many[1].close()
m = many[4].recv_type("controls")
ok(m["instrument"] == numbers[1] and control(m, "feedback.integral_gain") == ki0,
   "once page 2 closed, the fifth took its instrument %d, reset to the start (I gain %s Hz)"
   % (m["instrument"], control(m, "feedback.integral_gain")))
for w in many[:1] + many[2:]:
    w.close()

# ---- connections at once are bounded: 300 idle ones hold under 100 of the server's
# descriptors (64 connections and its own), and once they close it serves again


def fds():
    return len(os.listdir("/proc/%d/fd" % pid))


idle = []
for i in range(300):
    c = socket.socket()
    c.settimeout(10)
    c.connect(("127.0.0.1", port))  # the kernel's backlog completes what lws does not take
    idle.append(c)
held = 0
for _ in range(100):  # until the server took what it takes
    time.sleep(0.1)
    n = fds()
    if n == held and n > 60:
        break
    held = n
ok(held < 100, "300 idle connections: the server holds %d descriptors" % held)
for c in idle:
    c.close()
st, _, _ = request("GET", "/")
ok(st == 200, "served again once they closed (%d)" % st)

# ---- four pages; one flooding, one never reading, one closed mid-stream
rss0 = rss_kb()
pages = [WS(port) for _ in range(4)]
flood, mute, gone, calm = pages
# each page drives an instrument of its own: the flooding and the mute page's are paused,
# so that one engine runs beside the server as when the pages shared one (the flood's
# drops need the server's thread to read faster than 20 messages a second)
for p in (flood, mute):
    ok(ask(p, "pause")["ok"], "an instrument paused")
raw = socket.create_connection(("127.0.0.1", port))  # half a handshake, then nothing
raw.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n")
gone.recv_type("row")
gone.s.close()  # no close frame: a tab killed
t_end = time.time() + 6
sent = 0
while time.time() < t_end:  # 6 s of flood: far more than 20 messages a second
    flood.send("set feedback.integral_gain = %d Hz" % (1000 + sent % 7))
    sent += 1
    if sent % 200 == 0:
        calm.recv()  # the calm page reads as a browser does
scopes, t0 = 0, time.time()
t_end = t0 + float(os.environ.get("TT_LIVE_WAIT", "300"))
while time.time() < t_end and scopes < 3:  # three lines' scopes after the flood
    m = calm.recv()
    scopes += m["type"] == "scope"
ok(scopes >= 3, "a calm page kept its scope updates through the flood (%d in %.1f s)"
   % (scopes, time.time() - t0))
replies, dropped = 0, 0
t_end = time.time() + 20
while time.time() < t_end and dropped == 0:  # the pages' own stream goes on meanwhile
    m = flood.recv()
    if m["type"] == "reply":
        replies += 1
        dropped = max(dropped, m.get("dropped", 0))
ok(dropped > 0 and replies < sent, "the flood of %d messages got %d replies, %d dropped at most "
   "in one" % (sent, replies, dropped))
rss1 = rss_kb()
ok(rss1 - rss0 < 64 * 1024, "the server's memory grew %.1f MB through it (%d to %d kB)"
   % ((rss1 - rss0) / 1024, rss0, rss1))
for p in (flood, mute, calm):
    p.close()
raw.close()

# ---- the exports: wait for a whole frame at one setting, then tiptap scan its scene
c = WS(port)
mine = c.recv_type("controls")["instrument"]
ok(ask(c, "set feedback.integral_gain = 2 kHz")["ok"], "a good gain accepted")
deadline = time.time() + float(os.environ.get("TT_LIVE_WAIT", "300"))
st = None
while time.time() < deadline:
    m = c.recv()
    if m["type"] == "status" and m["reproducible"]:
        st = m
        break
ok(st is not None, "a whole frame ran at one setting")
c.close()
exp = os.path.join(work, "export")
os.makedirs(exp, exist_ok=True)
names = ["scene.ini", "scan.gwy", "height_trace.gsf", "height_retrace.gsf", "phase_trace.gsf"]
for n in names:
    # the page's own instrument's, by its number: kept (idle) after its page closed
    with urllib.request.urlopen("http://127.0.0.1:%d/export/%d/%s" % (port, mine, n), timeout=300) as r:
        with open(os.path.join(exp, n), "wb") as f:
            f.write(r.read())
for bad_path in ("9/scene.ini", "0/scene.ini", "%d/x/scene.ini" % mine):
    try:
        urllib.request.urlopen("http://127.0.0.1:%d/export/%s" % (port, bad_path), timeout=20)
        ok(False, "/export/%s is refused" % bad_path)
    except urllib.error.HTTPError as e:
        ok(e.code == 404, "/export/%s is refused (%d)" % (bad_path, e.code))
try:
    urllib.request.urlopen("http://127.0.0.1:%d/export/..%%2Fscene.ini" % port, timeout=20)
    ok(False, "an export outside the export folder is refused")
except urllib.error.HTTPError as e:
    ok(e.code == 404, "an export outside the export folder is refused (%d)" % e.code)
out = os.path.join(work, "rescan")
run = subprocess.run([tiptap, "scan", os.path.join(exp, "scene.ini"), "-o", out, "-q", "-j", "2"],
                     capture_output=True, text=True)
ok(run.returncode == 0, "tiptap scan of the exported scene ran (%s)" % run.stderr.strip()[:200])
for n in names[1:]:
    ok(filecmp.cmp(os.path.join(exp, n), os.path.join(out, n), shallow=False),
       "%s: the export and tiptap scan's are the same bytes" % n)
ok(filecmp.cmp(os.path.join(exp, "scene.ini"), os.path.join(out, "scene.ini"), shallow=False),
   "scene.ini: tiptap scan writes back the exported scene unchanged")
sys.exit(1 if fails else 0)
