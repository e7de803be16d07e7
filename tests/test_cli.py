"""The `case` command: bad input gives one line and exit 2; JSON has the promised shape."""
import json
import subprocess
import sys

import pytest

BASE = ["--R", "20", "--t", "3", "--h", "20", "--C10", "0.3"]


def run(*args):
    return subprocess.run([sys.executable, "-m", "shell_adhesion", "case", *args],
                          capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("change,flag", [
    (["--t", "0"], "--t"), (["--t", "25"], "--t"), (["--t", "abc"], "--t"),
    (["--h", "3"], "--h"), (["--h", "21"], "--h"), (["--C10", "-1"], "--C10"),
    (["--C10", "nan"], "--C10"), (["--delta-max", "0"], "--delta-max"),
    (["--gamma", "-3"], "--gamma"), (["--gamma", "900"], "--gamma"), (["--R", "0"], "--R")])
def test_bad_input_one_line(change, flag):
    args = list(BASE)
    for k, v in zip(change[::2], change[1::2]):
        if k in args:
            args[args.index(k) + 1] = v
        else:
            args += [k, v]
    out = run(*args)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and flag in lines[0] and "Traceback" not in out.stderr
    assert out.stdout == ""


def test_json_case_with_adhesion():
    out = run(*BASE, "--mesh", "coarse", "--delta-max", "5", "--gamma", "30", "--gamma", "20", "--json", "--curves")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert set(data) >= {"input", "loading", "relaxation", "equilibrium", "pull_off", "provenance"}
    ld = data["loading"]
    assert len(ld["delta_mm"]) == len(ld["P_N"]) == len(ld["a_mm"]) > 10
    assert ld["delta_mm"][-1] == pytest.approx(5.0)
    assert 13.0 < ld["P_N"][-1] < 16.5
    assert [p["gamma_J_m2"] for p in data["pull_off"]] == [30.0, 20.0]
    p30, p20 = data["pull_off"]
    assert p30["fixed_load"]["P_N"] < p20["fixed_load"]["P_N"] < 0
    assert {"a_mm", "delta1_mm", "P1_N", "delta_mm", "P_N", "U_E_mJ"} <= set(data["relaxation"][0])
    prov = data["provenance"]
    assert prov["dofs"] > 0 and prov["newton_iterations"] > 0 and prov["mesh"] == "coarse"


def test_no_error_bars_asked_prints_no_missing_error_bar():
    """With --no-error-bars every number is printed bare; a missing error bar is only
    announced when error bars were asked for."""
    out = run(*BASE, "--mesh", "coarse", "--gamma", "30", "--no-error-bars")
    assert out.returncode == 0, out.stderr
    line = next(l for l in out.stdout.splitlines() if l.startswith("gamma = 30"))
    assert "P* = -1.71" in line and "+-" not in line and "no error bar" not in line
