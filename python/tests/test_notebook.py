"""examples/python/material-contrast.ipynb runs: its code cells in order, from the
repository's root, give the study's arrays (the whole study: about half a minute on two
cores). Jupyter is not needed: the cells are plain Python."""

import json
import os

from conftest import SRC, src


def test_the_notebooks_cells_run(monkeypatch):
    with open(src("examples", "python", "material-contrast.ipynb")) as f:
        nb = json.load(f)
    cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
    assert all(c["outputs"] == [] and c["execution_count"] is None for c in cells)
    monkeypatch.chdir(SRC)
    ns = {}
    for c in cells:
        code = "".join(c["source"]).replace('run="setpoint")', 'run="setpoint", progress=False)')
        exec(compile(code, "material-contrast.ipynb", "exec"), ns)
    assert ns["t"].rows == 144
    assert ns["height"].shape == ns["dphase"].shape == (4, 18)
    # at 80 nm and 20 % the disks read higher, at 95 % lower (docs/sweeps.md)
    assert ns["height"][3, 2] > 0 > ns["height"][3, 17]
    assert os.getcwd() == os.path.abspath(SRC)
