"""Progress of a study run: one line per stage with done/total and elapsed time; `bar`, the
one-line bar of a case and a design (a terminal or a notebook).

The totals are fixed when the plan is made; a count never runs past its total.  The
relaxation stage also counts paths: done/total, the total an estimate (~: study.cost
before a set's loading, and a set fitted further to its request adds paths) until every
set is done, and an ETA once a few have finished.  On a
terminal the lines are redrawn in place; elsewhere (a log file) a stage's line is printed
when it starts, at most every `every_s` seconds while it runs, and when it is complete.
"""
import sys
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
        self.every_s = every_s
        self._drawn = False
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
        else:
            last = self._printed.get(st.name)
            if last == "complete":
                return
            complete = st.t1 is not None
            if last is None or complete or now - last >= self.every_s:
                self.stream.write(st.line(now) + "\n")
                self._printed[st.name] = "complete" if complete else now
        self.stream.flush()

    def say(self, text: str):
        """A line of its own (the dashboard link, a warning)."""
        if self.enabled:
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


def bar(total, desc: str, unit: str, enabled: bool = True):
    """A tqdm bar on stderr (done/total, rate, ETA) when `enabled` and `shown()`; a silent
    one otherwise.  Close it (or use it as a context manager)."""
    from tqdm import tqdm
    return tqdm(total=total, desc=desc, unit=unit, file=sys.stderr, leave=False,
                disable=not (enabled and shown()))
