"""shell-adhesion solver: one soft spherical-cap shell on a rigid plane (pure computation).

Public entry points (dimensionless inside, see `solver.scaling` for units):
`solve_paths` (loading + relaxation paths of one shell), `PathSet.pull_off` (Maugis'
energy method, `shell_adhesion.energy`), `solver.geometry.check_cap` / `check_delta_max` /
`check_gamma` (the supported domain), `solver.quality` (element quality of a state),
`Material` (the solid).  The closed forms the solver is checked against (Hertz, JKR, eq. 3)
are in `shell_adhesion.theory`, its exceptions in `shell_adhesion.errors`.
"""
from shell_adhesion import __version__
from shell_adhesion.errors import ConvergenceError, InputError, MaterialLimitError, QualityError

from .case import (GAMMA_MAX, PathSet, Relaxation, relaxation_starts, relaxation_task,
                   solve_loading, solve_paths)
from .contact import INTERFACES
from .geometry import Cap, check_cap, check_delta_max, check_gamma
from .material import MODELS, NEO_HOOKE, Material
from .path import Settings

__all__ = ["GAMMA_MAX", "PathSet", "Relaxation", "relaxation_starts", "relaxation_task",
           "solve_loading", "solve_paths", "INTERFACES", "Cap", "InputError", "check_cap",
           "check_delta_max", "check_gamma", "ConvergenceError", "MaterialLimitError",
           "QualityError", "Settings",
           "MODELS", "NEO_HOOKE", "Material", "__version__"]
