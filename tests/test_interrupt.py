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
    before = signal.getsignal(signal.SIGINT)    # SIG_IGN where started in the background
    with interrupt.deferred():
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(0.05)                    # the handler runs; nothing is raised here
        assert interrupt.requested()
        with pytest.raises(KeyboardInterrupt):
            interrupt.check()
    assert signal.getsignal(signal.SIGINT) is before       # the caller's handler is back


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


# the command line with study.run._execute replaced by `on_ctrl_c`: it prints "running",
# waits, and on Ctrl-C does what the test asks
PATCHED_CLI = textwrap.dedent("""
    import sys, time
    from shell_adhesion import cli
    from shell_adhesion.study import run

    def waits(*args, **kwargs):
        try:
            print("running", flush=True)
            time.sleep(600)
        except KeyboardInterrupt:
            {on_ctrl_c}

    run._execute = waits
    cli.HARD_EXIT_S = 2.0
    sys.exit(cli.main(sys.argv[1:]))
""")


def ctrl_c(on_ctrl_c, *args):
    """Run the patched command line with `args`, press Ctrl-C once it runs; (exit code,
    stderr lines)."""
    script = PATCHED_CLI.format(on_ctrl_c=on_ctrl_c)
    proc = subprocess.Popen([sys.executable, "-c", script, *map(str, args)], cwd=REPO,
                            env=ENV, start_new_session=True, stdout=subprocess.PIPE,
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
    return proc.returncode, err.strip().splitlines()


def test_a_hung_shutdown_after_ctrl_c_still_ends_in_one_line(tmp_path):
    study = tmp_path / "s.yaml"
    study.write_text("name: s\nR_mm: 20\nbase: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, "
                     "gamma_J_m2: 30}\nmesh: coarse\ndelta_max_over_R: 0.05\n")
    code, lines = ctrl_c("time.sleep(600)  # the shutdown hangs", "run", study, "--out",
                         tmp_path / "out", "--catalogue", tmp_path / "cat", "--quiet")
    assert code == 130, lines
    assert len(lines) == 1 and lines[0].startswith("shell-adhesion: interrupted: "), lines
    assert "cut short" in lines[0] and "run again" in lines[0]


def test_ctrl_c_in_map_build_ends_in_one_line(tmp_path):
    """`map build` runs a study and ends on Ctrl-C as `run` does: exit 130, one line
    saying what is kept, no traceback and no map file."""
    study = tmp_path / "m.yaml"
    study.write_text("name: m\nR_mm: 20\nbase: {C10_MPa: 1.0}\ngrid: {t_over_R: [0.1, 0.15], "
                     "h_over_R: [0.5, 1.0], gamma_J_m2: [10, 20]}\nmesh: coarse\n")
    out = tmp_path / "m.nc"
    kept = "interrupted: 3 relaxation paths are kept in CAT; run again to resume"
    code, lines = ctrl_c(f"raise run.Interrupted({kept!r}) from None", "map", "build", study,
                         "--out", out, "--catalogue", tmp_path / "cat")
    assert code == 130, lines
    assert lines == [f"shell-adhesion: {kept}"], lines
    assert not out.exists() and not out.with_suffix(".nc.part").exists()
