"""Library failures as Python exceptions, each carrying the library's one-line message."""

from ._lib import lib, text


class TiptapError(Exception):
    """A library call failed. str(e) is the library's one line ("scene.ini: [cantilever]
    spring_constant: ..."); e.status is its status code (tiptap/util/error.h) and e.code
    its name ("TT_EINVAL")."""

    code = "TT_ERROR"

    def __init__(self, status, message):
        super().__init__(message)
        self.status = status
        self.message = message


class SceneError(TiptapError, ValueError):
    """Bad input: a key, a value, a unit, a file's content (TT_EINVAL)."""

    code = "TT_EINVAL"


class TiptapMemoryError(TiptapError, MemoryError):
    """An allocation failed (TT_ENOMEM); the message names what was being allocated."""

    code = "TT_ENOMEM"


class TiptapIOError(TiptapError, OSError):
    """A file could not be read or written (TT_EIO)."""

    code = "TT_EIO"


class NumericalError(TiptapError, ArithmeticError):
    """A numerical failure: no convergence, a NaN, a step too large (TT_ENUM)."""

    code = "TT_ENUM"


class CaptureError(TiptapError):
    """The run ended in a state the scene asked to treat as an error (TT_ECAPTURE)."""

    code = "TT_ECAPTURE"


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (or a progress callback that raised) stopped a run. A KeyboardInterrupt, so
    that `except KeyboardInterrupt` catches it and, uncaught, it ends a script with its
    traceback (exit status 1: Python gives the status of a death by SIGINT to
    KeyboardInterrupt itself only); e.result holds what the run had finished (a scan's
    finished lines, an approach's rows), or None."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


# named as the package exports them (a traceback reads tiptap.SceneError)
for _c in (TiptapError, SceneError, TiptapMemoryError, TiptapIOError, NumericalError,
           CaptureError, Interrupted):
    _c.__module__ = "tiptap"

_CLASSES = {1: SceneError, 2: TiptapMemoryError, 3: TiptapIOError, 4: NumericalError,
            6: CaptureError}


def error(status, message=None):
    """The exception for a failed call's status, with this thread's message."""
    if message is None:
        message = text(lib.tt_error_message())
    if not message:
        message = text(lib.tt_strerror(status))
    return _CLASSES.get(status, TiptapError)(status, message)


def check(status):
    """Raise the exception of a failed call made on this thread; TT_OK passes."""
    if status != 0:
        raise error(status)
    return status
