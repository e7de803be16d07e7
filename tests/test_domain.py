"""The supported domain (issue 10, item 5): t/R in [0.02, 1], h/R in [max(t/R, 0.2), 1]
(a solid cap, t = R: h/R in [0.2, 1]), delta up to 0.25 R, gamma/(C10 R) up to GAMMA_MAX.
A request outside gets one line naming the rule: InputError (a ValueError) from the
solver API, exit 2 from the command line, before any computation."""
import subprocess
import sys

import pytest

from shell_adhesion.solver import case
from shell_adhesion.solver.geometry import (DELTA_MAX, GAMMA_MAX, H_MIN, T_MIN, check_cap,
                                            check_delta_max, check_gamma)
from shell_adhesion.errors import InputError

from conftest import ENV, REPO


@pytest.mark.parametrize("t,h,rule", [(0.019, 1.0, "t/R >= 0.02"), (0.1, 0.19, "h/R >= 0.2"),
                                      (1.0, 0.19, "h/R >= 0.2"), (0.3, 0.3, "> t")])
def test_cap_outside_the_domain(t, h, rule):
    with pytest.raises(InputError, match=rule):
        check_cap(t, h)


@pytest.mark.parametrize("t,h", [(T_MIN, 1.0), (T_MIN, H_MIN), (0.15, H_MIN), (1.0, 1.0),
                                 (1.0, H_MIN), (0.5, 0.51)])
def test_cap_on_the_domain_edges(t, h):
    check_cap(t, h)


def test_delta_and_gamma_bounds():
    check_delta_max(DELTA_MAX, 1.0)
    check_gamma(GAMMA_MAX)
    for bad, rule in ((0.26, "delta/R <= 0.25"), (0.0, "> 0"), (float("inf"), "finite")):
        with pytest.raises(InputError, match=rule):
            check_delta_max(bad, 1.0)
    with pytest.raises(InputError, match="< h/R"):
        check_delta_max(0.2, 0.2)
    for bad, rule in ((0.031, "<= 0.03"), (-1e-3, "> 0")):
        with pytest.raises(InputError, match=rule):
            check_gamma(bad)


@pytest.mark.parametrize("t,h,delta_max,field", [(0.01, 1.0, 0.1, "t/R"), (0.15, 0.15, 0.1, "h/R"),
                                                 (0.15, 1.0, 0.3, "delta_max/R")])
def test_solver_api_refuses_before_computing(monkeypatch, t, h, delta_max, field):
    def no_mesh(*args):
        raise AssertionError("meshed a refused case")
    monkeypatch.setattr(case, "cap_mesh", no_mesh)
    with pytest.raises(ValueError, match=field):
        case.solve_paths(t, h, "no_slip", "coarse", delta_max)


def test_pull_off_refuses_gamma_beyond_the_domain(base_coarse):
    ps, _, _ = base_coarse
    from dataclasses import replace
    with pytest.raises(ValueError, match="gamma/\\(C10 R\\)"):
        replace(ps, gamma_max=0.1).pull_off(0.04)


@pytest.mark.parametrize("args,word", [
    (["--t", "0.3"], "t/R"),                          # t/R = 0.015
    (["--t", "3", "--h", "3.5", "--delta-max", "2"], "h/R"),   # h/R = 0.175
    (["--t", "20", "--h", "3.8", "--delta-max", "2"], "h/R"),  # solid cap, h/R = 0.19
    (["--t", "3", "--delta-max", "6"], "delta"),      # delta/R = 0.3
    (["--t", "3", "--gamma", "200"], "gamma"),        # gamma/(C10 R) = 0.033
])
def test_cli_refuses_with_one_line_and_exit_2(args, word):
    base = dict(zip(["--R", "--t", "--h", "--C10"], ["20", "3", "20", "0.3"]))
    base.update(dict(zip(args[::2], args[1::2])))
    cmd = [sys.executable, "-m", "shell_adhesion", "case", "--mesh", "coarse"]
    for k, v in base.items():
        cmd += [k, v]
    out = subprocess.run(cmd, cwd=REPO, env=ENV, capture_output=True, text=True, timeout=60)
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and word in lines[0] and out.stdout == ""
