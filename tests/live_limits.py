#!/usr/bin/python3
"""tiptap live's memory and latency promises, and its port-80 names, over its WebSocket
and HTTP (tests/cli_live_limits.sh starts a server for each mode):

  changes PORT PID   a change whose memory the machine cannot hold is refused and changes
                     nothing; a change the scan cannot be built for is refused (not "ok"),
                     the controls and the exported scene keep the values in force
  abandon PORT       a line at 0.01 Hz on the every-cycle tier (minutes of work) is
                     abandoned for a change of line rate: the new rate's own line comes
                     within 120 s, not after the old line's minutes
  exports PORT PID   20 requests of a 25 MB export that read nothing hold a bounded memory
                     in the server (streamed, not copied whole per request)
  port80 PORT        on port 80 a browser's port-less Host and Origin are this server's

usage: live_limits.py MODE PORT [PID]"""
import http.client
import os
import socket
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_ws import WS, Refused, ask, control  # noqa: E402

mode, port = sys.argv[1], int(sys.argv[2])
pid = int(sys.argv[3]) if len(sys.argv) > 3 else 0
fails = 0


def ok(cond, what):
    global fails
    print(("ok " if cond else "FAIL ") + what)
    fails += not cond


def get(path, host=None, origin=None):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=300)
    c.putrequest("GET", path, skip_host=host is not None)
    if host is not None:
        c.putheader("Host", host)
    if origin is not None:
        c.putheader("Origin", origin)
    c.endheaders()
    r = c.getresponse()
    body = r.read()
    c.close()
    return r.status, body


def rss_kb():
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


if mode == "changes":
    a = WS(port)
    first = a.recv_type("controls")
    keep = {n: control(first, n) for n in ("scan.line_rate", "scan.pixels", "scan.size", "sample",
                                           "feedback.integral_gain")}
    for text, want in [
            ("set feedback.integral_gain = 7 kHz\nset scan.line_rate = 0.0002 Hz",
             "console: [scan] line_rate:"),
            ("set scan.pixels = 16384\nset scan.lines = 16384\nset scan.line_rate = 1 Hz",
             "console: [scan] pixels:")]:
        r = ask(a, text)
        ok(not r["ok"] and want in r["error"] and "memory" in r["error"],
           "refused %r: %s" % (text[:50], r["error"][:160]))
    # the configuration layer accepts 15 spheres of 15 nm in 50 nm; the scan's surface
    # does not: the reply says so, and nothing changes
    r = ask(a, "set feedback.integral_gain = 7 kHz\nset sample = particles\nset scan.size = 50 nm")
    ok(not r["ok"] and "particle_count" in r["error"],
       "a change the scan cannot be built for is refused: %s" % r["error"][:120])
    # the page's own instrument (each page has one): its exported scene is the one in force
    mine = first["instrument"]
    st, scene = get("/export/%d/scene.ini" % mine)
    text = scene.decode()
    lines = text.splitlines()
    ok(st == 200 and "type = grating" in lines and "size = 1um" in lines
       and "integral_gain = 1000 Hz" in lines,
       "the exported scene is the one in force (grating, 1 um, ki 1 kHz)")
    # a change that is taken shows at once in the controls and in the exported scene
    ok(ask(a, "set feedback.integral_gain = 1.5 kHz")["ok"], "a good change is taken")
    ok(control(a.recv_type("controls"), "feedback.integral_gain") == "1500", "the controls show it")
    # another page has its own instrument, at the start's values: the change is not its
    b = WS(port)
    other = b.recv_type("controls")
    ok(other["instrument"] != mine and control(other, "feedback.integral_gain") == keep["feedback.integral_gain"],
       "another page's instrument %d keeps I gain %s Hz" % (other["instrument"], control(other, "feedback.integral_gain")))
    b.close()
    a.close()

elif mode == "abandon":
    a = WS(port, timeout=600)
    a.recv_type("frame")
    a.recv_type("status")
    t0 = time.time()
    ok(ask(a, "set scan.line_rate = 8 Hz")["ok"], "a line rate of 8 Hz taken")
    got = None
    while time.time() < t0 + 120:  # the old line ran for minutes; the new one takes seconds
        a.s.settimeout(max(1, t0 + 120 - time.time()))
        try:
            m = a.recv()
        except (socket.timeout, TimeoutError):
            break
        if m["type"] == "scope" and m["tier"] == "every":
            got = m
            break
    dt = time.time() - t0
    ok(got is not None and got["trace"]["t1"] - got["trace"]["t0"] < 0.07,
       "the line under way abandoned: the first line of the scan's own tier at 8 Hz after %.1f s "
       "(a trace of %s s)" % (dt, got["trace"]["t1"] - got["trace"]["t0"] if got else "none"))
    a.close()

elif mode == "exports":
    st, body = get("/export/scan.gwy")
    size = len(body)
    ok(st == 200 and size > 8e6, "scan.gwy: %.1f MB" % (size / 1e6))
    r0 = rss_kb()
    held = []
    for _ in range(20):
        c = socket.socket()
        c.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        c.settimeout(300)
        c.connect(("127.0.0.1", port))
        c.sendall(b"GET /export/scan.gwy HTTP/1.1\r\nHost: 127.0.0.1:%d\r\n\r\n" % port)
        held.append(c)
    answered = 0
    for c in held:  # each reply under way: its headers came
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = c.recv(1024)
            if not chunk:
                break
            head += chunk
        answered += head.startswith(b"HTTP/1.1 200")
    ok(answered == 20, "20 requests that read no further are answered (%d)" % answered)
    grew = (rss_kb() - r0) * 1024
    ok(grew < 2 * size, "20 unread exports of %.1f MB: the server grew %.1f MB"
       % (size / 1e6, grew / 1e6))
    for c in held:
        c.close()

elif mode == "port80":
    for host in ("127.0.0.1", "localhost", "[::1]"):
        try:
            WS(port, host=host, origin="http://" + host).close()
            ok(True, "a page at http://%s/ is let in" % host)
        except (Refused, ConnectionError, OSError) as e:
            ok(False, "a page at http://%s/ is let in (%s)" % (host, e))
        st, body = get("/", host=host)
        ok(st == 200, "GET / with Host %s: %d" % (host, st))
    for host, origin in (("127.0.0.1:8421", None), ("127.0.0.1", "http://127.0.0.1:8421")):
        try:
            WS(port, host=host, origin=origin).close()
            ok(False, "Host %s, Origin %s refused" % (host, origin))
        except (Refused, ConnectionError, OSError):
            ok(True, "Host %s, Origin %s refused" % (host, origin))

sys.exit(1 if fails else 0)
