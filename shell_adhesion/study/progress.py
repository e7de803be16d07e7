"""Progress of a study run: one line per stage with done/total and elapsed time; `bar`, the
one-line bar of a case, a design and a map search (tqdm on a terminal or in a notebook; in
a log file the same lines as a stage's, LogBar).

The totals are fixed when the plan is made; a count never runs past its total.  The
relaxation stage also counts paths: done/total, the total an estimate (~: study.cost
before a set's loading, and a set fitted further to its request adds paths) until every
set is done, and an ETA once a few have finished.  On a
terminal the lines are redrawn in place; in a notebook the running stages share one line
redrawn in place; elsewhere (a log file) a stage's line is printed when it starts, at most
every `every_s` seconds while it runs, and when it is complete.
"""
from contextlib import contextmanager
import sys
import threading
import time


def _clock(seconds: float) -> str:
    m, s = divmod(int(seconds), 60)
    return f"{m}:{s:02d}" if m < 60 else f"{m // 60}:{m % 60:02d}:{s:02d}"


ETA_AFTER = 20      # tasks finished (after the first) before an ETA is shown


def path_eta(t0: float, finished: int, remaining: int, now: float = None) -> str:
    """', ETA m:ss' from the pace of the tasks finished since t0 (time.perf_counter()),
    once ETA_AFTER have finished; '' before, and when nothing remains."""
    if t0 is None or finished < ETA_AFTER or remaining <= 0:
        return ""
    now = time.perf_counter() if now is None else now
    return f", ETA {_clock((now - t0) / finished * remaining)}"


class Stage:
    """One line: `name: done/total unit, note, elapsed`."""

    def __init__(self, name: str, total: int, unit: str):
        self.name, self.total, self.unit = name, int(total), unit
        self.done = 0
        self.note = ""
        self.t0 = None          # first update
        self.t1 = None          # completion

    def line(self, now: float) -> str:
        if self.t0 is None:
            clock = "waiting"
        else:
            clock = _clock((self.t1 or now) - self.t0)
        note = f", {self.note}" if self.note else ""
        return f"{self.name:<17}{self.done:>5}/{self.total:<5} {self.unit}{note}  {clock}"


class Progress:
    """Stage lines on `stream` (stderr by default); `enabled=False` prints nothing."""

    def __init__(self, stages, enabled: bool = True, stream=None, every_s: float = 10.0):
        self.stages = {name: Stage(name, total, unit) for name, total, unit in stages}
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = enabled
        self.tty = enabled and hasattr(self.stream, "isatty") and self.stream.isatty()
        # a notebook redraws the last line only (a carriage return): the running stages
        # on one line, each stage's line of its own once complete
        self.notebook = enabled and not self.tty and shown(self.stream)
        self.every_s = every_s
        self._drawn = False
        self._width = 0         # of the notebook's running line
        self._printed = {}      # stage -> time of its last printed line (no terminal)

    def start(self, name: str):
        self.update(name, 0)

    def update(self, name: str, done: int = None, note: str = None, advance: int = 0):
        """Set (or advance) a stage's count and note, and show it."""
        st = self.stages[name]
        now = time.perf_counter()
        if st.t0 is None:
            st.t0 = now
        if done is not None:
            st.done = done
        st.done = min(st.done + advance, st.total)
        if note is not None:
            st.note = note
        if st.done >= st.total and st.t1 is None:
            st.t1 = now
        self._show(st, now)

    def _show(self, st: Stage, now: float):
        if not self.enabled:
            return
        if self.tty:
            if self._drawn:
                self.stream.write(f"\x1b[{len(self.stages)}F")
            for s in self.stages.values():
                self.stream.write("\x1b[2K" + s.line(now) + "\n")
            self._drawn = True
        elif self.notebook:
            if st.t1 is not None and self._printed.get(st.name) != "complete":
                self._redraw(st.line(now) + "\n")
                self._printed[st.name] = "complete"
            running = [s.line(now) for s in self.stages.values()
                       if s.t0 is not None and s.t1 is None]
            self._redraw(" | ".join(" ".join(r.split()) for r in running))
        else:
            last = self._printed.get(st.name)
            if last == "complete":
                return
            complete = st.t1 is not None
            if last is None or complete or now - last >= self.every_s:
                self.stream.write(st.line(now) + "\n")
                self._printed[st.name] = "complete" if complete else now
        self.stream.flush()

    def _redraw(self, text: str):
        """Overwrite the notebook's last line (a carriage return, blanks over what was
        longer); a text ending in a newline stays."""
        body = text.rstrip("\n")
        self.stream.write("\r" + body.ljust(self._width) + text[len(body):])
        self._width = 0 if text.endswith("\n") else len(body)

    def say(self, text: str):
        """A line of its own (the dashboard link, a warning)."""
        if self.enabled and self.notebook:
            self._redraw(text + "\n")
            self.stream.flush()
        elif self.enabled:
            if self.tty and self._drawn:
                self.stream.write(f"\x1b[{len(self.stages)}F\x1b[0J")
                self._drawn = False
            self.stream.write(text + "\n")
            if self.tty:
                self._show(next(iter(self.stages.values())), time.perf_counter())
            self.stream.flush()


