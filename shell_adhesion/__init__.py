"""shell-adhesion: adhesion and pull-off of a soft hyperelastic spherical-cap shell on a
rigid plane (axisymmetric finite elements and Maugis' energy method).

Subpackages: `shell_adhesion.solver` (one shell, pure computation, dimensionless inside),
`shell_adhesion.study` (parameter studies on dask, the results cube, the command line),
`shell_adhesion.catalogue` (the store of solved path sets).
"""
from .solver import __version__

__all__ = ["__version__"]
