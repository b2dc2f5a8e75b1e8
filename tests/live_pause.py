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


def wait_status(ws, cond, what, seconds=300):
    """The first status for which cond holds, within a generous bound (sanitizer builds
    run a line in seconds)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        m = ws.recv()
        if m["type"] == "status" and cond(m):
            return m
    raise AssertionError("no status with %s within %d s" % (what, seconds))


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
# the scan's own tier is the scene's (the teaching scene's averaged, common.ini)
ok(row["preview"] is False and row["tier"] == first["tier"],
   "a row of the scan's own tier: tier %s (the status's %s), preview %s"
   % (row["tier"], first["tier"], row["preview"]))
st = wait_status(ws, lambda m: m["judged"] >= 1 and not m["running"], "a judged line")
ok(st["judged_line"] is not None, "after a line: judged %s on line %s" % (st["judged"], st["judged_line"]))
ok(st["error_rms"] > 0 and st["setpoint"] > 0 and st["height_range"] > 0,
   "the judged line's error rms %s, setpoint %s, height range %s" %
   (st["error_rms"], st["setpoint"], st["height_range"]))

# pause: once the line under way ends nothing runs, the thread waits
ws.send("pause")
ok(ws.recv_type("reply")["ok"], "pause accepted")
st = wait_status(ws, lambda m: m["paused"] and not m["running"], "paused, no line under way")
line0 = st["line"]
share = cpu_share(3)
st2 = latest_status(ws, 0.5) or st
ok(st2["line"] == line0 and st2["passes"] == st["passes"] and not st2["running"],
   "paused: the line stays at %s over 3 s (now %s)" % (line0, st2["line"]))
ok(share < 0.10, "paused: the server takes %.1f %% of a core (under 10 %%)" % (100 * share))

# step: exactly one line
lines = fr["lines"]
ws.send("step")
ok(ws.recv_type("reply")["ok"], "step accepted")
st3 = wait_status(ws, lambda m: m["line"] != line0 and not m["running"], "the step's line")
st3 = latest_status(ws, 3.0) or st3
ok(st3["line"] == (line0 + 1) % lines and st3["paused"] is True and not st3["running"],
   "step: line %s to %s, still paused, none after it in 3 s" % (line0, st3["line"]))
ws.send("step")
ws.recv_type("reply")
st4 = wait_status(ws, lambda m: m["line"] != st3["line"] and not m["running"], "the second step's line")
st4 = latest_status(ws, 3.0) or st4
ok(st4["line"] == (line0 + 2) % lines, "a second step: line %s" % st4["line"])

# resume: lines again
ws.send("resume")
ws.recv_type("reply")
st5 = wait_status(ws, lambda m: not m["paused"] and m["line"] not in (st4["line"],), "a line after resume")
ok(True, "resumed: line %s after %s" % (st5["line"], st4["line"]))

# the page closes: idle again
ws.close()
# the line under way ends (generous: sanitizer builds run a line in seconds)
for _ in range(300):
    share = cpu_share(1)
    if share < 0.10:
        break
share = cpu_share(3)
ok(share < 0.10, "the page gone: the server takes %.1f %% of a core (under 10 %%)" % (100 * share))
sys.exit(1 if fails else 0)
