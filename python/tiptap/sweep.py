"""Sweeps over scene keys (`tiptap sweep`, docs/sweeps.md) as one table."""

from ._errors import SceneError, check
from ._lib import ffi, lib
from ._run import Progress, finish
from ._run import run as run_call
from ._warnings import Collector
from .scene import Scene, c_bytes, format_value
from .tables import table_of


def _spec(key, values):
    """A --vary specification from a key and its values: a text ("10nm:30nm:5",
    "log:1nm:100nm:3", "10 nm,20 nm") or a list of values (numbers in the key's SI unit,
    as Scene.set reads them)."""
    if isinstance(values, str):
        return f"{key}={values}"
    texts = [format_value(key, v) for v in values]
    for t in texts:
        if "," in t:
            raise SceneError(lib.TT_EINVAL, f"{key}: a value with a comma cannot be varied: {t!r}")
    return f"{key}=" + ",".join(texts)


def sweep(scene, vary, *, run="steady", threads=0, set=None, progress=None, hdf5=None, **keys):
    """Every combination of the varied keys, as `tiptap sweep` runs them, in one Table.

    vary: {key: values} (values: a range text "10nm:30nm:5", a log range
    "log:1nm:100nm:3", a list text "10 nm,20 nm", or a Python list), or a list of
    "KEY=VALUES" texts; the first key varies slowest. run: "steady" (the steady point at
    [approach] from), "setpoint" (the steady point whose amplitude is the [feedback]
    setpoint), "approach" (the [approach] curve) or "scan" (a summary row per material
    of each combination's scan: height and phase mean, spread and contrast). threads:
    combinations in parallel (scans: lines in parallel), 0: all cores. hdf5: also write
    the table as an HDF5 file over the grid (docs/hdf5.md); when interrupted, with the
    combinations finished (the others NaN).

    The table's columns: combination, each varied key (SI, or text), then the run's
    (z, amplitude, phase, ... in SI; docs/python.md). Every combination is checked
    before the first runs; Ctrl-C raises Interrupted with the combinations finished.
    Warnings (a setpoint not reached) are raised with warnings.warn and kept in
    table.warnings.
    """
    s = Scene.of(scene, set, caller="sweep", **keys)
    if isinstance(vary, dict):
        specs = [_spec(k, v) for k, v in vary.items()]
    else:
        specs = list(vary)
    kind = ffi.new("tt_sweep_kind *")
    if lib.tt_sweep_kind_parse(c_bytes(run, "run"), kind) != 0:
        raise SceneError(lib.TT_EINVAL, f"run: '{run}' is not steady, setpoint, approach or scan")
    texts = [ffi.new("char[]", c_bytes(x, "vary")) for x in specs]
    path = c_bytes(hdf5, "hdf5") if hdf5 is not None else None
    check(lib.tt_sweep_check_size(texts, len(texts)))
    g = ffi.new("tt_sweep **")
    check(lib.tt_sweep_alloc(g, s._p))
    grid = ffi.gc(g[0], lib.tt_sweep_free)
    for x in texts:
        check(lib.tt_sweep_vary(grid, x))
    if path is not None:
        from .hdf5 import check_output

        check_output(path, s)
    out = ffi.new("tt_table **")
    prog = Progress(progress, "sweep", "combinations")
    col = Collector()
    status, message, interrupted = run_call(
        lambda: lib.tt_run_sweep(grid, kind[0], int(threads), out, prog.c, ffi.NULL), prog, col)
    p = out[0]
    try:
        # the combinations finished, also of an interrupted sweep (as a scan keeps its lines)
        if p != ffi.NULL and path is not None and (status == 0 or interrupted):
            check(lib.tt_run_sweep_hdf5(path, grid, kind[0], s._p, p))
    finally:
        result = table_of(p)
    if result is not None:
        result.meta.update({"run": run, "combinations": int(lib.tt_sweep_count(grid)),
                            "varied": [x.split("=", 1)[0] for x in specs]})
    col.emit(stacklevel=2, result=result)
    finish(status, message, interrupted, "sweep", result, prog)
    return result

