#!/usr/bin/python3
"""The figures of tiptap live in docs/live.md: how soon a gain change shows (the
averaged preview, then the scan's own tier) and how fast the instrument runs against
its own clock (wall and per CPU second of the engine's thread). A measurement, not a
test: run it on a quiet machine and say what else ran.

usage: scripts/live-figures.py TIPTAP SECONDS SCENE... [--set K=V]...
It starts `tiptap live --port 0 SCENE...`, lets one line run, then alternates the I gain
between 1.5 and 2.5 kHz once a line for SECONDS and prints the medians."""
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from live_ws import WS  # noqa: E402

tiptap, seconds, scene = sys.argv[1], float(sys.argv[2]), sys.argv[3:]
srv = subprocess.Popen([tiptap, "live", "--port", "0"] + scene, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
line = srv.stdout.readline()
port = int(line.split("127.0.0.1:")[1].split("/")[0])
ws = WS(port, timeout=600)
preview, accurate, rt, rt_cpu, line_s = [], [], [], [], []
last = None
t_end = time.time() + seconds
gain = 0
pending = False
while time.time() < t_end:
    m = ws.recv()
    if m["type"] != "status" or not m["realtime"]:
        continue
    if (m["frame"], m["line"], m["passes"]) != last:  # a line finished
        last = (m["frame"], m["line"], m["passes"])
        rt.append(m["realtime"])
        rt_cpu.append(m["realtime_cpu"])
        line_s.append(m["line_s"])
        # each change's figures once (the status repeats the last ones)
        if pending and m["accurate_ms"] and (not accurate or m["accurate_ms"] != accurate[-1]):
            accurate.append(m["accurate_ms"])
        if pending and m["preview_ms"] and (not preview or m["preview_ms"] != preview[-1]):
            preview.append(m["preview_ms"])
        gain += 1
        ws.send("set feedback.integral_gain = %d Hz" % (1500 if gain % 2 else 2500))
        pending = True
srv.send_signal(2)
srv.wait()


def med(x, unit):
    return "%.3g %s (median of %d; %.3g to %.3g)" % (statistics.median(x), unit, len(x), min(x),
                                                  max(x)) if x else "none"


print("scene: %s" % " ".join(scene))
print("change to its preview line (averaged tier): %s" % med(preview, "ms"))
print("change to its line on the scan's own tier: %s" % med(accurate, "ms"))
print("a line's work: %s" % med(line_s, "s"))
print("real-time factor, wall: %s" % med(rt, "x"))
print("real-time factor per CPU second of the engine's thread: %s" % med(rt_cpu, "x"))
print("load average at the end: %s" % open("/proc/loadavg").read().split()[:3])
