"""The adhesive edge force of a held set whose nodes slide (frictionless; DESIGN.md
section 10).

A held set relaxed with free sliding is a shear-free contact disc of radius r, the deformed
radius of its outermost held node, and its total potential carries -gamma pi r^2.  At a
fixed held set that term pulls the edge node outward: residual -2 pi gamma r on its radial
dof (the full circle, units of C10 R^2), tangent -2 pi gamma.  On that one node the force
is a zero-range interface's line force, whose displacement is log-singular, so where it
sits is part of the model (docs/theory.md).  `width` > 0 spreads it: the covered area is
then pi <r^2>, the mean of r^2 over the outer surface's last `width` of reference arc
inside the edge (uniform weight, integrated with the Q2 shape functions: the consistent
nodal loads of an even line load), so node i carries 2 pi gamma w_i r_i with sum w_i = 1
(the width of a cohesive zone regularises the same line force).

To second order in gamma (`area_compliance`): at a fixed held set and delta, the state
of gamma moves from the gamma-free one by gamma K^-1 g (K the tangent of the free dofs, g
= dA/dx = 2 pi w_i r_i on the carriers' radial dofs), so with c = g . K^-1 g the covered
area is A + gamma c and the total potential U_E - gamma A - gamma^2 c / 2 (the energy
method's second order: shell_adhesion.energy).
Dimensionless: gamma / (C10 R), r / R, arc / R, energies / (C10 R^3).
"""
from dataclasses import dataclass, replace
import math

import numpy as np


@dataclass(frozen=True, eq=False)
class EdgeAdhesion:
    """-gamma pi sum_i w_i r_i^2 of the held edge: `dofs` the radial dofs of the nodes that
    carry it, `r0` their reference radii, `weights` their shares (sum 1)."""

    dofs: np.ndarray
    r0: np.ndarray
    weights: np.ndarray
    gamma: float

    @property
    def dof(self) -> int:
        """The radial dof of the edge node itself (the outermost carrier)."""
        return int(self.dofs[-1])

    def radius(self, x) -> float:
        """The covered radius sqrt(<r^2>) / R (the edge node's radius without spreading)."""
        r = self.r0 + np.asarray(x)[self.dofs]
        return float(np.sqrt(self.weights @ r ** 2))

    def slope(self, x, dx) -> float:
        """d radius along dx (e.g. dx/ddelta)."""
        r = self.r0 + np.asarray(x)[self.dofs]
        return float(self.weights @ (r * np.asarray(dx)[self.dofs]) / self.radius(x))

    def gradient(self, x) -> np.ndarray:
        """d(covered area pi <r^2>)/dx on `dofs`: 2 pi w_i r_i (units of R)."""
        return 2 * math.pi * self.weights * (self.r0 + np.asarray(x)[self.dofs])

    def energy(self, x) -> float:
        return -self.gamma * math.pi * self.radius(x) ** 2

    def add_residual(self, x, r):
        r = np.array(r, dtype=float)
        r[self.dofs] -= self.gamma * self.gradient(x)
        return r

    def add_tangent(self, K):
        """K with -2 pi gamma w_i on the carriers' diagonal entries (in the FE pattern), in
        place."""
        for dof, w in zip(self.dofs, self.weights):
            lo, hi = K.indptr[dof], K.indptr[dof + 1]
            K.data[lo + int(np.flatnonzero(K.indices[lo:hi] == dof)[0])] -= \
                2 * math.pi * self.gamma * w
        return K


def spread_weights(arc: np.ndarray, edge: int, width: float) -> np.ndarray:
    """Shares w_i (sum 1) of the outer nodes 0..edge (reference arc / R from the apex,
    Q2 elements: corners at even indices) of an even line load over the arc
    [arc[edge] - width, arc[edge]] (clipped at the apex); width 0: the edge node alone."""
    arc = np.asarray(arc, dtype=float)
    w = np.zeros(edge + 1)
    if not width > 0:
        w[edge] = 1.0
        return w
    lo, hi = max(arc[edge] - width, 0.0), arc[edge]
    points, gauss = np.polynomial.legendre.leggauss(3)      # exact on quadratics
    for first in range(0, edge, 2):                         # element: first, first+1, first+2
        s0, s2 = arc[first], arc[first + 2]
        a, b = max(lo, s0), min(hi, s2)
        if b <= a:
            continue
        s = 0.5 * (a + b) + 0.5 * (b - a) * points
        xi = 2 * (s - s0) / (s2 - s0) - 1                   # nodes at xi -1, 0, 1
        N = np.array([xi * (xi - 1) / 2, 1 - xi ** 2, xi * (xi + 1) / 2])
        w[first:first + 3] += N @ (0.5 * (b - a) * gauss) / (hi - lo)
    return w


def outer_arc(capmesh) -> np.ndarray:
    """Reference arc / R of the outer nodes from the apex (the outer surface is the unit
    sphere through the apex)."""
    r, z = capmesh.nodes[:, capmesh.outer]
    return np.arctan2(r, 1.0 - z)


def carriers(d, held, gamma: float = 1.0, width: float = 0.0) -> EdgeAdhesion:
    """The edge adhesion of the held set `held` (outer node indices) on the discretisation
    `d`, gamma / (C10 R), spread over `width` of arc / R inside the edge (0: on the edge
    node)."""
    if not (math.isfinite(width) and width >= 0):
        raise ValueError(f"edge width: {width!r} must be a finite number >= 0 (arc / R)")
    cm = d.capmesh
    edge = max(held)
    if width > 0 and not cm.outer_corner[edge]:
        raise ValueError("edge width: a spread edge force needs a held set ending on an "
                         "element corner")
    w = spread_weights(outer_arc(cm), edge, width)
    on = np.flatnonzero(w != 0)     # a corner of a partly loaded element: < 0
    nodes = cm.outer[on]
    return EdgeAdhesion(np.array([int(d.ur(n)) for n in nodes]),
                        cm.nodes[0, nodes].astype(float), w[on], float(gamma))


def with_edge(d, held, gamma: float, width: float = 0.0):
    """The discretisation `d` with the edge force of the held set `held` (outer node
    indices) for gamma / (C10 R) > 0, spread over `width` of arc / R inside the edge (0:
    on the edge node); `d` itself for gamma = 0."""
    if not gamma > 0:
        return d
    return replace(d, edge=carriers(d, held, gamma, width))
