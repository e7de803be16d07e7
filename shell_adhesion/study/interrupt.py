"""Ctrl-C during a run, taken at a safe point and ended within a bound.

A KeyboardInterrupt raised at an arbitrary bytecode can land inside dask's client (holding
one of its locks) or inside a catalogue write, and the shutdown that follows can then
wait forever.  While the dask part of a run is computing, `deferred()` turns the first
SIGINT into a request that the computing loop takes at its next poll (within about a
second); a second SIGINT raises at once.  `hard_exit_after` (for the command line only,
never for a notebook) bounds the whole shutdown: if the process has not ended some
seconds after the first SIGINT, it prints one line and exits with 130.
"""
from contextlib import contextmanager
import os
import signal
import sys
import threading

EXIT_INTERRUPTED = 130

_requested = threading.Event()
_deferring = False
_hard_exit = None          # (seconds, line) while the command line runs a study
_timer = None              # the armed hard exit


def requested() -> bool:
    """True once Ctrl-C was pressed inside `deferred()`."""
    return _requested.is_set()


def check():
    """Raise KeyboardInterrupt here (a safe point) if Ctrl-C was pressed."""
    if _requested.is_set():
        raise KeyboardInterrupt


@contextmanager
def hard_exit_after(seconds: float, line: str):
    """Within this block, after the first SIGINT, end the process (exit 130, `line` on
    stderr) if it is still running `seconds` later.  For the command line: a notebook
    kernel must not exit.  Leaving the block normally disarms it; leaving it by Ctrl-C
    keeps an armed bound, which then also bounds the interpreter's exit."""
    global _hard_exit, _timer
    _hard_exit = (float(seconds), line)
    try:
        yield
    except KeyboardInterrupt:       # the process is ending: the bound stays armed
        raise
    else:
        if _timer is not None:
            _timer.cancel()
            _timer = None
    finally:
        _hard_exit = None


def _arm_hard_exit():
    global _timer
    if _hard_exit is None or _timer is not None:
        return
    seconds, line = _hard_exit

    def stop():
        try:
            print(line, file=sys.stderr, flush=True)
        finally:
            os._exit(EXIT_INTERRUPTED)

    _timer = threading.Timer(seconds, stop)
    _timer.daemon = True
    _timer.start()


def _handle(signum, frame):
    first = not _requested.is_set()
    _requested.set()
    if first:
        _arm_hard_exit()
    if not (first and _deferring):
        raise KeyboardInterrupt


@contextmanager
def deferred():
    """Within this block (main thread only), the first SIGINT is a request polled by
    `check()`; outside it, and in other threads, Ctrl-C behaves as usual."""
    global _deferring
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _requested.clear()
    previous = signal.signal(signal.SIGINT, _handle)
    _deferring = True
    try:
        yield
    finally:
        _deferring = False
        signal.signal(signal.SIGINT, previous)


@contextmanager
def watched():
    """Within this block (main thread only), SIGINT raises KeyboardInterrupt as usual but
    also arms the hard exit; `deferred()` may be nested inside."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _requested.clear()
    previous = signal.signal(signal.SIGINT, _handle)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
