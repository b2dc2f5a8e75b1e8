"""A measured topography drives a scan from each source it may come from: a numpy array,
a GSF, a 16-bit PNG and a .gwy written by Gwyddion itself (docs/surfaces.md, "Measured
surfaces"); the artefact channel is height - topography."""

import os
import shutil
import struct
import subprocess
import zlib

import numpy as np
import pytest

import tiptap
from conftest import SRC

SCAN = os.path.join(SRC, "scans", "quick.ini")
SET = {"scan.pixels": "16", "scan.lines": "4", "scan.size": "64 nm"}
DX = 4e-9
TOP = 3e-9


def bump():
    """A 16 x 16 image, 4 nm pixels: a Gaussian bump TOP high on a flat."""
    j, i = np.mgrid[0:16, 0:16]
    return (TOP * np.exp(-((i - 7.5) ** 2 + (j - 7.5) ** 2) / (2 * 3.0 ** 2))).astype("<f4")


def write_gsf(path, z, dx):
    ny, nx = z.shape
    head = (f"Gwyddion Simple Field 1.0\nXRes = {nx}\nYRes = {ny}\nXReal = {nx * dx!r}\n"
            f"YReal = {ny * dx!r}\nXYUnits = m\nZUnits = m\nTitle = Height\n").encode()
    with open(path, "wb") as f:
        f.write(head + b"\0" * (4 - len(head) % 4) + z.astype("<f4").tobytes())


def write_png16(path, levels):
    """A 16-bit grey PNG, written by hand (zlib), so that the test needs no imaging package."""
    ny, nx = levels.shape
    raw = b"".join(b"\0" + levels[j].astype(">u2").tobytes() for j in range(ny))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", nx, ny, 16, 0, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def scan(**keys):
    s = tiptap.Scene(SCAN, set=SET)
    s.set(keys)
    return tiptap.scan(s, progress=False)


@pytest.fixture(scope="module")
def from_gsf(tmp_path_factory):
    d = tmp_path_factory.mktemp("measured")
    write_gsf(d / "bump.gsf", bump(), DX)
    return d, scan(**{"surface.type": "measured", "surface.image": str(d / "bump.gsf")})


def test_a_gsf_drives_a_scan_with_topography_and_artefact(from_gsf):
    _, r = from_gsf
    assert "topography" in r.channels and "artefact" in r.channels
    topo = r["topography"]
    # the tip passes over the bump: the true surface under it reaches most of TOP
    assert 0.5 * TOP < topo.max() <= TOP and abs(topo.min()) < 0.05 * TOP
    np.testing.assert_allclose(r["artefact"], r["height"] - r["topography"], atol=1e-15)
    assert r.units["artefact"] == "m"


def test_a_numpy_array_gives_the_gsfs_scan(from_gsf):
    _, r = from_gsf
    s = tiptap.Scene(SCAN, set=SET)
    s.set_surface_image(bump(), DX)
    n = tiptap.scan(s, progress=False)
    # the same float32 heights: the same surface, the same images bit for bit
    assert n["topography"].tobytes() == r["topography"].tobytes()
    assert n["height"].tobytes() == r["height"].tobytes()


def test_a_16_bit_png_with_its_scale_gives_the_gsfs_surface(from_gsf):
    d, r = from_gsf
    levels = np.round(bump() / TOP * 65535).astype(np.uint16)
    write_png16(d / "bump.png", levels)
    p = scan(**{"surface.type": "measured", "surface.image": str(d / "bump.png"),
                "surface.pixel_size": "4 nm", "surface.png_height_range": "3 nm"})
    # within half a level of the PNG's 16 bits
    np.testing.assert_allclose(p["topography"], r["topography"], atol=0.5 * TOP / 65535 + 1e-16)


@pytest.mark.skipif(shutil.which("gwyddion") is None, reason="Gwyddion is not installed")
def test_a_gwy_written_by_gwyddion_gives_the_gsfs_scan(from_gsf):
    d, r = from_gsf
    out = d / "by-gwyddion.gwy"
    subprocess.run(["gwyddion", f"--convert-to-gwy={out}", str(d / "bump.gsf")], check=True,
                   timeout=120, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for channel in ("Height", "0"):
        g = scan(**{"surface.type": "measured", "surface.image": str(out), "surface.channel": channel})
        assert g["topography"].tobytes() == r["topography"].tobytes()
    with pytest.raises(tiptap.SceneError) as e:
        scan(**{"surface.type": "measured", "surface.image": str(out), "surface.channel": "Phase"})
    assert "no channel 'Phase'" in str(e.value) and "0 'Height'" in str(e.value)
    assert "\n" not in str(e.value)


def test_a_nan_in_the_array_is_refused_in_one_line():
    z = bump()
    z[2, 3] = np.nan
    s = tiptap.Scene(SCAN, set=SET)
    s.set_surface_image(z, DX)
    with pytest.raises(tiptap.SceneError) as e:
        tiptap.scan(s, progress=False)
    msg = str(e.value)
    assert "[surface] image" in msg and "pixel (3, 2)" in msg and "heights.gsf" in msg
    assert "\n" not in msg
