"""A material map from a numpy integer array (Scene.set_material_labels): the materials
where the labels put them, the same images as the GSF label file the CLI reads, and bad
arrays or names refused (docs/surfaces.md, "Material maps from data")."""

import os

import numpy as np
import pytest

import tiptap
from conftest import SRC

SCAN = os.path.join(SRC, "scans", "quick.ini")
BLEND = os.path.join(SRC, "surfaces", "polymer-blend.ini")
SET = {"scan.pixels": "16", "scan.lines": "2", "scan.size": "64 nm"}
DX = 4e-9


def halves():
    """16 x 16 labels of 4 nm: 0 on the left half, 1 on the right."""
    a = np.zeros((16, 16), dtype=np.uint8)
    a[:, 8:] = 1
    return a


def test_labels_from_numpy_give_the_materials_where_they_are(tmp_path):
    s = tiptap.Scene(BLEND, SCAN, set=SET)
    s.set_material_labels(halves(), DX, {0: "matrix", 1: "disk"})
    n = tiptap.scan(s, progress=False)
    # the same labels through a GSF file, as a scene file names it
    path = tmp_path / "l.gsf"
    head = (f"Gwyddion Simple Field 1.0\nXRes = 16\nYRes = 16\nXReal = {16 * DX!r}\n"
            f"YReal = {16 * DX!r}\nXYUnits = m\n").encode()
    path.write_bytes(head + b"\0" * (4 - len(head) % 4) + halves().astype("<f4").tobytes())
    f = tiptap.scan(tiptap.Scene(BLEND, SCAN, set=dict(SET, **{
        "surface.map": "labels", "surface.map_image": str(path),
        "material.matrix.map_value": "0", "material.disk.map_value": "1"})), progress=False)
    assert n["phase"].tobytes() == f["phase"].tobytes()
    # swapped labels swap the sides: the matrix's phase moves to the right half
    w = tiptap.scan(tiptap.Scene(BLEND, SCAN, set=SET).set_material_labels(
        1 - halves(), DX, {0: "matrix", 1: "disk"}), progress=False)
    left, right = n["phase"][:, 2], n["phase"][:, 13]
    assert abs(left.mean() - right.mean()) > 10  # matrix and disk differ by tens of degrees
    np.testing.assert_allclose(w["phase"][:, 13], left, atol=1)
    np.testing.assert_allclose(w["phase"][:, 2], right, atol=1)


def test_bad_labels_are_refused():
    s = tiptap.Scene(BLEND, SCAN, set=SET)
    with pytest.raises(ValueError, match="must be integers"):
        s.set_material_labels(halves() * 0.5, DX, {0: "matrix"})
    with pytest.raises(ValueError, match="no \\[material glass\\]"):
        s.set_material_labels(halves(), DX, {0: "matrix", 1: "glass"})
    with pytest.raises(ValueError, match="labels -1 to 1"):
        s.set_material_labels(halves().astype(int) - (halves() == 0), DX, {0: "matrix"})
    # a label with no material: refused by the library when the scene is run
    s.set_material_labels(halves(), DX, {0: "matrix"})
    with pytest.raises(tiptap.SceneError) as e:
        tiptap.scan(s, progress=False)
    assert "label 1, which no [material] map_value names" in str(e.value)