def shown(stream=None) -> bool:
    """Whether a progress bar on `stream` (stderr by default) is seen live: a terminal, or a
    Jupyter kernel (whose cell output redraws a carriage-returned line)."""
    stream = sys.stderr if stream is None else stream
    if hasattr(stream, "isatty") and stream.isatty():
        return True
    shell = sys.modules.get("IPython")
    ip = shell.get_ipython() if shell is not None and hasattr(shell, "get_ipython") else None
    return ip is not None and "IPKernelApp" in getattr(ip, "config", {})


class LogBar:
    """The bar of a log file (stderr not seen live), as `Progress` prints a stage there: a
    line `desc: done/total unit, ETA m:ss  elapsed` when a stage starts, at most every
    `every_s` seconds while it runs, and once when it is complete (or left for the next
    stage).  It answers the part of tqdm's interface that `bar`'s users call."""

    def __init__(self, total, desc: str, unit: str, stream=None, every_s: float = 10.0):
        self.stream = sys.stderr if stream is None else stream
        self.every_s = every_s
        self.desc, self.unit = desc, unit
        self._begin(total)

    def _begin(self, total):
        self.total, self.n = total, 0
        self.t0 = time.perf_counter()
        self._last = None           # time of the last line; "complete" once it is printed
        self._shown_n = None        # the count that line showed

    def line(self, now: float) -> str:
        total = "?" if self.total is None else f"{self.total:g}"
        eta = ""
        if self.total is not None and 0 < self.n < self.total:
            eta = f", ETA {_clock((now - self.t0) / self.n * (self.total - self.n))}"
        return f"{self.desc}: {self.n:g}/{total} {self.unit}{eta}  {_clock(now - self.t0)}"

    def _show(self, force: bool = False):
        if self._last == "complete" or self.total is None:
            return
        now = time.perf_counter()
        complete = self.total is not None and self.n >= self.total
        if force or complete or self._last is None or now - self._last >= self.every_s:
            self.stream.write(self.line(now) + "\n")
            self.stream.flush()
            self._last = "complete" if complete else now
            self._shown_n = self.n

    def _leave(self):
        """The stage ends (reset, close): its last count, if not shown yet."""
        if self._last not in (None, "complete") and self._shown_n != self.n:
            self._show(force=True)

    def update(self, k=1):
        self.n += k
        self._show()

    def reset(self, total=None):
        self._leave()
        self._begin(total)
        self._show()

    def set_description(self, desc: str):
        self.desc = desc

    def close(self):
        self._leave()

    def __enter__(self):
        self._show()
        return self

    def __exit__(self, *exc):
        self.close()


LOG_EVERY_S = 10.0      # a bar's line in a log file at most this often (as `run`'s stages)
_logged = threading.local()


@contextmanager
def logged():
    """Bars made inside the block print a LogBar's lines where they are not seen live (a
    log file): a long command such as `design` shows its stages there as `run` does.
    Outside it they print nothing there (`case`: a refusal found while solving stays the
    one line on stderr)."""
    before = getattr(_logged, "on", False)
    _logged.on = True
    try:
        yield
    finally:
        _logged.on = before


def bar(total, desc: str, unit: str, enabled: bool = True, stream=None):
    """A bar on `stream` (stderr by default) when `enabled`: tqdm's (done/total, rate,
    ETA) when `shown()` (a terminal, a notebook); else, inside `logged()`, a LogBar's
    lines (a log file), and nothing outside it.  Close it (or use it as a context
    manager)."""
    stream = sys.stderr if stream is None else stream
    live = enabled and shown(stream)
    if enabled and not live and getattr(_logged, "on", False):
        return LogBar(total, desc, unit, stream, LOG_EVERY_S)
    from tqdm import tqdm
    return tqdm(total=total, desc=desc, unit=unit, file=stream, leave=False,
                disable=not live)
