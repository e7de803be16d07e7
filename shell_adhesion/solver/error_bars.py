"""Discretisation error bars from meshes of the same family (solver.mesh.LEVELS).

The value on a mesh and on the next coarser one (every size doubled) differ by about
(2^p - 1) times the error of the finer value, for a method of order p (Richardson).

- Three meshes (f_h, f_2h, f_4h) that converge monotonically (the differences have one
  sign and shrink) give the observed order p = log2((f_4h - f_2h) / (f_2h - f_h)); within
  OBSERVED_ORDERS, and where both steps of the family refine every direction (a shell's
  element layers through its thickness grow at each step: `refines_through_thickness`),
  it is used with Roache's factor for an observed order, at most the assumed ORDER:
      error = SAFETY_OBSERVED * |f_h - f_2h| / (2^min(p, ORDER) - 1).
  A faster observed convergence is not credited: on these meshes the observed order falls
  as they refine (base shell P*: 1.54 from coarser-coarse-default, 1.19 from
  coarse-default-fine), and crediting 1.54 left the default mesh's bar at 0.83 of its
  distance to the extrapolated value; an order just inside or outside OBSERVED_ORDERS
  would also switch a bar by 100x on a 0.1 % change of a coarser value.
- Otherwise the grid convergence index with an assumed order 1 and factor 3,
      error = SAFETY * max(|f_h - f_2h|, |f_2h - f_4h| / 2^ORDER) / (2^ORDER - 1),
  the second term only with a third mesh: where the values cross (f_h - f_2h near 0
  between differences of either sign) the finer difference alone says nothing of the
  error, and the coarser one, carried to the finer mesh at the assumed order, bounds it.
  (Measured on t/R 0.02, h/R 0.2, gamma/(C10 R) 0.015: coarser, coarse, default, fine
  -0.065719, -0.065516, -0.065528, -0.065731 C10 R^2; with the finer difference alone the
  default mesh's error bar was 0.06 %, its distance to the fine mesh 0.31 %.)

A mesh with a single element layer through a shell (t/R below about 0.041 on the coarser
mesh) is outside the range where the error falls with the size: it does not enter a bar
(`coarsest_usable`; the callers then give two meshes), and the two-mesh bar of such a shell
assumes THIN_ORDER, not ORDER (`assumed_order`): its coarse mesh (2 layers) is not in the
asymptotic range either.  Measured on t/R 0.02, h/R 0.2 against a windowed 16-layer mesh
(P* [N] on 2, 4, 8, 16 layers; benchmarks/error_bars.py ... --window 0.98,1.4): at
gamma/(C10 R) 0.015 -7.87840, -7.88395, -7.89428, -7.90074 (steps -0.0055, -0.0103,
-0.0065: the first the smallest), at 0.03 -13.5916, -13.6170, -13.6395, -13.6537, at
0.005 -3.07726, -3.07537, -3.07769, -3.07937 (the first two cross); the last three give
orders 0.68, 0.67 and 0.47, and the bar 3 |f_h - f_2h| of order 1 was 0.6, 1.25 and 0.68
times the default mesh's distance to the extrapolated value: it did not bracket it at
0.015 and 0.005.  With order 2/3 (factor 3 / (2^(2/3) - 1) = 5.1 on the step) it is
1.03, 2.1 and 1.15 times (at 0.001, where the fine value lies past the 16-layer one, 1.7
times the distance to the latter).  The order-1 bars on t/R 0.02, h/R 0.2
(P* on 1, 2, 4, 8 layers; bar / distance of the default mesh to the fine one, with the
coarser mesh -> without; the order-2/3 bar is 1.70 times the latter): gamma/(C10 R) 0.001 (its own mesh) 20 -> 1.8, 0.005 1.02 ->
2.4, 0.015 5.0 -> 1.6, 0.03 3.4 -> 3.4; 0.001 on the mesh fitted to 0.03 28 -> 68 (there
the default mesh lies 0.012 % from the fine one, 1/24 of its own step: no two-mesh rule
sees that; that set relaxes corner fronts, whose values converge fast there, where 0.001
alone relaxes midside ones: docs/domain.md, "Which contact fronts").

The meshes must also relax the same kind of paths: contact fronts ending on element
corners and on midside nodes (solver.case.relaxation_starts) converge to one value from
different sides, so values of the two kinds measure no order (the thin shell R 15, t 1.5,
h 11.25 mm, C10 0.5 MPa, gamma 20 J/m^2, coarser, coarse, default P* [N]: corner -0.67742,
-0.68141, -0.68311; midside -0.66872, -0.67693, -0.68081, both order 1.1-1.2 toward
-0.6844; the larger kind of each mesh, midside, corner, midside, crossed and gave the
order-1 bar 0.019 N, 5.5 times the default mesh's error).  `rule` names the rule a value's
bar used.

Pure functions, any units (the error has the value's units); NaN where a value is.
"""
import numpy as np

from .mesh import LEVELS, mesh_spec, thickness_layers

ORDER = 1.0             # assumed: on the base shell the three meshes give no clean order
SAFETY = 3.0            # Roache's factor for an order assumed, not observed per case
SAFETY_OBSERVED = 1.25  # Roache's factor for an order observed on three meshes
OBSERVED_ORDERS = (0.5, 4.0)   # an observed order outside is not trusted
THIN_ORDER = 2.0 / 3.0  # assumed by a thin shell's two-mesh bar: the order its 4-, 8- and
#                         16-layer meshes show (t/R 0.02, h/R 0.2: 0.67, 0.68, 0.47; module doc)


