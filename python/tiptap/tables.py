"""Runs that give tables: approach(), trace(), force(), tune(), contact(), accuracy() (and
sweep(), in sweep.py). Each returns a Table: a dict of numpy arrays, one per column, in
SI units (the phase in degrees), with .units and .meta; force_volume() a Table of maps."""

import math

import numpy as np

from ._errors import SceneError, check
from ._lib import ffi, lib, text
from ._run import Progress, finish, run
from ._warnings import Collector
from .scene import Scene, c_bytes, check_keywords


class Table(dict):
    """Columns by name (numpy arrays: float64, or str for text columns), in the library's
    order; t.units[name] is the column's SI unit ("" for counts, fractions and texts);
    t.meta holds what the table is of (numbers as floats where they read as one);
    t.warnings the library's warnings about the run, a list of (category, message)."""

    def __init__(self, columns=(), units=None, meta=None):
        super().__init__(columns)
        self.units = dict(units or {})
        self.meta = dict(meta or {})
        self.warnings = []

    @property
    def rows(self):
        return len(next(iter(self.values()))) if self else 0

    def __repr__(self):
        cols = ", ".join(f"{k} [{self.units[k]}]" if self.units.get(k) else k for k in self)
        return f"<tiptap.Table {self.rows} rows: {cols}>"


def _number(v):
    try:
        return float(v)
    except ValueError:
        return v


def table_of(p):
    """A tt_table as a Table (copied), then freed."""
    if p == ffi.NULL:
        return None
    try:
        rows = lib.tt_table_rows(p)
        t = Table()
        for c in range(lib.tt_table_columns(p)):
            name = text(lib.tt_table_name(p, c))
            if lib.tt_table_is_text(p, c):
                t[name] = np.array([text(lib.tt_table_text(p, c, r)) for r in range(rows)], dtype=str)
            else:
                buf = ffi.buffer(lib.tt_table_numbers(p, c), rows * 8) if rows else b""
                t[name] = np.frombuffer(buf, dtype=np.float64).copy()
            t.units[name] = text(lib.tt_table_unit(p, c))
        for i in range(lib.tt_table_metas(p)):
            t.meta[text(lib.tt_table_meta_key(p, i))] = _number(text(lib.tt_table_meta_value(p, i)))
        return t
    finally:
        lib.tt_table_free(p)


def _refused(message):
    return SceneError(lib.TT_EINVAL, message)


def _run_table(call, what, unit, progress):
    """call(out, progress_c) -> status: a run layer function into a tt_table."""
    out = ffi.new("tt_table **")
    prog = Progress(progress, what, unit)
    col = Collector()
    status, message, interrupted = run(lambda: call(out, prog.c), prog, col)
    result = table_of(out[0])
    col.emit(stacklevel=3, result=result)
    finish(status, message, interrupted, what, result, prog)
    return result


def approach(scene, *, set=None, progress=None, **keys):
    """The approach curve of the scene's [approach] (`tiptap approach`): a row per point
    of both branches; z, amplitude, phase, mean_deflection, peak_force, max_indentation,
    contact_fraction, dissipated, branch, settled, cycles, drive_work, energy_residual,
    deflection_min, deflection_max, period; with a viscous material (viscosity,
    film_thickness) also the loss per mechanism, dissipated_hysteresis,
    dissipated_damping, dissipated_viscous; with mode 2 driven ([cantilever]
    mode2_free_amplitude) also its lock-in's amplitude_2 (m) and phase_2 (deg). Points
    that did not settle are warned of (tiptap.SettleWarning)."""
    s = Scene.of(scene, set, caller="approach", **keys)
    return _run_table(lambda out, c: lib.tt_run_approach(s._p, out, c, ffi.NULL), "approach",
                      "points", progress)


def trace(scene, *, set=None, progress=None, **keys):
    """The time trace of the scene's [trace] (`tiptap trace`): samples_per_cycle rows per
    recorded cycle; cycle, t, base, tip, sample, deflection, force, contact_radius,
    pressure, contact, and the ramped key's value when [trace] ramp is set."""
    s = Scene.of(scene, set, caller="trace", **keys)
    return _run_table(lambda out, c: lib.tt_run_trace(s._p, out, c, ffi.NULL), "trace", "cycles",
                      progress)


