#!/usr/bin/python3
"""The lesson's settings in `tiptap live` (docs/live.md, "The lesson on the averaged
tier"): for each of the seven settings of tiptap bench's lesson figure
(src/cli/bench_lesson.c) it starts `tiptap live --port 0` on the teaching scene
(scans/standard.ini surfaces/grating.ini examples/feedback-tuning/common.ini, on the
tier common.ini gives) with that setting, lets line 0 pass (it engages and settles),
reads six lines' real time per CPU second of the engine's thread from the status
messages and prints their median and range, then stops the server. A measurement, not
a test: run it on a quiet machine and say what else ran (it prints the load average).

The figure is the status's `realtime_cpu`: src/live/engine.c (run_line) times
tt_run_scan_step, the line's trace and retrace with the scope's record, by the engine
thread's own CPU clock (TT_CLOCK_THREAD) and divides the line's instrument time
(1 / line rate) by it. tt_scan_step runs on the calling thread, and on the averaged
tier the console runs no preview thread, so that clock holds the whole line.

With --errors it also runs `tiptap bench --lesson-only --lesson-tier TIER
--lesson-setting N` for each setting (the same line code, tt_scan_step, beside the
every-cycle tier on the same lines) and prints its height and phase columns: the
line's error against every cycle with the noise on (each tier draws its own noise) and
with the noise 1e9 times colder (the tier's own model error). The bench takes about a
minute a setting on one core (the every-cycle tier runs at a tenth of real time).

usage: scripts/live-lesson.py [--errors] [--lines N] [--setting N]... [--set K=V]... [TIPTAP]
  TIPTAP      the binary (default build/tiptap)
  --errors    add the bench's errors against every cycle
  --lines N   lines measured after line 0 (default 6)
  --setting N only the Nth setting (1 to 7, bench_lesson.c's order); repeatable
  --set K=V   added to every run's scene (e.g. --set solver.tier=envelope)"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
sys.path.insert(0, os.path.join(root, "tests"))
from live_ws import WS  # noqa: E402

# bench_lesson.c's settings, in its order (--lesson-setting N is the Nth)
SETTINGS = [
    ("ki 100 Hz", ["feedback.integral_gain=100 Hz"]),
    ("ki 1.18 kHz", ["feedback.integral_gain=1180 Hz"]),
    ("ki 4 kHz", ["feedback.integral_gain=4 kHz"]),
    ("ki 10 kHz", ["feedback.integral_gain=10 kHz"]),
    ("ki 30 kHz", ["feedback.integral_gain=30 kHz"]),
    ("P 5 (ki 1.18 kHz)", ["feedback.integral_gain=1180 Hz", "feedback.proportional_gain=5"]),
    ("40 Hz lines (ki 1.18 kHz)", ["feedback.integral_gain=1180 Hz", "scan.line_rate=40 Hz"]),
]
SCENE = [os.path.join(root, f) for f in
         ("scans/standard.ini", "surfaces/grating.ini", "examples/feedback-tuning/common.ini")]


def usage(why):
    sys.exit("scripts/live-lesson.py: %s\n%s" % (why, __doc__.split("usage: ", 1)[1]))


def parse(argv):
    opt = {"errors": False, "lines": 6, "only": [], "sets": [],
           "tiptap": os.path.join(root, "build", "tiptap")}
    i = 0
    while i < len(argv):
        a = argv[i]
        if a == "--errors":
            opt["errors"] = True
        elif a in ("--lines", "--setting", "--set"):
            if i + 1 >= len(argv):
                usage("%s needs a value" % a)
            i += 1
            if a == "--set":
                opt["sets"].append(argv[i])
            elif not argv[i].isdigit() or int(argv[i]) < 1 or (a == "--setting" and int(argv[i]) > 7):
                usage("%s: '%s' is not a whole number in range" % (a, argv[i]))
            elif a == "--lines":
                opt["lines"] = int(argv[i])
            else:
                opt["only"].append(int(argv[i]))
        elif a in ("-h", "--help"):
            print(__doc__.split("usage: ", 1)[1])
            sys.exit(0)
        elif a.startswith("-"):
            usage("unknown option %s" % a)
        else:
            opt["tiptap"] = a
        i += 1
    if not os.access(opt["tiptap"], os.X_OK):
        usage("no tiptap binary at %s" % opt["tiptap"])
    return opt


def live(tiptap, sets, lines):
    """One setting in tiptap live: (tier, real time per CPU second of lines 1 .. lines)."""
    args = [tiptap, "live", "--port", "0"] + SCENE
    for s in sets:
        args += ["--set", s]
    err = tempfile.TemporaryFile(mode="w+")
    srv = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=err, text=True)
    try:
        first = srv.stdout.readline()
        if "127.0.0.1:" not in first:
            err.seek(0)
            raise RuntimeError("tiptap live did not start: %s" % err.read().strip())
        ws = WS(int(first.split("127.0.0.1:")[1].split("/")[0]), timeout=600)
        # the status after line k names line k + 1 and carries line k's figures (run_line);
        # the first seen for each line is kept, line 0's dropped
        got, tier, frame = {}, None, None
        while len(got) < lines:
            m = ws.recv()
            if m["type"] != "status" or not m.get("realtime_cpu"):
                continue
            frame = m["frame"] if frame is None else frame
            if m["frame"] != frame or m["passes"] != 0:
                raise RuntimeError("the frame changed or wrapped before %d lines" % lines)
            done = m["line"] - 1
            if done >= 1 and done not in got:
                got[done] = m["realtime_cpu"]
                tier = m["tier"]
        return tier, [got[k] for k in sorted(got)]
    finally:
        srv.send_signal(2)
        try:
            srv.wait(timeout=30)
        except subprocess.TimeoutExpired:
            srv.kill()
            srv.wait()
        err.close()


def bench(tiptap, n, tier):
    """tiptap bench's row for setting n: (height, phase, cold height, cold phase) as printed."""
    out = subprocess.run([tiptap, "bench", "--lesson-only", "--lesson-tier", tier,
                          "--lesson-setting", str(n)], capture_output=True, text=True, check=True)
    for row in out.stdout.splitlines():
        t = row.split()
        if row.startswith("#") or tier not in t:
            continue
        c = t[t.index(tier) + 1:]
        if len(c) >= 8 and "/" in c[3]:
            return c[3], c[4], c[6], c[7]
    raise RuntimeError("no row for setting %d in the bench's output:\n%s" % (n, out.stdout))