def observed_order(value, coarser_value, coarsest_value, order_observable=True):
    """The order p observed on three meshes, NaN where they do not converge monotonically,
    p lies outside OBSERVED_ORDERS or the family's steps do not refine every direction
    (not `order_observable`: `refines_through_thickness`)."""
    if not order_observable:
        return np.full(np.shape(value), np.nan)
    f1, f2, f4 = (np.asarray(v, dtype=float) for v in (value, coarser_value, coarsest_value))
    e1, e2 = f2 - f1, f4 - f2
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.log2(e2 / e1)
    ok = (e1 * e2 > 0) & np.isfinite(p) & (p >= OBSERVED_ORDERS[0]) & (p <= OBSERVED_ORDERS[1])
    return np.where(ok, p, np.nan)


def refines_through_thickness(t_over_R: float, mesh: str, steps: int = 2) -> bool:
    """Whether each of the `steps` refinements of the family up to `mesh` adds element
    layers through a shell of thickness t/R (True for a solid cap, t/R >= 1).  A step that
    keeps the layers refines the meridian only: the differences of such steps measure no
    order (t/R 0.02: 1, 1, 2 layers on coarser, coarse, default)."""
    if t_over_R >= 1.0:
        return True
    names = {v: n for n, v in LEVELS.items()}
    level = LEVELS[mesh]
    if level - steps not in names:
        return False
    layers = [len(thickness_layers(t_over_R, mesh_spec(names[level - k]))) - 1
              for k in range(steps + 1)]
    return all(finer > coarser for finer, coarser in zip(layers, layers[1:]))


def coarsest_usable(t_over_R: float, mesh: str) -> bool:
    """Whether the mesh two levels coarser than `mesh` enters `mesh`'s error bar: not where
    it has a single element layer through a shell (t/R below about 0.041: solver.mesh
    THIN_LAYERS).  One layer is outside the range where the error falls with the element
    size (t/R 0.02, h/R 0.2, gamma/(C10 R) 0.001, P* [N] on 1, 2, 4, 8 layers: -0.64813,
    -0.64294, -0.64271, -0.64309: the one-layer step is 23 times the next and the default
    mesh's distance to the fine one 1.7 times its own step; with it the bar was 20 times
    that distance); such a bar uses two meshes."""
    if t_over_R >= 1.0:
        return True
    names = {v: n for n, v in LEVELS.items()}
    coarsest = names.get(LEVELS[mesh] - 2)
    return coarsest is not None and len(thickness_layers(t_over_R, mesh_spec(coarsest))) - 1 >= 2


def assumed_order(t_over_R: float, mesh: str) -> float:
    """The order a two-mesh bar of `mesh` assumes: THIN_ORDER where the mesh two levels
    coarser does not enter the bar (`coarsest_usable`: a thin shell, whose next coarser
    mesh is not in the asymptotic range either), else ORDER."""
    return ORDER if coarsest_usable(t_over_R, mesh) else THIN_ORDER


def error_bar(value, coarser_value, coarsest_value=None, order_observable=True, order=ORDER):
    """The error estimate of `value` from the same quantity on the next coarser mesh, and
    on the one after it if given (Richardson where those converge and
    `order_observable`, see `refines_through_thickness`; the module says how).  `order`:
    the order a bar from two meshes assumes (`assumed_order`)."""
    value, coarser_value = np.asarray(value, dtype=float), np.asarray(coarser_value, dtype=float)
    finer_step = np.abs(value - coarser_value)
    if coarsest_value is None:
        return SAFETY * finer_step / (2.0 ** order - 1.0)
    coarser_step = np.abs(coarser_value - np.asarray(coarsest_value, dtype=float))
    with np.errstate(invalid="ignore"):
        assumed = SAFETY * np.fmax(finer_step, coarser_step / 2.0 ** ORDER) / (2.0 ** ORDER - 1.0)
        assumed = np.where(np.isnan(finer_step), np.nan, assumed)
    p = observed_order(value, coarser_value, coarsest_value, order_observable)
    with np.errstate(invalid="ignore"):
        three = SAFETY_OBSERVED * finer_step / (2.0 ** np.fmin(p, ORDER) - 1.0)
    return np.where(np.isfinite(p), three, assumed)


def rule(value, coarser_value, coarsest_value=None, order_observable=True,
         order=ORDER) -> str:
    """Which rule `error_bar` uses for these values, in words: "observed order p = ...
    (factor 1.25)" (", used as 1" where p is above the assumed order), "order 1 assumed
    (factor 3)" (three meshes not converging
    monotonically, an order outside OBSERVED_ORDERS, or steps that do not refine every
    direction) or "order 1 assumed (factor 3), two meshes" (`order` in place of 1);
    "none" without a coarser value."""
    if not np.isfinite(float(value)) or not np.isfinite(float(coarser_value)):
        return "none"
    assumed = f"order {ORDER:g} assumed (factor {SAFETY:g})"
    if coarsest_value is None or not np.isfinite(float(coarsest_value)):
        return f"order {order:.3g} assumed (factor {SAFETY:g}), two meshes"
    p = float(observed_order(value, coarser_value, coarsest_value, order_observable))
    if np.isfinite(p):
        used = f", used as {ORDER:g}" if p > ORDER else ""
        return f"observed order p = {p:.3g}{used} (factor {SAFETY_OBSERVED:g})"
    return assumed


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
    return {"order": ORDER, "thin_shell_two_mesh_order": THIN_ORDER,
            "safety_factor": SAFETY, "refinement_ratio": 2.0,
            "observed_order_safety_factor": SAFETY_OBSERVED,
            "observed_orders": list(OBSERVED_ORDERS)}
