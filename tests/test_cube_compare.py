"""benchmarks/cube_compare.py: a move beyond its share of the error bar, or a point
answered in one cube only, fails the comparison; equal cubes pass."""
import sys

import numpy as np
import xarray as xr

from conftest import REPO

sys.path.insert(0, str(REPO / "benchmarks"))
import cube_compare  # noqa: E402


def _cube(P_star, P_star_error):
    dims = cube_compare.DIMS
    shape = (1, 1, 1, len(P_star))
    coords = dict(C10=[0.3], t_over_R=[0.15], h_over_R=[1.0], gamma=[10.0, 30.0][:len(P_star)])
    return xr.Dataset({"P_star": (dims, np.reshape(P_star, shape)),
                       "P_star_error": (dims, np.reshape(P_star_error, shape))}, coords=coords)


def test_equal_cubes_pass_and_a_move_beyond_a_fifth_of_the_bar_fails():
    before = _cube([-1.0, -2.0], [0.01, 0.02])
    rows, failures = cube_compare.compare(before, before, ["P_star"], 0.2)
    assert len(rows) == 2 and not failures
    # 0.0019 is within a fifth of 0.01; 0.0041 is beyond a fifth of 0.02 (the larger bar)
    rows, failures = cube_compare.compare(before, _cube([-1.0019, -2.0041], [0.01, 0.005]),
                                          ["P_star"], 0.2)
    assert [round(r[5], 3) for r in rows] == [0.19, 0.205]
    assert len(failures) == 1 and "gamma 30" in failures[0]


def test_a_point_answered_in_one_cube_only_fails():
    rows, failures = cube_compare.compare(_cube([-1.0, -2.0], [0.01, 0.02]),
                                          _cube([-1.0, np.nan], [0.01, np.nan]), ["P_star"],
                                          0.2)
    assert len(rows) == 1 and "not the same ones" in failures[0]


def test_the_command_exits_1_on_a_failure(tmp_path):
    before, after = tmp_path / "before.nc", tmp_path / "after.nc"
    _cube([-1.0, -2.0], [0.01, 0.02]).to_netcdf(before)
    _cube([-1.0, -2.1], [0.01, 0.02]).to_netcdf(after)
    assert cube_compare.main([str(before), str(before), "--names", "P_star"]) == 0
    assert cube_compare.main([str(before), str(after), "--names", "P_star"]) == 1
