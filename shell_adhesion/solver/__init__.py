"""shell-adhesion solver: one soft spherical-cap shell on a rigid plane (pure computation).

Public entry points (dimensionless inside, see `solver.scaling` for units):
`solve_paths` (loading + relaxation paths of one shell), `PathSet.pull_off`,
`solver.theory` (Hertz, JKR, eq. 3), `solver.geometry.check_cap` / `check_delta_max` /
`check_gamma` (the supported domain), `solver.quality` (element quality of a state),
`Material` (the solid).
"""
from .case import (GAMMA_MAX, PathSet, Relaxation, relaxation_starts, relaxation_task,
                   solve_loading, solve_paths)
from .contact import INTERFACES
from .geometry import Cap, check_cap, check_delta_max, check_gamma
from shell_adhesion.errors import InputError
from .material import MODELS, NEO_HOOKE, Material
from .path import Settings
from shell_adhesion.errors import ConvergenceError, MaterialLimitError, QualityError

__version__ = "0.1.0"
__all__ = ["GAMMA_MAX", "PathSet", "Relaxation", "relaxation_starts", "relaxation_task",
           "solve_loading", "solve_paths", "INTERFACES", "Cap", "InputError", "check_cap",
           "check_delta_max", "check_gamma", "ConvergenceError", "MaterialLimitError",
           "QualityError", "Settings",
           "MODELS", "NEO_HOOKE", "Material", "__version__"]
