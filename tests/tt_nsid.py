"""Shared by the tests that read tiptap's files with the vendored pyNSID and sidpy
(tests/cli_nsid.sh, tests/cli_nsid_sweep.sh): the readers' versions checked, and ok/FAIL
lines whose failures set the exit status (tt_nsid.done())."""
import sys

import pyNSID
import sidpy

assert pyNSID.__version__ == "0.0.7.2" and sidpy.__version__ == "0.12.8", (pyNSID.__version__, sidpy.__version__)
failed = 0


def check(ok, what):
    global failed
    print(("ok   " if ok else "FAIL ") + what)
    failed |= not ok


def done():
    sys.exit(failed)