def force(scene, *, set=None, progress=None, **keys):
    """The force-distance curve of the scene's [force] (`tiptap force`): a row per sample;
    t, z (rest separation), deflection, separation (negative: indentation), force
    (tip-sample, repulsive positive), lever_force (-k deflection), contact, leg
    (approach, dwell, retract). .meta holds what the command prints, in SI units: k,
    speed, cycles, jumpin_z, jumpin_force, jumpin_gap, contact_z, pulloff_z,
    pulloff_force, adhesion, max_force, slope, slope_deflection, slope_retract,
    indentation (docs/force-and-tune.md)."""
    s = Scene.of(scene, set, caller="force", **keys)
    return _run_table(lambda out, c: lib.tt_run_force(s._p, out, ffi.NULL, c, ffi.NULL), "force",
                      "periods", progress)


def tune(scene, *, set=None, progress=None, **keys):
    """The thermal tune of the scene's [tune] and [noise] (`tiptap tune`): a row per bin of
    the spectrum; f, psd (one-sided, m^2/Hz), fit (NAN outside the fit's window). .meta
    holds the fit and its statistical errors, in SI units: f0, f0_err, Q, Q_err, k, k_err,
    chi, white, white_err, chi2_dof, variance, variance_err, noise_factor and the
    record's temperature, sample_rate, bin_width, segments, averages, fit_low, fit_high,
    cycles (docs/force-and-tune.md)."""
    s = Scene.of(scene, set, caller="tune", **keys)
    return _run_table(lambda out, c: lib.tt_run_tune(s._p, out, ffi.NULL, c, ffi.NULL), "tune",
                      "periods", progress)


class ForceVolume(Table):
    """A force volume's maps by name (numpy float64 arrays of shape (lines along y,
    pixels along x), row 0 at y = 0, as a scan's images; NaN where a line did not
    finish): height, adhesion, stiffness, pulloff_distance, pulloff_force, indentation,
    max_force, material; .units (SI), .x and .y (pixel centres, m), .meta
    (lines_finished, lines_total, drive_periods)."""


def force_volume(scene, *, threads=0, output=None, hdf5=False, set=None, progress=None, **keys):
    """A force curve at every pixel of the scene's [scan] raster over its [surface] and
    materials (`tiptap force --volume`): a ForceVolume of maps. output: a folder written as
    the program writes it (GSF and PNG per map, force_volume.gwy, scene.ini, and
    force_volume.h5 with hdf5), also with the lines finished when stopped; threads: 0 for
    every core (the maps are the same on any number). Ctrl-C raises Interrupted whose
    .result holds the lines finished."""
    s = Scene.of(scene, set, caller="force_volume", **keys)
    folder = ffi.new("char[]", c_bytes(output, "output")) if output is not None else ffi.NULL
    prog = Progress(progress, "force volume", "lines")
    job = ffi.new("tt_force_volume_job *")
    job.threads, job.folder, job.hdf5, job.progress = int(threads), folder, bool(hdf5), prog.c
    out = ffi.new("tt_force_volume **")
    col = Collector()
    status, message, interrupted = run(lambda: lib.tt_run_force_volume(s._p, job, out, ffi.NULL), prog, col)
    result = None
    if out[0] != ffi.NULL:
        v = ffi.gc(out[0], lib.tt_force_volume_free)
        xres, yres = lib.tt_force_volume_xres(v), lib.tt_force_volume_yres(v)
        result = ForceVolume(meta={"lines_finished": lib.tt_force_volume_lines_done(v),
                                   "lines_total": lib.tt_force_volume_lines(v),
                                   "drive_periods": lib.tt_force_volume_cycles(v)})
        for ch in range(lib.TT_FV_COUNT):
            name = text(lib.tt_force_volume_channel_name(ch))
            buf = ffi.buffer(lib.tt_force_volume_map(v, ch), xres * yres * 8)
            result[name] = np.frombuffer(buf, dtype=np.float64).reshape(yres, xres).copy()
            result.units[name] = text(lib.tt_force_volume_channel_unit(ch))
        result.x = (np.arange(xres) + 0.5) * lib.tt_force_volume_size_x(v) / xres
        result.y = (np.arange(yres) + 0.5) * lib.tt_force_volume_size_y(v) / yres
    col.emit(stacklevel=2, result=result)
    finish(status, message, interrupted, "force_volume", result, prog)
    return result


