#!/usr/bin/python3
"""tiptap live's pause, step and idle, its honest status and its images, over its
WebSocket (tests/cli_live_lesson.sh starts the server on the teaching scene at 8 Hz):

  * with no page open the engine waits: the server's CPU over 3 s is under 10 % of a
    core (a running scan takes most of one), and no line ran while no page looked;
  * before the first line is judged the status says judged 0 and no judged line, and
    sends no latency (null) before any change;
  * the frame has amplitude and peak-force images beside height, error and phase;
  * pause: no line in 3 s and the server's CPU under 10 % of a core; step: exactly one
    line; resume: lines again;
  * the rows of the scan's own tier are not marked as previews.

usage: live_pause.py PORT PID"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_ws import WS  # noqa: E402

port, pid = int(sys.argv[1]), int(sys.argv[2])
fails = 0


def ok(cond, what):
    global fails
    print(("ok " if cond else "FAIL ") + what)
    fails += not cond


def cpu_seconds():
    """The server's user + system CPU time so far (/proc/PID/stat, clock ticks)."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def cpu_share(seconds):
    c0, t0 = cpu_seconds(), time.monotonic()
    time.sleep(seconds)
    return (cpu_seconds() - c0) / (time.monotonic() - t0)


def latest_status(ws, seconds):
    """The newest status within `seconds` (the messages drained meanwhile)."""
    st = None
    ws.s.settimeout(0.5)
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        try:
            m = ws.recv()
        except OSError:
            continue
        if m["type"] == "status":
            st = m
    ws.s.settimeout(60)
    return st


# no page yet: idle from the start
share = cpu_share(3)
ok(share < 0.10, "no page: the server takes %.1f %% of a core (under 10 %%)" % (100 * share))

ws = WS(port)
fr = ws.recv_type("frame")
names = [c["name"] for c in fr["channels"]]
ok(names == ["height", "error", "phase", "amplitude", "peak_force"],
   "the frame's images: %s" % names)
first = ws.recv_type("status")
ok(first["lines_done"] == 0 and first["passes"] == 0,
   "no line ran while no page looked (lines_done %d)" % first["lines_done"])
ok(first["judged"] == 0 and first["judged_line"] is None,
   "before the first line: judged %s, judged_line %s" % (first["judged"], first["judged_line"]))
ok(first["preview_ms"] is None and first["accurate_ms"] is None,
   "no change yet: latencies %s, %s" % (first["preview_ms"], first["accurate_ms"]))

# a line comes, judged, its row not a preview
row = ws.recv_type("row", limit=100000)
ok(len(row["data"]) == 2 * len(names), "a row carries %d lines (5 channels, both ways)" % len(row["data"]))
ok(row["preview"] is False and row["tier"] == "envelope",
   "a row of the scan's own tier: tier %s, preview %s" % (row["tier"], row["preview"]))
st = latest_status(ws, 1.5)
ok(st and st["judged"] >= 1 and st["judged_line"] is not None,
   "after a line: judged %s on line %s" % (st and st["judged"], st and st["judged_line"]))
ok(st and st["error_rms"] > 0 and st["setpoint"] > 0 and st["height_range"] > 0,
   "the judged line's error rms %s, setpoint %s, height range %s" %
   (st and st["error_rms"], st and st["setpoint"], st and st["height_range"]))

# pause: nothing runs, the thread waits
ws.send("pause")
ok(ws.recv_type("reply")["ok"], "pause accepted")
time.sleep(1.0)  # the line under way ends (8 Hz: 0.125 s a line, slower under load)
st = latest_status(ws, 1.0)
line0 = st["line"] if st else None
ok(st and st["paused"] is True, "the status says paused")
share = cpu_share(3)
st2 = latest_status(ws, 0.5) or st
ok(st2["line"] == line0 and st2["passes"] == st["passes"],
   "paused: the line stays at %s over 3 s (now %s)" % (line0, st2["line"]))
ok(share < 0.10, "paused: the server takes %.1f %% of a core (under 10 %%)" % (100 * share))

# step: exactly one line
ws.send("step")
ok(ws.recv_type("reply")["ok"], "step accepted")
st3 = latest_status(ws, 3.0)
lines = fr["lines"]
ok(st3 and st3["line"] == (line0 + 1) % lines and st3["paused"] is True,
   "step: line %s to %s, still paused" % (line0, st3 and st3["line"]))
ws.send("step")
ws.recv_type("reply")
st4 = latest_status(ws, 3.0)
ok(st4 and st4["line"] == (line0 + 2) % lines, "a second step: line %s" % (st4 and st4["line"]))

# resume: lines again
ws.send("resume")
ws.recv_type("reply")
st5 = latest_status(ws, 3.0)
ok(st5 and st5["paused"] is False and st5["line"] != st4["line"],
   "resumed: line %s after %s" % (st5 and st5["line"], st4["line"]))

# the page closes: idle again
ws.close()
time.sleep(1.0)
share = cpu_share(3)
ok(share < 0.10, "the page gone: the server takes %.1f %% of a core (under 10 %%)" % (100 * share))
sys.exit(1 if fails else 0)
