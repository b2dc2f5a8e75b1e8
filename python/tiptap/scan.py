"""Closed-loop imaging: tiptap.scan(), the images of `tiptap scan` as numpy arrays."""

import numpy as np

from ._errors import check
from ._lib import ffi, lib, text
from ._run import Progress, finish, run
from ._warnings import Collector
from .scene import Scene, c_bytes


def channel_table():
    """Every channel the library can record, by index: a list of (name, unit, harmonic)
    (harmonic: the deflection's harmonic it demodulates, 0 for none)."""
    return [
        (text(lib.tt_scan_channel_name(i)), text(lib.tt_scan_channel_unit(i)),
         lib.tt_scan_channel_harmonic(i))
        for i in range(lib.tt_scan_channel_count())
    ]


def scan_meta(scan_p, scene):
    """The run's metadata as the library lists it for the program's files (the version,
    the lines finished and every scene key): a tt_meta the caller frees (tt_meta_free)."""
    m = ffi.new("tt_meta *")
    first = {"tiptap_version": text(lib.tt_version()),
             "lines_finished": str(lib.tt_scan_lines_done(scan_p)),
             "lines_total": str(lib.tt_scan_lines(scan_p))}
    keys = [ffi.new("char[]", k.encode()) for k in first]
    vals = [ffi.new("char[]", v.encode()) for v in first.values()]
    check(lib.tt_meta_scene(m, scene._p, keys, vals, len(first)))
    return m


class ScanResult:
    """A scan's images and everything about the run.

    r["height"] and r.trace["height"]: the trace image of a channel, r["height",
    "retrace"] and r.retrace["height"]: the retrace (numpy float64 arrays of shape
    (lines along y, pixels along x), row 0 at y = 0, in the sample's orientation
    whatever the fast axis; NaN where a line did not finish). r.units["height"]: the
    channel's SI unit ("m", "deg", "N", "J"). r.x, r.y: the pixel centres (m).
    r.meta: the run's parameters, as the GSF and HDF5 files carry them (the version,
    lines finished and every key of the effective scene, "section.key": "value unit").
    r.run: figures of the run (instrument time, cycles, the energy balance, ...).
    r.error: the error estimate's figures when it was asked for. r.scene: the effective
    scene's text. r.warnings: the library's warnings about the run, a list of (category,
    message) (also raised with warnings.warn; tiptap.TiptapWarning).
    """

    def __init__(self, scan_p, scene):
        self.channels = []
        self.units = {}
        self.harmonics = {}
        self.trace = {}
        self.retrace = {}
        xres, yres = lib.tt_scan_xres(scan_p), lib.tt_scan_yres(scan_p)
        for i, (name, unit, harmonic) in enumerate(channel_table()):
            for r, images in ((0, self.trace), (1, self.retrace)):
                p = lib.tt_scan_image(scan_p, i, r)
                if p == ffi.NULL:
                    continue
                buf = ffi.buffer(p, xres * yres * ffi.sizeof("double"))
                images[name] = np.frombuffer(buf, dtype=np.float64).reshape(yres, xres).copy()
                if name not in self.units:
                    self.channels.append(name)
                    self.units[name] = unit
                    self.harmonics[name] = harmonic
        self.size = (lib.tt_scan_size_x(scan_p), lib.tt_scan_size_y(scan_p))
        self.x = (np.arange(xres) + 0.5) * self.size[0] / xres
        self.y = (np.arange(yres) + 0.5) * self.size[1] / yres
        done, total = lib.tt_scan_lines_done(scan_p), lib.tt_scan_lines(scan_p)
        m = scan_meta(scan_p, scene)
        try:
            self.meta = {text(m.keys[i]): text(m.values[i]) for i in range(m.n)}
        finally:
            lib.tt_meta_free(m)
        cycles = lib.tt_scan_cycles(scan_p)
        self.run = {
            "lines_finished": done,
            "lines_total": total,
            "fast_axis": "y" if lib.tt_scan_fast_y(scan_p) else "x",
            "profile_line": lib.tt_scan_profile_line(scan_p),
            "instrument_time_s": lib.tt_scan_instrument_time(scan_p),
            "cycles": cycles,
            "cycles_integrated": lib.tt_scan_cycles_integrated(scan_p),
            "energy_balance": lib.tt_scan_error_estimate(scan_p),
            "z_clamped": bool(lib.tt_scan_clamped(scan_p)),
            "materials": [text(lib.tt_scan_material_name(scan_p, i))
                          for i in range(lib.tt_scan_materials(scan_p))],
        }
        self.error = None
        self.warnings = []
        self.scene = scene.text()

    def __getitem__(self, key):
        if isinstance(key, tuple):
            name, direction = key
            if direction not in ("trace", "retrace"):
                raise KeyError(f"direction {direction!r}: trace or retrace")
            return (self.trace if direction == "trace" else self.retrace)[name]
        return self.trace[key]

    def __contains__(self, name):
        return name in self.trace

    def __repr__(self):
        ny, nx = next(iter(self.trace.values())).shape if self.trace else (0, 0)
        return (f"<tiptap.ScanResult {nx} x {ny} pixels, {self.run['lines_finished']}/"
                f"{self.run['lines_total']} lines, channels {', '.join(self.channels)}>")


