"""`design` and `map` at their edges, on the shipped coarse map (no FE): fixed and narrow
bounds inside the map answered, a value off the map named with the map's range, progress
while the search runs, a file that is not a map refused in one line (exit 2).  A map
study that cannot be interpolated: tests/test_pull_off_map.py."""
import json

import numpy as np
import pytest
import xarray as xr

import shell_adhesion as sa
from shell_adhesion.cli import main
from shell_adhesion.study import progress
from shell_adhesion.study.pull_off_map import pull_off_map

DESIGN = ["design", "--C10", "0.3", "--gamma", "30", "--map", "coarse", "--no-confirm",
          "--json"]


def designed(capsys, *args):
    assert main(DESIGN + list(args)) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)["design"]


@pytest.mark.parametrize("size", [["--R", "20"], ["--b", "15"]])
def test_fixed_thickness_inside_the_map_is_answered(capsys, size):
    d = designed(capsys, *size, "--t", "3", "3")
    assert d["t_mm"] == 3.0
    assert "t fixed at 3 mm (your bounds)" in d["on_bounds"]
    fixed = designed(capsys, *size, "--t", "3", "3", "--h", "12", "12")
    assert (fixed["t_mm"], fixed["h_mm"]) == (3.0, 12.0)
    # the map's own answer at that shell
    want = pull_off_map("coarse").shell(fixed["R_mm"], 3.0, 12.0, 0.3, 30)["P_star_N"][0]
    assert fixed["answers"]["P_star_N"][0] == pytest.approx(want, rel=1e-12)


def test_narrow_bounds_are_searched_inside_themselves(capsys):
    """Bounds narrower than a step of a grid over the whole map: the optimum lies in them
    and is no worse than their corners."""
    d = designed(capsys, "--R", "20", "--t", "3", "3.05", "--h", "15", "15.1")
    assert 3 <= d["t_mm"] <= 3.05 and 15 <= d["h_mm"] <= 15.1
    pm = pull_off_map("coarse")
    corners = [abs(pm.shell(20, t, h, 0.3, 30)["P_star_N"][0]) for t in (3, 3.05)
               for h in (15, 15.1)]
    assert d["objective_value"] >= max(corners) * (1 - 1e-9)


@pytest.mark.parametrize("args, message", [
    (["--R", "20", "--t", "30", "40"],
     "--t: 30 to 40 mm is outside the map: t from 1 to 8 mm for R 20 mm"),
    (["--R", "20", "--t", "3", "3", "--h", "21", "30"],
     "--h: 21 to 30 mm is outside the map: h from 10 to 20 mm for R 20 mm"),
    (["--R", "20", "--gamma", "3000"],
     "--gamma: 3000 J/m^2 is gamma/(C10 R) = 0.5, outside the map's 0.0003 to 0.03 (gamma "
     "from 1.8 to 180 J/m^2"),
    (["--b", "15", "--t", "30", "30"],
     "--t: 30 mm is outside the map: t from 0.75 to 6.928 mm for b 15 mm and h from 8.66 to "
     "15 mm"),
])
def test_a_value_off_the_map_is_named_with_the_maps_range(args, message, capsys):
    argv = [a for a in DESIGN if a != "--json"]
    if "--gamma" in args:
        i = argv.index("--gamma")
        argv = argv[:i] + argv[i + 2:]
    assert main(argv + args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err, err


def test_design_shows_its_progress(capsys, monkeypatch):
    monkeypatch.setattr(progress, "shown", lambda stream=None: True)
    sa.design(0.3, 30, R_mm=20, map="coarse", confirm=False, progress=True)
    err = capsys.readouterr().err
    assert "design 1/1: map search" in err
    assert "/1681 " in err and "<" in err, err      # n of N, and tqdm's time left
    sa.design(0.3, 30, R_mm=20, map="coarse", confirm=False, progress=False)
    assert capsys.readouterr().err == ""


def _not_a_map(folder):
    (folder / "text.nc").write_text("delta_mm,P_N\n0,0\n")
    xr.Dataset({"P_N": ("i", np.zeros(3))}).to_netcdf(folder / "curve.nc")
    pull_off_map("coarse").ds.isel(h_over_R=[0]).to_netcdf(folder / "one_h.nc")


@pytest.mark.parametrize("name, message", [
    ("text.nc", "is not a netCDF file that xarray can read"),
    ("curve.nc", "is a netCDF file but not a pull-off map (it has no t_over_R, h_over_R, "
                 "gamma_hat, P_star)"),
    ("one_h.nc", "h_over_R has 1 value: a map interpolates along each of"),
])
@pytest.mark.parametrize("command", [
    ["map", "query", "--R", "20", "--t", "3", "--h", "15", "--C10", "0.3", "--gamma", "30"],
    ["design", "--R", "20", "--C10", "0.3", "--gamma", "30", "--no-confirm"]])
def test_a_map_file_that_is_not_a_map_is_one_line(name, message, command, capsys, tmp_path,
                                                  monkeypatch):
    _not_a_map(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert main(command + ["--map", name]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"shell-adhesion: error: --map: '{name}'") and message in err, err
    assert len(err.splitlines()) == 1
