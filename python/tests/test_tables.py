"""approach(), trace(), contact(), accuracy(): the program's CSV numbers, in SI, from
the same library calls: each value printed as the program prints it gives its CSV
field."""

import csv
import math

import numpy as np
import pytest

import tiptap
from conftest import cli, sets, src

FIG4A = src("examples", "seed-fig4a", "scene.ini")
FIG4B = src("examples", "seed-fig4b", "scene.ini")


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def g(v, digits=9):
    """A number as C's printf %.Ng prints it."""
    if math.isnan(v):
        return "nan"
    return f"{v:.{digits}g}"


def check_columns(table, rows, columns):
    """columns: {CSV column: (table column, scale, digits or 'd' or 's')}."""
    assert table.rows == len(rows)
    for name, (col, scale, fmt) in columns.items():
        for i, row in enumerate(rows):
            v = table[col][i]
            if fmt == "s":
                got = str(v)
            elif fmt == "d":
                got = str(int(v))
            else:
                got = g(v * scale, fmt)
            assert got == row[name], (name, i, got, row[name])


def test_approach_is_the_programs_csv(tmp_path):
    over = {"approach.points": "30"}
    cli("approach", FIG4A, *sets(over), "-o", tmp_path / "a.csv", "-q")
    t = tiptap.approach(FIG4A, set=over, progress=False)
    assert t.units["z"] == "m" and t.units["phase"] == "deg" and t.units["dissipated"] == "J"
    check_columns(t, csv_rows(tmp_path / "a.csv"), {
        "z_nm": ("z", 1e9, 9), "amplitude_nm": ("amplitude", 1e9, 9), "phase_deg": ("phase", 1, 9),
        "mean_deflection_nm": ("mean_deflection", 1e9, 9), "peak_force_nN": ("peak_force", 1e9, 9),
        "max_indentation_nm": ("max_indentation", 1e9, 9),
        "contact_fraction": ("contact_fraction", 1, 9), "dissipated_aJ": ("dissipated", 1e18, 9),
        "branch": ("branch", 1, "s"), "settled": ("settled", 1, "d"), "cycles": ("cycles", 1, "d"),
        "drive_work_aJ": ("drive_work", 1e18, 9), "energy_residual": ("energy_residual", 1, 3),
        "deflection_min_nm": ("deflection_min", 1e9, 9),
        "deflection_max_nm": ("deflection_max", 1e9, 9),
    })
    assert set(t["branch"]) == {"approach", "retract"}


def test_trace_is_the_programs_csv(tmp_path):
    over = {"trace.cycles": "20"}
    cli("trace", FIG4B, *sets(over), "-o", tmp_path / "t.csv", "-q")
    t = tiptap.trace(FIG4B, set=over, progress=False)
    rows = csv_rows(tmp_path / "t.csv")
    check_columns(t, rows, {
        "t_us": ("t", 1e6, 9), "base_nm": ("base", 1e9, 9), "tip_nm": ("tip", 1e9, 9),
        "sample_nm": ("sample", 1e9, 9), "deflection_nm": ("deflection", 1e9, 9),
        "force_nN": ("force", 1e9, 9), "contact_radius_nm": ("contact_radius", 1e9, 9),
        "pressure_GPa": ("pressure", 1e-9, 9), "contact": ("contact", 1, "d"),
    })
    assert t["cycle"][0] == 0 and t["cycle"][-1] == 19
    assert t.units["pressure"] == "Pa"


def test_a_ramped_key_is_a_column_in_its_unit(tmp_path):
    over = {"trace.cycles": "10", "trace.ramp": "material.glass.adhesion_energy",
            "trace.ramp_from": "2 mJ/m^2", "trace.ramp_to": "72 mJ/m^2"}
    s = tiptap.Scene(src("examples", "seed-fig5", "scene.ini"), set=over)
    t = tiptap.trace(s, progress=False)
    col = "material.glass.adhesion_energy"
    assert t.units[col] == "J/m^2"
    assert t[col][0] == pytest.approx(2e-3) and t[col][-1] == pytest.approx(72e-3)
    # the scene given is not changed by the ramp
    assert s["material.glass.adhesion_energy"] != "72 mJ/m^2"


def test_contact_is_the_programs_curve_and_summary(tmp_path):
    scene = src("examples", "extreme", "captured.ini")
    p = cli("contact", scene, "-o", tmp_path / "c.csv")
    t = tiptap.contact(scene)
    check_columns(t, csv_rows(tmp_path / "c.csv"), {
        "A": ("A", 1, 10), "Delta": ("Delta", 1, 10), "P": ("P", 1, 10), "stable": ("stable", 1, "d")})
    summary = dict(line.split(" = ", 1) for line in p.stdout.splitlines())
    for key, value in summary.items():
        if key in ("model", "adhesive"):
            continue
        number = value.split(" ")[0]
        assert g(t.meta[key], 10) == number, key
    normalised = tiptap.contact(lam=1)
    lines = dict(l.split(" = ", 1) for l in cli("contact", "--lambda", "1").stdout.splitlines())
    assert g(normalised.meta["pulloff_load"], 10) == lines["pulloff_load"]
    with pytest.raises(tiptap.SceneError, match="no \\[material nothing\\] section"):
        tiptap.contact(scene, material="nothing")


def test_accuracy_rows_are_the_programs(tmp_path):
    over = {"approach.points": "1"}
    args = ["--methods", "rk4", "--repeats", "1", "--cycles", "100"]
    cli("accuracy", FIG4A, *sets(over), *args, "-o", tmp_path / "acc.csv", "-q")
    t = tiptap.accuracy(FIG4A, set=over, methods="rk4", repeats=1, cycles=100, progress=False)
    rows = csv_rows(tmp_path / "acc.csv")
    # the errors and the settings, not the times
    check_columns(t, rows, {
        "method": ("method", 1, "s"), "knob": ("knob", 1, "s"), "value": ("value", 1, 6),
        "amplitude_err_rel": ("amplitude_err_rel", 1, 6), "phase_err_deg": ("phase_err_deg", 1, 6),
        "residual_rel": ("residual_rel", 1, 3), "role": ("role", 1, "s"),
        "status": ("status", 1, "s"),
    })
    assert t.units["run_time"] == "s" and t.units["mean_err_m"] == "m"
    assert t.meta["kind"] == "point" and t.meta["cycles"] == 100
    assert list(t["role"][:2]) == ["reference", "floor"]
    with pytest.raises(tiptap.SceneError, match="unknown method 'rk5'; known: dopri5"):
        tiptap.accuracy(FIG4A, methods="rk5")


def test_tables_hold_numpy_arrays():
    t = tiptap.approach(FIG4A, set={"approach.points": "5"}, progress=False)
    assert isinstance(t["z"], np.ndarray) and t["z"].dtype == np.float64
    assert t["branch"].dtype.kind == "U"
    assert "amplitude [m]" in repr(t)