def scan(scene, *, set=None, threads=0, progress=None, error_estimate=False, hdf5=None,
         output=None, **keys):
    """Closed-loop tapping image of a scene, as `tiptap scan` makes it.

    scene: a Scene, a scene file or a list of them (read in order); set / keywords:
    keys overridden for this run only (Scene.set). The run works on its own copy of the
    scene, taken now. threads: lines in parallel (0: all cores; the images do not depend
    on it). progress: None (a tqdm bar when tqdm is installed), False, or
    progress(done, total) called after each line. error_estimate: also run the companion
    line at a tighter tolerance (r.error), as `tiptap scan` does. hdf5: a file name to
    write the scan into (docs/hdf5.md), also the finished lines of an interrupted scan.
    output: a folder (made if missing) to write the files `tiptap scan -o` writes of the
    images: scan.gwy (every channel, trace and retrace, titled "height (trace)", ...),
    CHANNEL_trace.gsf and CHANNEL_retrace.gsf, their PNG previews and profile.csv, with
    the run's parameters as metadata, byte for byte as the program's.

    Returns a ScanResult. Bad input raises SceneError, and a scan needing more memory
    than the process can allocate TiptapMemoryError (the program's estimate), before
    anything runs; Ctrl-C raises Interrupted (a KeyboardInterrupt) whose .result holds
    the finished lines. The program's warnings (the estimate of a long run, a material
    not used, a contact past the force laws' validity, the loop oscillating, the z piezo
    at its range's end, the error estimate above the tolerance) are raised with
    warnings.warn as TiptapWarning subclasses after the run and kept in r.warnings.
    """
    scene = Scene.of(scene, set, caller="scan", **keys)
    names = {}  # the C strings the job points to, alive for the run
    if hdf5 is not None:
        names["hdf5"] = ffi.new("char[]", c_bytes(hdf5, "hdf5"))
    if output is not None:
        names["output"] = ffi.new("char[]", c_bytes(output, "output"))
    col = Collector()
    sp = ffi.new("tt_scan_scope **")
    check(lib.tt_scan_scope_alloc(sp))
    scope = ffi.gc(sp[0], lib.tt_scan_scope_free)
    prog = Progress(progress, "scan", "lines")
    # the library's scan sequence (tt_run_scan), the program's: the warnings, the
    # profile line's full-rate record, the outputs asked for, the estimate
    job = ffi.new("tt_run_scan_job *")
    job.threads = int(threads)
    job.progress = prog.c
    job.scope = scope
    job.folder = names.get("output", ffi.NULL)
    job.hdf5_file = names.get("hdf5", ffi.NULL)
    job.estimate = bool(error_estimate)
    r = ffi.new("tt_run_scan_result *")
    status, message, interrupted = run(lambda: lib.tt_run_scan(scene._p, job, r), prog, col)
    if r.scan == ffi.NULL:  # refused before the scan was made
        col.emit(stacklevel=2)
        finish(status, message, interrupted, "scan", None, prog)
    s = ffi.gc(r.scan, lib.tt_scan_free)
    lib.tt_scan_scope_attach(s, 0, ffi.NULL)
    result = ScanResult(s, scene) if lib.tt_scan_lines_done(s) > 0 else None
    if result is not None and r.estimate_status == 0:
        e = r.est
        result.error = {
            "height_max_m": e.height_max, "height_rms_m": e.height_rms,
            "amplitude_max_rel": e.amplitude_max, "amplitude_rms_rel": e.amplitude_rms,
            "phase_max_deg": e.phase_max, "phase_rms_deg": e.phase_rms,
            "line": e.line, "tolerance": e.tolerance,
            # where it checked (the image's hardest stretches) and what it cost
            "pixels": e.pixels, "pixels_line": e.pixels_line, "first_pixel": e.first,
            "step_m": e.step, "cycles": e.cycles, "cpu_s": e.seconds, "stretches": e.stretches,
            # its work (integrator steps and one a cycle) against the scan's: at most a
            # fifth, or the whole hardest line ran over the share (a scan too short for a
            # stretch's settling at the tight setting; with noise, for one whole line)
            "work": e.work, "scan_work": e.scan_work, "lines_whole": e.lines,
            "error_signal_m": e.signal,
            "over_share": bool(e.over), "run_cpu_s": r.cpu_seconds,
        }
    col.emit(stacklevel=2, result=result)
    finish(status, message, interrupted, "scan", result, prog)
    return result
