"""A command line without traps: every bad input gives exit 2, exactly one line on stderr,
no traceback, and creates nothing (run in a fresh folder, compared before and after).
The cases run one after another in one fresh interpreter, each in its own folder, through
the command's entry point (`python -m shell_adhesion` is `sys.exit(cli.main())`, held by a
test of its own): one start-up and import instead of one per case."""
import json
from pathlib import Path
import subprocess
import sys

import pytest

from conftest import ENV

CASE = ["case", "--R", "20", "--t", "3", "--h", "20", "--C10", "0.3"]
STUDY = """\
name: tiny
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
mesh: coarse
delta_max_over_R: 0.05
"""


def with_flag(flag, value):
    args = list(CASE)
    args[args.index(flag) + 1] = value
    return args


def corrupt_index(folder):
    (folder / "catalogue-data").mkdir()
    (folder / "catalogue-data" / "index.sqlite").write_bytes(b"not a database\n" * 64)


def files(name, text):
    def make(d):
        (d / name).write_text(text)
    return make


# (id, files to make first, argv, text the one line must hold)
BAD = [
    ("R huge", None, with_flag("--R", "1e200"), "--R: 1e+200 must be from 0.001 to 10000 mm"),
    ("R nan", None, with_flag("--R", "nan"), "--R: nan must be a finite number"),
    ("t negative", None, with_flag("--t", "-1"), "--t (t/R = -1/20): -0.05 must"),
    ("-h for the depth", None, CASE[:5] + ["-h", "20"] + CASE[7:], "-h 20: not an option (the flag is --h"),
    ("corrupt index, list", corrupt_index, ["catalogue", "list"],
     "catalogue-data/index.sqlite: not a catalogue index (file is not a database); "
     "`shell-adhesion catalogue rebuild` rebuilds it"),
    ("corrupt index, run", lambda d: (corrupt_index(d), (d / "s.yaml").write_text(STUDY)),
     ["run", "s.yaml"], "catalogue: catalogue-data/index.sqlite: not a catalogue index"),
    ("list names no catalogue", None, ["catalogue", "list", "--catalogue", "nowhere"],
     "--catalogue: nowhere: no catalogue there (no index.sqlite)"),
    ("rebuild names no catalogue", None, ["catalogue", "rebuild", "--catalogue", "nowhere"],
     "--catalogue: nowhere: no stored path sets there"),
    ("study over 1 MB", files("s.yaml", STUDY + "#" * 1_000_001 + "\n"), ["run", "s.yaml"],
     "the study file is over 1 MB"),
    ("duplicate key", files("s.yaml", STUDY + "mesh: fine\n"), ["run", "s.yaml"],
     "duplicate key 'mesh'"),
    ("unknown key", files("s.yaml", STUDY + "delta_max_over_r: 0.1\n"), ["run", "s.yaml"],
     "delta_max_over_r: unknown key; did you mean delta_max_over_R?"),
    ("unstable yeoh", None, CASE + ["--material", "yeoh", "--C20", "-0.1"],
     "--material: yeoh (C10 = 0.3 MPa, C20 = -0.1 MPa, C30 = 0 MPa) is unstable (Drucker): "
     "the uniaxial tangent stiffness d sigma / d stretch is <= 0 at stretch 1.5"),
    ("unstable mooney-rivlin", None, CASE + ["--material", "mooney-rivlin", "--C01", "-0.5"],
     "--material: mooney_rivlin (C10 = 0.3 MPa, C01 = -0.5 MPa) is unstable (Drucker)"),
    ("coefficient not of the model", None, CASE + ["--material", "yeoh", "--C01", "0.05"],
     "--C01: 0.05 is not a coefficient of the yeoh model (C10, C20, C30, D1)"),
    ("C01 of neo-Hookean", None, CASE + ["--C01", "0.05"],
     "--C01: 0.05 is not a coefficient of the neo_hooke model (C10, D1)"),
    ("gent without Jm", None, CASE + ["--material", "gent"],
     "--Jm: the gent model needs Jm (a number > 0)"),
    ("gent Jm negative", None, CASE + ["--material", "gent", "--Jm", "-1"], "--Jm: -1 must be > 0"),
    ("D1 negative", None, CASE + ["--D1", "-0.01"],
     "--D1: -0.01 /MPa must be >= 0 (0: incompressible)"),
    ("gent lock-up", None, CASE + ["--material", "gent", "--Jm", "0.001", "--mesh", "coarse"],
     "gent limit: the solid locks up at delta = "),
    ("unknown model", None, CASE + ["--material", "ogden"],
     "--material: 'ogden' must be one of neo-hookean, mooney-rivlin, yeoh, gent"),
    ("C20 not a number", None, CASE + ["--material", "yeoh", "--C20", "abc"],
     "--C20: 'abc' must be a number (MPa)"),
    ("mistyped flag alone", None, ["case", "--gama", "30"],
     "shell-adhesion case: error: --gama: not an option; did you mean --gamma?"),
    ("mistyped flag", None, CASE + ["--gama", "30"], "--gama: not an option; did you mean --gamma?"),
    ("mistyped flag with =", None, CASE + ["--delta_max=3"],
     "--delta_max: not an option; did you mean --delta-max?"),
    ("mistyped run flag", files("s.yaml", STUDY), ["run", "s.yaml", "--ouput", "r"],
     "--ouput: not an option; did you mean --out?"),
    ("flag spelt out", None, ["case", "--R", "20", "--thickness", "3", "--h", "20", "--C10",
                              "0.3", "--gamma", "30"],
     "shell-adhesion case: error: --thickness: not an option; did you mean --t?"),
    ("design flag spelt out", None, ["design", "--C10", "0.3", "--gamma", "30", "--R", "20",
                                     "--thickness", "1", "3"],
     "shell-adhesion design: error: --thickness: not an option; did you mean --t?"),
    ("map query flag spelt out", None, ["map", "query", "--R", "20", "--t", "3", "--depth", "15",
                                        "--C10", "0.3", "--gamma", "30"],
     "--depth: not an option; did you mean --h?"),
    ("size spelt out", None, ["design", "--C10", "0.3", "--gamma", "30", "--radius", "20"],
     "--radius: not an option; did you mean --R or --b?"),
    ("mistyped --version", None, ["--verison"], "--verison: not an option; did you mean --version?"),
    ("YAML 1.2 number out of range", files("s.yaml", STUDY.replace("R_mm: 20", "R_mm: 1e200")),
     ["run", "s.yaml"], "R_mm: 1e+200 must be from 0.001 to 10000 mm"),
]


