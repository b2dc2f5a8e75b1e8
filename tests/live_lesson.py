#!/usr/bin/python3
"""A lesson in tiptap live, over its WebSocket and HTTP (tests/cli_live_lesson.sh starts
the server with --lesson): the controls message carries the lesson's title and
instructions and marks its hidden and locked controls; the server refuses a change to a
locked or hidden control, naming the lesson, and changes nothing; a free control changes;
lesson.ini (the page's "save lesson") holds the [lesson] section and the scene in force,
written to OUT for the script to start again.

usage: live_lesson.py PORT OUT"""
import http.client
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_ws import WS  # noqa: E402

port, out = int(sys.argv[1]), sys.argv[2]
fails = 0


def ok(cond, what):
    global fails
    print(("ok " if cond else "FAIL ") + what)
    fails += not cond


def by_name(msg):
    return {c["name"]: c for c in msg["controls"]}


ws = WS(port)
ctl = ws.recv_type("controls")
ls = ctl.get("lesson") or {}
ok(ls.get("title") == "Tuning the I gain", "the lesson's title: %s" % ls.get("title"))
ok(ls.get("instructions", "").split("\n") ==
   ["Raise the I gain until the scope rings.", "Then take the warning's suggestion."],
   "its instructions, two lines: %r" % ls.get("instructions"))
c = by_name(ctl)
ok([n for n in c if c[n]["hidden"]] == ["noise", "solver.tier"], "hidden: noise, solver.tier")
ok([n for n in c if c[n]["locked"]] == ["scan.size", "scan.pixels"], "locked: scan.size, scan.pixels")
size0 = c["scan.size"]["value"]

for msg, word in (("set scan.size = 500 nm", "locked"), ("set scan.pixels = 32", "locked"),
                  ("set noise = off", "hidden"),
                  ("set feedback.integral_gain = 1500 Hz\nset scan.size = 500 nm", "locked")):
    ws.send(msg)
    r = ws.recv_type("reply")
    ok(not r["ok"] and ("is %s by the lesson" % word) in r["error"],
       "refused, %s: %r -> %s" % (word, msg, r["error"]))
ws.send("set feedback.integral_gain = 2 kHz")
ok(ws.recv_type("reply")["ok"], "a free control changes: I gain 2 kHz")
c = by_name(ws.recv_type("controls"))
ok(c["scan.size"]["value"] == size0 and c["feedback.integral_gain"]["value"] in ("2 kHz", "2000"),
   "the size stays %s, I gain now %s" % (c["scan.size"]["value"], c["feedback.integral_gain"]["value"]))

# the change's own line ran (an export shows the scene of the lines it holds)
for _ in range(100000):
    m = ws.recv()
    if m["type"] == "status" and m["accurate_ms"] is not None:
        break
h = http.client.HTTPConnection("127.0.0.1", port, timeout=300)
h.request("GET", "/export/lesson.ini")
r = h.getresponse()
body = r.read().decode()
ok(r.status == 200 and body.startswith("[lesson]\ntitle = Tuning the I gain\n"),
   "lesson.ini: %d, starts with the [lesson] section" % r.status)
ok("lock = scan.size, scan.pixels" in body and "hide = noise, solver.tier" in body,
   "lesson.ini keeps the locks and hidden controls")
ok("integral_gain = 2 kHz" in body or "integral_gain = 2000" in body, "lesson.ini has the I gain in force")
with open(out, "w") as f:
    f.write(body)
ws.close()
sys.exit(1 if fails else 0)
