"""The adhesive edge force of a held set whose nodes slide (frictionless; DESIGN.md
section 10).

A held set relaxed with free sliding is a shear-free contact disc of radius r, the deformed
radius of its outermost held node, and its total potential carries -gamma pi r^2.  At a
fixed held set that term pulls the edge node outward: residual -2 pi gamma r on its radial
dof (the full circle, units of C10 R^2), tangent -2 pi gamma.  The force sits on that one
node, where the held zone ends (a zero-range interface); the displacement under a line
force is log-singular, so the choice is part of the model (docs/theory.md).
Dimensionless: gamma / (C10 R), r / R, energies / (C10 R^3).
"""
from dataclasses import dataclass, replace
import math

import numpy as np


@dataclass(frozen=True)
class EdgeAdhesion:
    """-gamma pi r^2 of the held edge: `dof` its radial dof, `r0` its reference radius."""

    dof: int
    r0: float
    gamma: float

    def radius(self, x) -> float:
        return self.r0 + float(x[self.dof])

    def energy(self, x) -> float:
        return -self.gamma * math.pi * self.radius(x) ** 2

    def add_residual(self, x, r):
        r = np.array(r, dtype=float)
        r[self.dof] -= 2 * math.pi * self.gamma * self.radius(x)
        return r

    def add_tangent(self, K):
        """K with -2 pi gamma on the edge's diagonal entry (in the FE pattern), in place."""
        lo, hi = K.indptr[self.dof], K.indptr[self.dof + 1]
        K.data[lo + int(np.flatnonzero(K.indices[lo:hi] == self.dof)[0])] -= \
            2 * math.pi * self.gamma
        return K


def with_edge(d, held, gamma: float):
    """The discretisation `d` with the edge force of the held set `held` (outer node
    indices) for gamma / (C10 R) > 0; `d` itself for gamma = 0."""
    if not gamma > 0:
        return d
    cm = d.capmesh
    node = cm.outer[max(held)]
    return replace(d, edge=EdgeAdhesion(int(d.ur(node)), float(cm.nodes[0, node]),
                                        float(gamma)))
