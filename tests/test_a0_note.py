"""A case whose loading stops short of P = 0 on the equilibrium curve says where the curve
ends and gives the --delta-max that answers a0; that command does answer it (coarse mesh)."""
import json
import re
from types import SimpleNamespace

from shell_adhesion.cli import main
from shell_adhesion.solver.geometry import Cap, delta_bound
from shell_adhesion.study.a0_note import a0_note

BASE = ["case", "--R", "20", "--t", "3", "--h", "20", "--C10", "0.3", "--gamma", "30",
        "--mesh", "coarse", "--no-error-bars"]


def test_an_undefined_a0_names_the_depth_that_answers_it(capsys):
    assert main(BASE) == 0
    out = capsys.readouterr().out
    assert "a0 = undefined (below)" in out
    hint = re.search(r"a deeper loading gives a0: add --delta-max ([0-9.]+) ", out)
    assert hint, out
    assert float(hint.group(1)) == delta_bound(Cap(3 / 20, 1.0)) * 20
    assert main(BASE + ["--delta-max", hint.group(1), "--json"]) == 0
    po = json.loads(capsys.readouterr().out)["pull_off"][0]
    a_star = po["fixed_load"]["a_mm"]
    assert po["a0_mm"] is not None and po["a0_mm"] > a_star, po
    assert "a0_note" not in po


def test_a0_beyond_the_deepest_loading_says_so():
    shell = SimpleNamespace(R_mm=20.0, t_mm=3.0, h_mm=20.0, delta_max_mm=None)
    deepest = delta_bound(Cap(0.15, 1.0)) * 20
    note = a0_note(shell, {"loading_reached": {"delta_reached_mm": deepest}}, 8.5, -0.2)
    assert note.startswith("a0 undefined: the equilibrium curve ends at a = 8.5 mm with "
                           "P = -0.2 N")
    assert "a0 lies beyond the contact radii it reaches" in note and "--delta-max" not in note