def listing(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.stat().st_size for p in sorted(folder.rglob("*"))}


# each case in its own folder of one interpreter: the exit code (main's return, or
# SystemExit's from argparse), stdout and stderr as the process would give them
_DRIVER = """
import contextlib, io, json, os, sys, traceback
from shell_adhesion.cli import main
out = []
for folder, argv in json.load(sys.stdin):
    os.chdir(folder)
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        try:
            code = main(argv)
        except SystemExit as e:
            code = e.code
        except BaseException:
            traceback.print_exc()
            code = None
    out.append(dict(code=code, stdout=stdout.getvalue(), stderr=stderr.getvalue()))
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    """Case id -> (outcome, listing of its folder before, its folder)."""
    folders, before = {}, {}
    for name, make, _, _ in BAD:
        folders[name] = tmp_path_factory.mktemp("trap")
        if make is not None:
            make(folders[name])
        before[name] = listing(folders[name])
    env = {k: v for k, v in ENV.items() if k != "SHELL_ADHESION_CATALOGUE"}
    cases = [(str(folders[name]), argv) for name, _, argv, _ in BAD]
    run = subprocess.run([sys.executable, "-c", _DRIVER], input=json.dumps(cases), env=env,
                         cwd=tmp_path_factory.mktemp("driver"), capture_output=True,
                         text=True, timeout=600)
    assert run.returncode == 0 and run.stderr == "", run.stderr[-3000:]
    return {b[0]: (o, before[b[0]], folders[b[0]])
            for b, o in zip(BAD, json.loads(run.stdout))}


@pytest.mark.parametrize("name, expected", [(b[0], b[3]) for b in BAD], ids=[b[0] for b in BAD])
def test_bad_input_exit_2_one_line_nothing_created(outcomes, name, expected):
    out, before, folder = outcomes[name]
    assert out["code"] == 2, out["stderr"]
    lines = out["stderr"].splitlines()
    assert len(lines) == 1 and "Traceback" not in out["stderr"], out["stderr"]
    assert expected in lines[0]
    assert out["stdout"] == ""
    assert listing(folder) == before


def test_the_process_gives_the_exit_code_and_the_one_line():
    """`python -m shell_adhesion` itself: the cases above go through its entry point."""
    out = subprocess.run([sys.executable, "-m", "shell_adhesion", *with_flag("--R", "nan")],
                         env=ENV, capture_output=True, text=True, timeout=120)
    assert out.returncode == 2 and out.stdout == ""
    (line,) = out.stderr.splitlines()
    assert line.startswith("shell-adhesion: error: --R: nan must be a finite number")


def test_help_still_works():
    out = subprocess.run([sys.executable, "-m", "shell_adhesion", "case", "--help"], env=ENV,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and "--h H" in out.stdout and "--delta-max" in out.stdout
    assert "-h 20" not in out.stdout        # the refused spellings are not advertised
    assert out.stdout.startswith("usage: shell-adhesion case")


def test_flag_prefixes_still_accepted():
    """A prefix of one flag is argparse's abbreviation, not a typo."""
    from shell_adhesion.cli import _parser

    ns = _parser().parse_args(CASE + ["--gam", "30", "--no-error", "--delta=2"])
    assert ns.gamma == ["30"] and ns.no_error_bars and ns.delta_max == "2"