def main():
    opt = parse(sys.argv[1:])
    todo = opt["only"] or range(1, len(SETTINGS) + 1)
    print("# tiptap live on the teaching scene (%s), lines 1 to %d after line 0; %s"
          % (" ".join(os.path.relpath(f, root) for f in SCENE), opt["lines"],
             " ".join("--set " + s for s in opt["sets"]) or "the scene's own tier"))
    print("# load average at the start: %s" % " ".join(open("/proc/loadavg").read().split()[:3]))
    print(("%-26s %-9s %-30s%s" % ("setting", "tier", "real time per CPU s (median, range)",
                                  "  height nm max/rms, phase deg max/rms vs every cycle: "
                                  "noise on; colder" if opt["errors"] else "")).rstrip())
    for n in todo:
        label, sets = SETTINGS[n - 1]
        t0 = time.time()
        tier, rt = live(opt["tiptap"], sets + opt["sets"], opt["lines"])
        fig = "%.2fx (%.2f to %.2f)" % (statistics.median(rt), min(rt), max(rt))
        more = ""
        if opt["errors"] and tier in ("envelope", "averaged"):  # the bench's --lesson-tier
            h, ph, ch, cph = bench(opt["tiptap"], n, tier)
            more = "  %s, %s; %s, %s" % (h, ph, ch, cph)
        elif opt["errors"]:
            more = "  (every cycle: no errors against itself)"
        print(("%-26s %-9s %-30s%s" % (label, tier, fig, more)).rstrip(), flush=True)
        print("#   lines: %s (%.0f s)" % (" ".join("%.2f" % x for x in rt), time.time() - t0),
              flush=True)
    print("# load average at the end: %s" % " ".join(open("/proc/loadavg").read().split()[:3]))


if __name__ == "__main__":
    main()