def contact(scene=None, *, material=None, model=None, lam=None, xi0=0.3, points=600, amax=3.0,
            set=None, **keys):
    """The contact curve (`tiptap contact`) in Burnham et al.'s normalised units (eq. 3):
    A, Delta, P, stable; the summary (lambda, P0, Delta0, pulloff_load, jumpout_delta,
    ..., with a scene also the physical values) in .meta.

    With a scene: the force law of [material NAME] (material: NAME, default the first),
    model replacing its model. Without: the normalised law of model (default maugis) at
    Maugis parameter lam, with the normalised interatomic distance xi0."""
    out = ffi.new("tt_table **")
    c = ffi.new("tt_contact **")
    if scene is not None:
        if lam is not None:
            raise TypeError("contact: lam draws the normalised curve, which takes no scene")
        s = Scene.of(scene, set, caller="contact", **keys)
        params = ffi.new("tt_contact_params *")
        qi = ffi.new("double *")
        check(lib.tt_run_contact_alloc(s._p, c_bytes(material, "material") if material else ffi.NULL,
                                       c_bytes(model, "model") if model else ffi.NULL, c, params, qi))
        law = ffi.gc(c[0], lib.tt_contact_free)
        check(lib.tt_run_contact_table(law, params, qi[0], points, amax, out))
    else:
        m = ffi.new("tt_contact_model *")
        check_keywords("contact", keys)
        if keys or set:
            raise TypeError("contact: scene keys (set, keywords) need a scene")
        if lib.tt_contact_model_parse(c_bytes(model or "maugis", "model"), m) != 0:
            raise _refused(f"model: '{model}' is not one of maugis, hertz, dmt, jkr")
        if lam is None and m[0] == lib.TT_CONTACT_MAUGIS:
            raise TypeError("contact: give a scene, or lam (the Maugis parameter, 1e-4 to 1e4)")
        lam = 1.0 if lam is None else float(lam)
        if not 1e-4 <= lam <= 1e4:
            raise _refused(f"lam: {lam!r}: expected a number from 1e-4 to 1e4")
        check(lib.tt_contact_alloc_normalised(c, m[0], lam, float(xi0)))
        law = ffi.gc(c[0], lib.tt_contact_free)
        check(lib.tt_run_contact_table(law, ffi.NULL, math.nan, points, amax, out))
    t = table_of(out[0])
    if model or scene is None:
        t.meta["model"] = model or "maugis"
    return t


def accuracy(scene, *, point=None, cycles=0, pixels=8, methods=None, repeats=3, clock="wall",
             set=None, progress=None, **keys):
    """The work-precision study (`tiptap accuracy`): a row per solver setting (reference,
    floor, each ladder loosest first) with its run time and its errors against the
    reference. point: judge a steady point at this rest separation (m) even if the scene
    has [scan]; cycles: per run (0: the default); pixels: of a scan line; methods:
    "dopri5,rk4" (default all); repeats: timing passes; clock: "wall" or "cpu"."""
    s = Scene.of(scene, set, caller="accuracy", **keys)
    p = ffi.new("tt_accuracy_params *")
    lib.tt_accuracy_params_default(p)
    if point is not None:
        p.kind = lib.TT_ACCURACY_POINT
        p.point = float(point)
    p.cycles, p.line_pixels, p.repeats = int(cycles), int(pixels), int(repeats)
    if clock not in ("wall", "cpu"):
        raise _refused(f"clock: '{clock}' is not wall or cpu")
    p.cpu_clock = clock == "cpu"
    ladders = ffi.new("tt_accuracy_ladder[16]")
    if methods:
        n = ffi.new("size_t *")
        check(lib.tt_accuracy_pick(c_bytes(methods, "methods"), ladders, 16, n))
        p.ladders, p.nladders = ladders, n[0]
    return _run_table(lambda out, c: lib.tt_run_accuracy(s._p, p, out, c, ffi.NULL), "accuracy",
                      "settings", progress)
