"""tiptap live says what tiptap scan says of the same scene: the run layer's warnings
(the inputs at a scan's first line, the results at a pass's end), in the status message.
usage: live_warnings.py PORT SCAN_STDERR"""
import sys
import time

from live_ws import WS

port, scan_err = int(sys.argv[1]), sys.argv[2]
said = [l.split(": warning: ", 1)[1].rstrip("\n") for l in open(scan_err) if ": warning: " in l]
ws = WS(port)
seen, t0 = None, time.time()
while time.time() - t0 < 60:
    m = ws.recv()
    if m["type"] == "status" and m["passes"] >= 1 and m["warnings"]:
        seen = m
        break
ws.close()
fail = 0
if not seen:
    print("FAIL no status with the run's warnings after a pass")
    sys.exit(1)
texts = [w["text"] for w in seen["warnings"]]
validity = [t for t in said if "contact radius" in t]
if validity and validity[0] in texts and all(w["category"] and w["frame"] == seen["frame"] for w in seen["warnings"]):
    print("ok the console warns as tiptap scan does after pass %d: %s" % (seen["passes"], validity[0][:70]))
else:
    print("FAIL the console's warnings %s, tiptap scan's %s" % (texts, said))
    fail = 1
# everything the console says, tiptap scan says too (it adds the error estimate's)
extra = [t for t in texts if t not in said]
if extra:
    print("FAIL the console warns of what tiptap scan does not: %s" % extra)
    fail = 1
else:
    print("ok every console warning is one of tiptap scan's %d" % len(said))
sys.exit(fail)
