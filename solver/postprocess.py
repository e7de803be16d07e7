"""Fields for plots: deformed profiles and von Mises stress (units of R and C10)."""
import numpy as np

from .forms import Discretisation, deformation
from .material import cauchy_stress, von_mises


def deformed_nodes(d: Discretisation, x):
    """Deformed (r, z) of every Q2 node, shape (2, n2)."""
    return d.capmesh.nodes + np.stack([x[: d.n2], x[d.n2: 2 * d.n2]])


def profiles(d: Discretisation, x):
    """Deformed outer and inner surfaces as (r, z) arrays ordered from the axis.

    The inner profile is empty for a solid cap.
    """
    cm = d.capmesh
    p = deformed_nodes(d, x)
    inner = cm.inner
    if len(inner):
        r0, z0 = cm.nodes[:, inner]
        inner = inner[np.argsort(np.arctan2(r0, 1.0 - z0))]
    return p[:, cm.outer], p[:, inner]


def von_mises_field(d: Discretisation, x):
    """Von Mises stress / C10 at the quadrature points with their deformed (r, z).

    Returns (r, z, sigma_vm), each of shape (E, Q).
    """
    f, p = deformation(d, x)
    sigma = cauchy_stress(f, p)
    xe = x[d.edofs[:18]]
    N = d.B[4, :9] * d.r_q[None]          # Q2 shape functions (B carries N / r in row 4)
    ur = np.einsum("aeq,ae->eq", N, xe[:9])
    uz = np.einsum("aeq,ae->eq", N, xe[9:18])
    return d.r_q + ur, d.z_q + uz, von_mises(sigma)
