"""Ctrl-C is taken at a safe point of the computing loop, and a shutdown that hangs after
Ctrl-C still ends the command within its bound (exit 130, one line)."""
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from shell_adhesion.study import interrupt

from conftest import ENV, REPO


def test_first_ctrl_c_inside_deferred_is_a_request_taken_at_check():
    with interrupt.deferred():
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(0.05)                    # the handler runs; nothing is raised here
        assert interrupt.requested()
        with pytest.raises(KeyboardInterrupt):
            interrupt.check()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_second_ctrl_c_inside_deferred_raises_at_once():
    with pytest.raises(KeyboardInterrupt):
        with interrupt.deferred():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1.0)                 # not reached: the second one raises
            pytest.fail("the second Ctrl-C did not raise")


def test_ctrl_c_outside_deferred_raises_as_usual():
    with pytest.raises(KeyboardInterrupt):
        with interrupt.watched():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1.0)
            pytest.fail("Ctrl-C did not raise")


def test_the_hard_exit_is_disarmed_outside_its_block():
    """An in-process `run` (a test, a notebook) leaves nothing armed behind it."""
    with interrupt.hard_exit_after(0.2, "never printed"):
        pass
    with pytest.raises(KeyboardInterrupt):
        with interrupt.watched():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1.0)
    assert interrupt._timer is None
    time.sleep(0.4)                         # the process is still here


# a run whose shutdown after Ctrl-C never ends (as a dask close that waits forever would)
HUNG_RUN = textwrap.dedent("""
    import sys, time
    from shell_adhesion import cli
    from shell_adhesion.study import run

    def never_ends(*args, **kwargs):
        try:
            print("running", flush=True)
            time.sleep(600)
        except KeyboardInterrupt:
            time.sleep(600)           # the shutdown hangs

    run._execute = never_ends
    cli.HARD_EXIT_S = 2.0
    sys.exit(cli.main(sys.argv[1:]))
""")


def test_a_hung_shutdown_after_ctrl_c_still_ends_in_one_line(tmp_path):
    study = tmp_path / "s.yaml"
    study.write_text("name: s\nR_mm: 20\nbase: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, "
                     "gamma_J_m2: 30}\nmesh: coarse\ndelta_max_over_R: 0.05\n")
    proc = subprocess.Popen([sys.executable, "-c", HUNG_RUN, "run", str(study), "--out",
                             str(tmp_path / "out"), "--catalogue", str(tmp_path / "cat"),
                             "--quiet"], cwd=REPO, env=ENV, start_new_session=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "running"
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    assert proc.returncode == 130, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("shell-adhesion: interrupted: "), err
    assert "cut short" in lines[0] and "run again" in lines[0]


# a map build whose computing loop is interrupted (as study.run._execute ends on Ctrl-C)
INTERRUPTED_BUILD = textwrap.dedent("""
    import sys
    import time
    from shell_adhesion import cli
    from shell_adhesion.study import run

    def interrupted(*args, **kwargs):
        try:
            print("running", flush=True)
            time.sleep(600)
        except KeyboardInterrupt:
            raise run.Interrupted("interrupted: 3 relaxation paths finished and are kept in "
                                  "the catalogue CAT; run again to resume") from None

    run._execute = interrupted
    sys.exit(cli.main(sys.argv[1:]))
""")


def test_ctrl_c_in_map_build_ends_in_one_line(tmp_path):
    """`map build` runs a study and ends on Ctrl-C as `run` does: exit 130, one line
    saying what is kept, no traceback and no map file."""
    study = tmp_path / "m.yaml"
    study.write_text("name: m\nR_mm: 20\nbase: {C10_MPa: 1.0}\ngrid: {t_over_R: [0.1, 0.15], "
                     "h_over_R: [0.5, 1.0], gamma_J_m2: [10, 20]}\nmesh: coarse\n")
    out = tmp_path / "m.nc"
    proc = subprocess.Popen([sys.executable, "-c", INTERRUPTED_BUILD, "map", "build",
                             str(study), "--out", str(out), "--catalogue",
                             str(tmp_path / "cat")], cwd=REPO, env=ENV,
                            start_new_session=True, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "running"
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    assert proc.returncode == 130, err
    lines = err.strip().splitlines()
    assert lines == ["shell-adhesion: interrupted: 3 relaxation paths finished and are kept "
                     "in the catalogue CAT; run again to resume"], err
    assert not out.exists() and not out.with_suffix(".nc.part").exists()
