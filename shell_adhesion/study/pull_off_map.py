"""Pull-off maps: built by a study, shipped with the package, opened by name or file.

`build_pull_off_map` runs a study over t/R x h/R x gamma (one C10; the catalogue, dask and
the error bars of any study) and writes the dimensionless map beside its cube;
`pull_off_map` opens a shipped map or a map file.  Shipped: ``default`` (default mesh,
`no_slip`, neo-Hookean; its study is `shell_adhesion/data/pull_off_map.yaml`) and
``coarse`` (the same grid on the coarse mesh, `pull_off_map_coarse.yaml`).  The
interpolant itself is `shell_adhesion.analysis.pull_off_map`.
"""
from pathlib import Path

from shell_adhesion.analysis.pull_off_map import PullOffMap, map_from_cube
from shell_adhesion.examples import DATA

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
    return PullOffMap.open(map_path(map))


def build_pull_off_map(study, out_nc, **run_options) -> Path:
    """Run `study` (a YAML file or dict: one C10, a grid over t_over_R, h_over_R and
    gamma_J_m2) with `run_study` and write its map to `out_nc` (netCDF); the cube, tables
    and figures go to ``run_options['out']`` (default: beside `out_nc`).  Returns the map's
    path."""
    from shell_adhesion.study.run import run_study      # dask only when building
    out_nc = Path(out_nc)
    run_options.setdefault("out", out_nc.parent / f"{out_nc.stem}_study")
    ds = map_from_cube(run_study(study, **run_options))
    out_nc.parent.mkdir(parents=True, exist_ok=True)
    tmp = out_nc.with_suffix(".nc.part")
    ds.to_netcdf(tmp)
    tmp.replace(out_nc)
    return out_nc
