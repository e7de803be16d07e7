"""`fit_curve` and `shell-adhesion fit`: a synthetic test of a shell is fitted back (coarse
mesh), the half-space JKR fit of the same data misses gamma, and bad input is one line with
exit 2."""
import functools
import importlib.util
import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from shell_adhesion import fit_curve
from shell_adhesion.solver.fit import gamma_curve
from shell_adhesion.errors import InputError
from shell_adhesion.cli import main

from conftest import ENV

EXAMPLE = pathlib.Path(__file__).parent.parent / "examples" / "ex04_fit_curve.py"


@functools.lru_cache(maxsize=None)
def example():
    spec = importlib.util.spec_from_file_location("ex04", EXAMPLE)
    ex = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ex)
    ex.synthetic_curve = functools.lru_cache(maxsize=None)(ex.synthetic_curve)
    return ex


@functools.lru_cache(maxsize=None)
def round_trip():
    return example().round_trip("coarse")


def test_round_trip():
    """C10 within 1 %, gamma within 3 %, delta0 within 0.01 mm, each true value inside its
    95 % interval; the half-space fit misses gamma by more than 20 %."""
    ex = example()
    result, rows = round_trip()
    print("\n" + ex.table(rows))
    (_, C10, C10_fit, C10_ci, _), (_, g, g_fit, g_ci, g_jkr), (_, d0, d0_fit, d0_ci, _) = rows
    assert abs(C10_fit / C10 - 1) < 0.01
    assert abs(g_fit / g - 1) < 0.03
    assert abs(d0_fit - d0) < 0.01
    for true, (lo, hi) in ((C10, C10_ci), (g, g_ci), (d0, d0_ci)):
        assert lo < true < hi
    print(f"half-space JKR: gamma = {g_jkr:.4g} J/m^2, {100 * (g_jkr / g - 1):+.1f} % off")
    assert abs(g_jkr / g - 1) > 0.2
    out = result.to_dict()
    assert out["points_used"] == {"loading": 40, "retraction": 40, "after_pull_off": 5,
                                  "on_the_drop": 0}
    assert out["residual_rms_N"] < 0.02 * np.max(np.abs(result.input.P_N))


def test_pull_off_force():
    """gamma from a measured pull-off force alone (the true P*) comes back within 3 %."""
    ex = example()
    result, _ = round_trip()
    g_hat = ex.GAMMA_J_M2 * 1e-3 / (ex.C10_MPA * ex.R_MM)
    P_star_N = gamma_curve(result.pathset, g_hat)[1].P_star * ex.C10_MPA * ex.R_MM ** 2
    fit = fit_curve(ex.R_MM, ex.T_MM, ex.H_MM, ex.synthetic_curve("coarse"),
                    pull_off_N=P_star_N, mesh="coarse").to_dict()
    assert fit["gamma_from"] == "pull_off"
    assert abs(fit["gamma_J_m2"] / ex.GAMMA_J_M2 - 1) < 0.03
    lo, hi = fit["gamma_J_m2_ci95"]
    assert lo <= fit["gamma_J_m2"] <= hi


def test_cli_json_and_plot(tmp_path, capsys):
    ex = example()
    csv = tmp_path / "test.csv"
    ex.write_csv(csv, *ex.synthetic_curve("coarse"))
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(csv),
                 "--mesh", "coarse", "--json", "--plot", str(tmp_path / "fit.png")])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert abs(out["C10_MPa"] / ex.C10_MPA - 1) < 0.01
    assert set(out["jkr"]) >= {"E_MPa", "gamma_J_m2"}
    assert (tmp_path / "fit.png").stat().st_size > 0


BAD = {
    "header": ("d,P\n0,0\n", "header: unknown column 'd'; accepted: delta_mm, delta_um"),
    "number": ("delta_mm,P_N\n0,0\n0.1,abc\n", "row 3: P_N: 'abc' is not a number"),
    "nan": ("delta_mm,P_N\n0,0\nnan,0.1\n", "row 3: delta_mm: nan must be a finite number"),
    "few": ("delta_mm,P_N\n0,0\n0.1,0.1\n0.2,0.3\n0.1,0\n", "3 loading points"),
    "tension": ("delta_mm,P_N\n" + "".join(f"{0.1 * i},{-0.1 * i}\n" for i in range(6)),
                "never compresses"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_curve(name, tmp_path, capsys):
    text, message = BAD[name]
    csv = tmp_path / "bad.csv"
    csv.write_text(text)
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(csv),
                 "--mesh", "coarse"])
    err = capsys.readouterr().err
    assert code == 2
    assert err.count("\n") == 1 and message in err and str(csv) in err


def test_bad_flags(tmp_path, capsys):
    csv = tmp_path / "missing.csv"
    assert main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(csv)]) == 2
    assert "cannot be read" in capsys.readouterr().err
    assert main(["fit", "--R", "20", "--t", "30", "--h", "20", "--curve", str(csv)]) == 2
    assert "--t" in capsys.readouterr().err


def test_too_deep(tmp_path, capsys):
    """A curve loaded beyond the shell's supported depth (R/4 here): one line, exit 2."""
    ex = example()
    d, P = ex.synthetic_curve("coarse")
    csv = tmp_path / "deep.csv"
    ex.write_csv(csv, 4 * d, P)
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(csv),
                 "--mesh", "coarse"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "beyond the supported 5 mm" in err


def test_bad_curve_api():
    with pytest.raises(InputError, match="row 4: P_N"):
        fit_curve(20, 3, 20, ([0, 0.1, 0.2, 0.3, 0.4], [0, 1, float("nan"), 2, 3]))


def test_bad_curve_command(tmp_path):
    """The installed command: one line on stderr, exit 2."""
    csv = tmp_path / "bad.csv"
    csv.write_text(BAD["header"][0])
    run = subprocess.run([sys.executable, "-m", "shell_adhesion", "fit", "--R", "20", "--t", "3",
                          "--h", "20", "--curve", str(csv)], capture_output=True, text=True,
                         env=ENV)
    assert run.returncode == 2
    assert run.stderr.count("\n") == 1 and "header" in run.stderr
