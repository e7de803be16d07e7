"""`case --cavity ...` and solve_case(cavity=...): refusals (one line, exit 2, before any
computation) and the JSON of a closed cavity (V_mm3, p_kPa, the first-touch state)."""
import json
import subprocess
import sys

import pytest

from shell_adhesion.errors import InputError
from shell_adhesion.study.case import solve_case
from shell_adhesion.study.case_input import case_input

BASE = ["--R", "20", "--t", "3", "--h", "20", "--C10", "0.3"]


def run(*args):
    return subprocess.run([sys.executable, "-m", "shell_adhesion", "case", *BASE, *args],
                          capture_output=True, text=True, timeout=120)


# the three refusals of the issue through the command line (one line, exit 2)
@pytest.mark.parametrize("args,flag,words", [
    (["--cavity", "pressure", "--p-kPa", "-150"], "--p-kPa", "negative absolute pressure"),
    (["--p-kPa", "10"], "--p-kPa", "without --cavity pressure"),
    (["--cavity", "sealed", "--gas-exponent", "0.9"], "--gas-exponent", ">= 1"),
])
def test_bad_cavity_input_one_line(args, flag, words):
    out = run(*args)
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and flag in lines[0] and words in lines[0], lines
    assert "Traceback" not in out.stderr and out.stdout == ""


FLAGS = dict(cavity="--cavity", p_kPa="--p-kPa", p0_kPa="--p0-kPa", p_atm_kPa="--p-atm-kPa",
             gas_exponent="--gas-exponent", t_mm="--t")


# and every rule, in process (the same case_input the command line calls)
@pytest.mark.parametrize("kw,flag,words", [
    (dict(cavity="sealed", p0_kPa=-102), "--p0-kPa", "negative absolute pressure"),
    (dict(cavity="sealed", p_atm_kPa=-1), "--p-atm-kPa", ">= 0"),
    (dict(cavity="pressure", p_kPa=10, p_atm_kPa=-1), "--p-atm-kPa", ">= 0"),
    (dict(cavity="sealed", p_kPa=10), "--p-kPa", "without --cavity pressure"),
    (dict(gas_exponent=1.4), "--gas-exponent", "without --cavity sealed"),
    (dict(p_atm_kPa=90), "--p-atm-kPa", "without --cavity pressure or sealed"),
    (dict(cavity="pressure"), "--cavity", "needs --p-kPa"),
    (dict(cavity="vacuum"), "--cavity", "must be one of"),
    (dict(cavity="pressure", p_kPa=float("nan")), "--p-kPa", "finite"),
    (dict(cavity="sealed", t_mm=20), "--cavity", "solid cap"),
])
def test_cavity_rules(kw, flag, words):
    t = kw.pop("t_mm", 3)
    with pytest.raises(InputError) as err:
        case_input(20, t, 20, 0.3, names=FLAGS, **kw)
    msg = str(err.value)
    assert msg.startswith(flag + ":") and words in msg and "\n" not in msg, msg


def test_api_names_fields():
    with pytest.raises(InputError, match="^p_kPa: given without cavity pressure"):
        case_input(20, 3, 20, 0.3, p_kPa=5)
    inp = case_input(20, 3, 20, 0.3, cavity="pressure", p_kPa=-15)
    assert inp.cavity.p == pytest.approx(-15e-3 / 0.3)
    assert inp.cavity.p_atm == pytest.approx(101.325e-3 / 0.3)
    assert inp.as_dict()["cavity"] == dict(mode="pressure", p_kPa=pytest.approx(-15),
                                           p0_kPa=None, p_atm_kPa=pytest.approx(101.325),
                                           gas_exponent=None)


def test_snap_refused_in_kPa():
    with pytest.raises(InputError) as err:
        solve_case(20, 3, 20, 0.3, cavity="pressure", p_kPa=400, mesh="coarse", progress=False)
    assert "400 kPa makes the free shell snap" in str(err.value) and "it holds" in str(err.value)


def test_json_of_a_sealed_cavity():
    res = solve_case(20, 3, 20, 0.3, 10, delta_max_mm=0.6, mesh="coarse", cavity="sealed",
                     progress=False)
    data = json.loads(res.to_json(curves=True))
    ld = data["loading"]
    assert len(ld["V_mm3"]) == len(ld["p_kPa"]) == len(ld["delta_mm"])
    assert ld["p_kPa"][0] == 0.0 and ld["p_kPa"][-1] > 0     # compressed on approach
    assert ld["V_mm3"][-1] < ld["V_mm3"][0]
    rel = data["relaxation"][0]
    assert len(rel["V_mm3"]) == len(rel["p_kPa"]) == len(rel["delta_mm"])
    assert data["input"]["cavity"]["mode"] == "sealed"
    touch = data["provenance"]["cavity_touch"]
    assert touch["apex_uz_mm"] == 0.0 and touch["p_kPa"] == 0.0
    # the undeformed cavity: the inner cap of radius 17 mm below z = h (Q2 arcs: 1e-5)
    assert touch["V_mm3"] == pytest.approx(2 / 3 * 3.141592653589793 * 17 ** 3, rel=1e-5)
    ds = res.to_dataset()
    assert ds["loading_p"].attrs["units"] == "kPa" and ds["relaxation_V"].attrs["units"] == "mm3"
    assert ds.attrs["cavity_mode"] == "sealed" and ds.attrs["cavity_gas_exponent"] == 1.0
    assert float(ds["loading_p"][-1]) == pytest.approx(ld["p_kPa"][-1], rel=1e-9)
