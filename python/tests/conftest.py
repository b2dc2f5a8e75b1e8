"""Shared by the Python package's tests: the source tree, the tiptap program of the same
build (to compare with) and the small scans they run. ctest sets TIPTAP_LIBRARY, TIPTAP,
TT_SOURCE_DIR and PYTHONPATH (CMakeLists.txt)."""

import os
import struct
import subprocess

import numpy as np
import pytest

SRC = os.environ.get("TT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
TIPTAP = os.environ.get("TIPTAP", os.path.join(SRC, "build", "tiptap"))

# The polymer blend on the quick scan, 16 pixels by 4 lines (as scripts/regenerate-all.sh
# scans the bundled surfaces): about a second.
QUICK = [os.path.join(SRC, "scans", "quick.ini"), os.path.join(SRC, "surfaces", "polymer-blend.ini")]
QUICK_SET = {"scan.pixels": "16", "scan.lines": "4"}


def src(*parts):
    return os.path.join(SRC, *parts)


def cli(*args, check=True):
    """Run the tiptap program; returns the CompletedProcess (text)."""
    p = subprocess.run([TIPTAP, *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"tiptap {' '.join(map(str, args))}: exit {p.returncode}: {p.stderr}")
    return p


def sets(mapping):
    out = []
    for k, v in mapping.items():
        out += ["--set", f"{k}={v}"]
    return out


def read_gsf(path):
    """A GSF file (include/tiptap/io/gsf.h): its header as a dict and its float32 data
    (as stored, little-endian) of shape (YRes, XRes)."""
    with open(path, "rb") as f:
        raw = f.read()
    end = raw.index(b"\0")
    header = {}
    for line in raw[:end].decode().splitlines()[1:]:
        k, v = line.split(" = ", 1)
        header[k] = v
    start = (end // 4 + 1) * 4
    nx, ny = int(header["XRes"]), int(header["YRes"])
    data = np.frombuffer(raw[start:start + 4 * nx * ny], dtype="<f4").reshape(ny, nx)
    assert len(raw) == start + 4 * nx * ny
    return header, data


@pytest.fixture(scope="session")
def quick_cli(tmp_path_factory):
    """The small scan by the program: its output folder."""
    out = tmp_path_factory.mktemp("cli") / "quick"
    cli("scan", *QUICK, *sets(QUICK_SET), "-o", out, "-q")
    return out
