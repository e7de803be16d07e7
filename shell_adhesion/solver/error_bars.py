"""Discretisation error bars from two meshes of the same family (solver.mesh.LEVELS).

The value on a mesh and on the next coarser one (every size doubled) differ by about
(2^p - 1) times the error of the finer value, for a method of order p (Richardson).  With
an order assumed from the family's measured convergence, the estimate is Roache's grid
convergence index for two meshes:

    error = SAFETY * |f_h - f_2h| / (2^ORDER - 1)

Pure functions, any units (the error has the value's units); NaN where either value is.
"""
import numpy as np

ORDER = 1.0     # assumed: on the base shell the three meshes give no clean order (README)
SAFETY = 3.0    # Roache's factor for an order assumed, not observed per case


def error_bar(value, coarser_value):
    """The error estimate of `value` from the same quantity on the next coarser mesh."""
    value, coarser_value = np.asarray(value, dtype=float), np.asarray(coarser_value, dtype=float)
    return SAFETY * np.abs(value - coarser_value) / (2.0 ** ORDER - 1.0)


def curve_error(x, y, x_coarser, y_coarser):
    """Error of the curve y(x) at its points x from the coarser mesh's curve, linear
    between the coarser curve's points; NaN outside the coarser curve's range of x."""
    x, x_c, y_c = (np.asarray(v, dtype=float) for v in (x, x_coarser, y_coarser))
    if len(x_c) < 2:
        return np.full(np.shape(x), np.nan)
    order = np.argsort(x_c)
    at = np.interp(x, x_c[order], y_c[order], left=np.nan, right=np.nan)
    return error_bar(y, at)


def estimate() -> dict:
    """How the error bars are built (for provenance)."""
    return {"order": ORDER, "safety_factor": SAFETY, "refinement_ratio": 2.0}
