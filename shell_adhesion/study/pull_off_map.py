"""Pull-off maps: built by a study, shipped with the package, opened by name or file.

`build_pull_off_map` runs a study over t/R x h/R x gamma (one C10; the catalogue, dask and
the error bars of any study) and writes the dimensionless map beside its cube;
`pull_off_map` opens a shipped map or a map file.  Shipped: ``default`` (default mesh,
`no_slip`, neo-Hookean; its study is `shell_adhesion/data/pull_off_map.yaml`) and
``coarse`` (the same grid on the coarse mesh, `pull_off_map_coarse.yaml`).  The
interpolant itself is `shell_adhesion.analysis.pull_off_map`.
"""
from pathlib import Path

import xarray as xr

from shell_adhesion.analysis.pull_off_map import AXES, PullOffMap, map_from_cube
from shell_adhesion.examples import DATA
from shell_adhesion.study.config import Study, StudyError, load_study, validate

SHIPPED = {"default": "pull_off_map.nc", "coarse": "pull_off_map_coarse.nc"}
DEFAULT_MAP = "default"         # the map used when none is named


def map_path(map=DEFAULT_MAP) -> Path:
    """The file of a shipped map (a key of SHIPPED) or of a map file given by path;
    ValueError naming --map otherwise."""
    if str(map) in SHIPPED:
        return DATA / SHIPPED[str(map)]
    path = Path(map)
    if not path.is_file():
        raise ValueError(f"--map: {str(map)!r} is neither a shipped map "
                         f"({', '.join(SHIPPED)}) nor a file ({path.resolve()} does not exist)")
    return path


def pull_off_map(map=DEFAULT_MAP) -> PullOffMap:
    """The interpolant of a pull-off map: a shipped one by name (``default``, ``coarse``) or a file
    written by `build_pull_off_map`.

    ``pull_off_map().shell(R_mm=20, t_mm=3, h_mm=20, C10_MPa=0.3, gamma_J_m2=30)`` gives
    P*, delta*, a*, P_dagger, delta_dagger, a_dagger and the preload (N, mm), each as
    (value, error): the interpolation error (grid points left out) and the FE error bar in
    quadrature.
    """
    path = map_path(map)
    try:
        with xr.open_dataset(path) as ds:
            ds = ds.load()
    except (OSError, ValueError, RuntimeError, KeyError, TypeError):  # by engine and format
        raise ValueError(f"--map: {str(map)!r} is not a netCDF file that xarray can read; a "
                         "map is a .nc file written by `map build`") from None
    return PullOffMap(_checked_map(ds, map))


def _checked_map(ds: xr.Dataset, map) -> xr.Dataset:
    """`ds` if it holds a map's axes (two or more values each) and P*; ValueError naming
    --map otherwise."""
    missing = [v for v in (*AXES, "P_star") if v not in ds.variables]
    if missing:
        raise ValueError(f"--map: {str(map)!r} is a netCDF file but not a pull-off map (it has "
                         f"no {', '.join(missing)}); a map is written by `map build`")
    short = [f"{a} has {ds[a].size} value" for a in AXES if ds[a].size < 2]
    if short:
        raise ValueError(f"--map: {str(map)!r}: {'; '.join(short)}: a map interpolates along "
                         "each of t_over_R, h_over_R and gamma_hat: two or more values each")
    return ds


MAP_AXES = ("t_over_R", "h_over_R", "gamma_J_m2")     # the study factors a map spans


def _values(study: Study, factor: str) -> list:
    """The distinct values a study gives a factor (its grid, its sweeps and its base)."""
    given = set(study.grid.get(factor, ())) | set(study.sweeps.get(factor, ()))
    if factor in study.base:
        given.add(study.base[factor])
    return sorted(given)


def check_map_study(study: Study):
    """StudyError (one line naming the field) unless the study spans a map that can be
    interpolated: two or more values of each axis in its grid, and one C10."""
    for axis in MAP_AXES:
        values = _values(study, axis)
        if len(values) < 2 or axis not in study.grid:
            where = f"grid.{axis}" if axis in study.grid else axis
            raise StudyError(f"{where}: {', '.join(f'{v:g}' for v in values) or 'no value'}: "
                             "a map interpolates along t_over_R, h_over_R and gamma_J_m2: "
                             "give each two or more values in the grid")
    C10 = _values(study, "C10_MPa")
    if len(C10) > 1:
        raise StudyError(f"C10_MPa: {', '.join(f'{v:g}' for v in C10)}: a map is made at one "
                         "C10 (it is dimensionless: gamma/(C10 R) spans it)")


def build_pull_off_map(study, out_nc, **run_options) -> Path:
    """Run `study` (a YAML file or dict: one C10, a grid over t_over_R, h_over_R and
    gamma_J_m2, two or more values each: `check_map_study`) with `run_study` and write its
    map to `out_nc` (netCDF); the cube, tables and figures go to ``run_options['out']``
    (default: beside `out_nc`).  Returns the map's path."""
    from shell_adhesion.study.run import run_study      # dask only when building
    # the grid is checked before anything is created (run_study reads the study again)
    check_map_study(validate(study) if isinstance(study, dict) else load_study(study))
    out_nc = Path(out_nc)
    run_options.setdefault("out", out_nc.parent / f"{out_nc.stem}_study")
    ds = map_from_cube(run_study(study, **run_options))
    out_nc.parent.mkdir(parents=True, exist_ok=True)
    tmp = out_nc.with_suffix(".nc.part")
    ds.to_netcdf(tmp)
    tmp.replace(out_nc)
    return out_nc
