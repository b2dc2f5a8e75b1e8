"""tiptap from Python: the tapping-mode AFM simulator's library (libtiptap) with scenes,
results as numpy arrays with their units and metadata, progress and Ctrl-C.

    import tiptap
    r = tiptap.scan(["scans/quick.ini", "surfaces/polymer-blend.ini"], scan__pixels=32)
    r["height"], r.units["height"], r.meta["cantilever.free_amplitude"]

docs/python.md has the whole API.
"""

from ._errors import (CaptureError, Interrupted, NumericalError, SceneError, TiptapError,
                      TiptapIOError, TiptapMemoryError)
from ._lib import lib as _clib, text as _text
from .scan import ScanResult, channel_table, scan
from .scene import Key, Scene, keys
from .sweep import sweep
from .tables import Table, accuracy, approach, contact, trace

__version__ = _text(_clib.tt_version())
version = __version__

__all__ = [
    "CaptureError", "Interrupted", "Key", "NumericalError", "ScanResult", "Scene",
    "SceneError", "Table", "TiptapError", "TiptapIOError", "TiptapMemoryError", "accuracy",
    "approach", "channel_table", "contact", "keys", "scan", "sweep", "trace", "version",
]
