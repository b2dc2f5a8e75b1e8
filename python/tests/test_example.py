"""examples/python/material_contrast.py is the study of examples/material-contrast:
its rows are the program's sweep's, as the program prints them (on one free amplitude
of the four, to keep the test short)."""

import csv
import sys

from conftest import cli, src
from test_tables import g

sys.path.insert(0, src("examples", "python"))
import material_contrast  # noqa: E402


def test_the_python_study_is_the_programs(tmp_path):
    t, d = material_contrast.study(amplitudes="40nm", progress=False)
    cli("sweep", *material_contrast.SCENE, "--vary", "cantilever.free_amplitude=40nm",
        "--vary", "approach.material=matrix,disk", "--vary", "feedback.setpoint=10%:95%:18",
        "--run", "setpoint", "-o", tmp_path / "c.csv", "-q")
    with open(tmp_path / "c.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert t.rows == len(rows) == 36
    for i, row in enumerate(rows):
        assert g(t["feedback.setpoint"][i]) == row["feedback.setpoint[1]"]
        assert g(t["z"][i] * 1e9) == row["z_nm"], i
        assert g(t["phase"][i]) == row["phase_deg"], i
        assert g(t["dissipated"][i] * 1e18) == row["dissipated_aJ"], i
    # the differences, disk minus matrix, at each setpoint
    z = t["z"].reshape(2, 18)
    assert d["height"].shape == (1, 18) and (d["height"][0] == z[1] - z[0]).all()
    # at 80 % of 40 nm the disks read about 2 nm low (docs/sweeps.md's table)
    j = abs(t["feedback.setpoint"][:18] - 0.8).argmin()
    assert -2.5e-9 < d["height"][0, j] < -1.5e-9


def test_the_readme_says_what_the_example_does():
    """examples/python/README.md: the command it gives is the script's, the files it
    names are there, and its 80 % figure is the study's."""
    import os
    import re

    with open(src("examples", "python", "README.md")) as f:
        readme = f.read()
    command = ("PYTHONPATH=python TIPTAP_LIBRARY=build/libtiptap.so /usr/bin/python3 "
               "examples/python/material_contrast.py")
    assert command in readme and command in material_contrast.__doc__
    for name in re.findall(r"`([\w.-]+\.(?:py|ipynb))`", readme):
        assert os.path.exists(src("examples", "python", name)) or \
            os.path.exists(src("python", "tests", name)), name
    low = float(re.search(r"at 80 % of 40 nm the disks read\s+([\d.]+) nm low", readme).group(1))
    t, d = material_contrast.study(amplitudes="40nm", progress=False)
    j = abs(t["feedback.setpoint"][:18] - 0.8).argmin()
    assert round(-d["height"][0, j] * 1e9, 2) == low
