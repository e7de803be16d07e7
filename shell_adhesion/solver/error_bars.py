"""Discretisation error bars from meshes of the same family (solver.mesh.LEVELS).

The value on a mesh and on the next coarser one (every size doubled) differ by about
(2^p - 1) times the error of the finer value, for a method of order p (Richardson).

- Three meshes (f_h, f_2h, f_4h) that converge monotonically (the differences have one
  sign and shrink) give the observed order p = log2((f_4h - f_2h) / (f_2h - f_h)); within
  OBSERVED_ORDERS it is used with Roache's factor for an observed order:
      error = SAFETY_OBSERVED * |f_h - f_2h| / (2^p - 1).
- Otherwise (two meshes, or three that do not converge monotonically, or an order outside
  OBSERVED_ORDERS): the grid convergence index with an assumed order 1 and factor 3,
      error = SAFETY * |f_h - f_2h| / (2^ORDER - 1).

Pure functions, any units (the error has the value's units); NaN where a value is.
"""
import numpy as np

ORDER = 1.0             # assumed: on the base shell the three meshes give no clean order
SAFETY = 3.0            # Roache's factor for an order assumed, not observed per case
SAFETY_OBSERVED = 1.25  # Roache's factor for an order observed on three meshes
OBSERVED_ORDERS = (0.5, 4.0)   # an observed order outside is not trusted


def observed_order(value, coarser_value, coarsest_value):
    """The order p observed on three meshes, NaN where they do not converge monotonically
    or p lies outside OBSERVED_ORDERS."""
    f1, f2, f4 = (np.asarray(v, dtype=float) for v in (value, coarser_value, coarsest_value))
    e1, e2 = f2 - f1, f4 - f2
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.log2(e2 / e1)
    ok = (e1 * e2 > 0) & np.isfinite(p) & (p >= OBSERVED_ORDERS[0]) & (p <= OBSERVED_ORDERS[1])
    return np.where(ok, p, np.nan)


def error_bar(value, coarser_value, coarsest_value=None):
    """The error estimate of `value` from the same quantity on the next coarser mesh, and
    on the one after it if given (Richardson where those converge; see the module)."""
    value, coarser_value = np.asarray(value, dtype=float), np.asarray(coarser_value, dtype=float)
    two = SAFETY * np.abs(value - coarser_value) / (2.0 ** ORDER - 1.0)
    if coarsest_value is None:
        return two
    p = observed_order(value, coarser_value, coarsest_value)
    with np.errstate(invalid="ignore"):
        three = SAFETY_OBSERVED * np.abs(value - coarser_value) / (2.0 ** p - 1.0)
    return np.where(np.isfinite(p), three, two)


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
    return {"order": ORDER, "safety_factor": SAFETY, "refinement_ratio": 2.0,
            "observed_order_safety_factor": SAFETY_OBSERVED,
            "observed_orders": list(OBSERVED_ORDERS)}
