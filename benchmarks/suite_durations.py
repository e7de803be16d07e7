"""The default test tier's durations, written to tests/durations.md: the wall time of
`python -m pytest -q` (the README's test command), the machine (cores, load average before
and after: the figures are only comparable at the same load), the time per test file and
the slowest tests (setup, call and teardown each, as `pytest --durations=0` reports them).

Run:  python benchmarks/suite_durations.py                 (runs the default tier in two
                                                          worker processes, pyproject's
                                                          addopts: about 10 minutes on 2
                                                          cores; per-file times add both)
      python benchmarks/suite_durations.py --from run.txt  (the page from the output of
                                                          `python -m pytest -q --durations=0`)
Extra pytest arguments follow `--`, e.g. `-- -n 0` for one process.
"""
import argparse
from collections import defaultdict
import os
from pathlib import Path
import re
import subprocess
import sys
import time

REPO = Path(__file__).resolve().parents[1]
LINE = re.compile(r"^\s*([\d.]+)s (setup|call|teardown)\s+(\S+?)(::\S.*)?$")
SUMMARY = re.compile(r"^(\d+ (?:passed|failed).*?) in ([\d.]+)s")
SLOWEST = 40


def parse(text):
    """([(seconds, phase, file, test)], summary line, pytest's wall seconds)."""
    rows, summary, wall = [], None, None
    for line in text.splitlines():
        m = LINE.match(line)
        if m:
            rows.append((float(m[1]), m[2], m[3], (m[4] or "")[2:]))
        m = SUMMARY.match(line.strip("= "))
        if m:
            summary, wall = m[1], float(m[2])
    return rows, summary, wall


def page(rows, summary, wall, machine, note=""):
    per_file = defaultdict(float)
    for s, _, f, _ in rows:
        per_file[f] += s
    out = ["# Test durations (default tier)", "",
           "Written by `python benchmarks/suite_durations.py` (do not edit by hand).  "
           "The machine is shared, so compare runs at the same load.", "",
           f"- {summary}; pytest's wall time {wall:.0f} s",
           f"- {machine}", *([f"- {note}"] if note else []), "",
           "## Per file (setup + call + teardown, s)", "",
           "| file | s |", "| --- | ---: |"]
    out += [f"| {f} | {s:.1f} |" for f, s in sorted(per_file.items(), key=lambda x: -x[1])
            if s >= 0.05]
    out += ["", f"## The {SLOWEST} slowest phases", "", "| s | phase | test |",
            "| ---: | --- | --- |"]
    out += [f"| {s:.1f} | {p} | {f}::{t} |" for s, p, f, t in sorted(rows, reverse=True)[:SLOWEST]]
    return "\n".join(out) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--from", dest="source", type=Path,
                    help="pytest output to read instead of running the tests")
    ap.add_argument("--out", type=Path, default=REPO / "tests" / "durations.md")
    ap.add_argument("--note", default="", help="a line on how the run was made")
    ap.add_argument("pytest_args", nargs="*", help="after --: more pytest arguments")
    ns = ap.parse_args(argv)
    if ns.source is not None:
        text = ns.source.read_text()
        machine = f"{os.cpu_count()} cores; read from {ns.source.name}"
    else:
        load0 = os.getloadavg()[0]
        t0 = time.perf_counter()
        run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                              "--durations=0", "-rfE", *ns.pytest_args], cwd=REPO,
                             capture_output=True, text=True)
        text = run.stdout
        machine = (f"{os.cpu_count()} cores; load average {load0:.1f} before, "
                   f"{os.getloadavg()[0]:.1f} after; the command's wall time "
                   f"{time.perf_counter() - t0:.0f} s; pytest {' '.join(ns.pytest_args)}")
    rows, summary, wall = parse(text)
    if summary is None or not rows:
        print("suite_durations: no pytest summary and durations in the output", file=sys.stderr)
        return 2
    ns.out.write_text(page(rows, summary, wall, machine, ns.note))
    print(f"{summary} in {wall:.0f} s -> {ns.out}")
    for line in text.splitlines():        # pytest's short summary (-rfE): what failed
        if line.startswith(("FAILED ", "ERROR ")):
            print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
