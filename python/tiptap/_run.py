"""Long library calls: progress, Ctrl-C and other Python threads.

A run (a scan, an approach) is one C call that takes seconds to hours. Called from the
main thread it runs in a worker thread while the main thread waits in short joins, so
that Python's own SIGINT handler runs: Ctrl-C there requests the library's cooperative
cancellation (tiptap/util/cancel.h), the run stops within a second keeping what it
finished, and the call raises Interrupted, a KeyboardInterrupt. The GIL is released
during the C call (cffi), so other Python threads keep going. Called from another
thread, the run simply runs there.

Cancellation is the library's, for the whole process: Ctrl-C stops every run under way.
"""

import contextlib
import threading

from ._errors import Interrupted, error
from ._lib import ffi, lib, text


class Progress:
    """The progress argument of a run, as the library's callback.

    progress=None: a tqdm bar when tqdm can be imported (tqdm.auto: a widget in a
    notebook, text in a terminal), else nothing; False: nothing;
    a callable: called as progress(done, total) after each unit of work (a line, a
    point, a combination), from the thread that finished it. An exception raised by the
    callable stops the run (as Ctrl-C does) and is raised again by the run.
    """

    def __init__(self, progress, desc, unit):
        self.error = None
        self.bar = None
        self.user = None
        self.desc, self.unit = desc, unit
        if progress is None:
            try:
                from tqdm import auto as tqdm
            except ImportError:
                tqdm = None
            if tqdm is not None:
                self.user = self._tqdm
                self._tqdm_mod = tqdm
        elif progress is not False:
            if not callable(progress):
                raise TypeError("progress: None, False or a callable progress(done, total)")
            self.user = progress
        self._c = ffi.callback("void(void *, long, long)", self._call) if self.user else ffi.NULL

    @property
    def c(self):
        """The C callback (NULL when no progress is wanted)."""
        return self._c

    def _tqdm(self, done, total):
        if self.bar is None:
            self.bar = self._tqdm_mod.tqdm(total=total, desc=self.desc, unit=self.unit)
        self.bar.update(done - self.bar.n)

    def _call(self, user, done, total):
        if self.error is not None:
            return
        try:
            self.user(int(done), int(total))
        except BaseException as e:  # noqa: B902: stop the run, raise it afterwards
            self.error = e
            lib.tt_cancel_request()

    def show(self, done, total):
        """For runs driven from Python (row by row)."""
        if self._c != ffi.NULL:
            self._call(ffi.NULL, done, total)

    def close(self):
        if self.bar is not None:
            self.bar.close()


def run(call, progress=None, collector=None):
    """Run call() -> status (a library call) so that Ctrl-C stops it; the library's
    warnings on the thread that makes it go to collector (tiptap._warnings.Collector).

    Returns (status, message, interrupted): message is the library's line for a failed
    status, read on the thread that made the call; interrupted says that Ctrl-C or the
    progress callback stopped it (the status is then TT_EINTR, or TT_OK when the run
    finished first); finish() raises what that calls for. Exceptions of the call itself
    propagate.
    """
    box = {}
    finished = threading.Event()

    def work():
        try:
            with collector.installed() if collector is not None else contextlib.nullcontext():
                status = call()
            box["status"] = status
            box["message"] = text(lib.tt_error_message()) if status else ""
        except BaseException as e:  # noqa: B902: handed to the waiting thread
            box["exception"] = e
        finally:
            finished.set()

    interrupted = False
    if threading.current_thread() is not threading.main_thread():
        work()
    else:
        # an Event, not Thread.join: a join interrupted by KeyboardInterrupt can leave
        # the thread looking finished while it runs on
        worker = threading.Thread(target=work, name="tiptap-run", daemon=True)
        worker.start()
        while not finished.is_set():
            try:
                finished.wait(0.05)
            except KeyboardInterrupt:
                interrupted = True
                lib.tt_cancel_request()
        worker.join()
    if progress is not None:
        progress.close()
        if progress.error is not None:
            interrupted = True
    if interrupted or box.get("status") == lib.TT_EINTR:
        lib.tt_cancel_reset()
    if "exception" in box:
        raise box["exception"]
    return box["status"], box["message"], interrupted or box["status"] == lib.TT_EINTR


def finish(status, message, interrupted, what, result=None, progress=None):
    """Raise what a run's end calls for, once its partial results are kept: the progress
    callback's exception, Interrupted (with the partial result) or the library's error;
    nothing when it succeeded."""
    if progress is not None and progress.error is not None:
        raise progress.error
    if interrupted:
        raise Interrupted(f"{what}: interrupted" + (f" ({message})" if message else ""), result)
    if status != 0:
        raise error(status, message)
