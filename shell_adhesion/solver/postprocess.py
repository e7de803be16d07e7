"""Fields for plots: deformed profiles and von Mises stress (units of R and C10).

`Profile` and `StressMap` are the few deformed states a path set keeps for figures (the
full solution vectors are not stored): profiles along loading and along the relaxation
of the largest contact radius, and stress maps at the end of loading and where that
relaxation passes delta = 0 (the paper's Fig. 2).
"""
from dataclasses import dataclass

import numpy as np
from skfem import CellBasis, ElementQuad1, ElementQuad2

from .forms import Discretisation, deformation
from .material import cauchy_stress, von_mises

N_PROFILES = 9          # profiles kept per path (loading and the widest relaxation)


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
    sigma = cauchy_stress(f, p, d.material)
    xe = x[d.edofs[:18]]
    N = d.B[4, :9] * d.r_q[None]          # Q2 shape functions (B carries N / r in row 4)
    ur = np.einsum("aeq,ae->eq", N, xe[:9])
    uz = np.einsum("aeq,ae->eq", N, xe[9:18])
    return d.r_q + ur, d.z_q + uz, von_mises(sigma)


def nodal_von_mises(d: Discretisation, x):
    """Von Mises stress / C10 at the Q2 nodes (n2,): the stress evaluated at each node in
    every element holding it, averaged over those elements (on the axis the hoop
    stretch u_r / r is taken as its limit d u_r / d r).  An element whose deformation
    gradient, extrapolated to a node, has J <= 0 there (a badly distorted element at a
    stress singularity such as the rim's inner corner) gives that node no value; a node
    with none is NaN."""
    mesh = d.capmesh.mesh
    at_nodes = (np.ascontiguousarray(ElementQuad2.doflocs.T), np.ones(9))
    bu = CellBasis(mesh, ElementQuad2(), quadrature=at_nodes)
    bp = CellBasis(mesh, ElementQuad1(), quadrature=at_nodes)
    ur, uz = x[d.edofs[:9]], x[d.edofs[9:18]]
    N = np.array([np.asarray(bu.basis[a][0]) for a in range(9)])       # (9, E, 9)
    dN = np.array([bu.basis[a][0].grad for a in range(9)])             # (9, 2, E, 9)
    r = bu.mapping.F(bu.X)[0]
    f = np.empty((5,) + r.shape)
    f[0] = 1 + np.einsum("aeq,ae->eq", dN[:, 0], ur)
    f[1] = np.einsum("aeq,ae->eq", dN[:, 1], ur)
    f[2] = np.einsum("aeq,ae->eq", dN[:, 0], uz)
    f[3] = 1 + np.einsum("aeq,ae->eq", dN[:, 1], uz)
    u_r = np.einsum("aeq,ae->eq", N, ur)
    on_axis = r < 1e-12
    f[4] = np.where(on_axis, f[0], 1 + u_r / np.where(on_axis, 1.0, r))
    Np = np.array([np.asarray(bp.basis[b][0]) for b in range(4)])
    p = np.einsum("beq,be->eq", Np, x[d.edofs[18:]])
    J = (f[0] * f[3] - f[1] * f[2]) * f[4]
    valid = J > 0
    f = np.where(valid, f, np.eye(5)[[0, 3, 4]].sum(axis=0)[:, None, None])  # identity there
    vm = np.where(valid, von_mises(cauchy_stress(f, p, d.material)), 0.0)  # (E, 9 nodes)
    nodes = d.edofs[:9].T                                               # (E, 9)
    total = np.bincount(nodes.ravel(), weights=vm.ravel(), minlength=d.n2)
    count = np.bincount(nodes.ravel(), weights=valid.ravel(), minlength=d.n2)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, total / count, np.nan)


def triangles(d: Discretisation):
    """Each Q2 element split into 8 triangles over its 9 nodes: (8 E, 3) node indices."""
    grid = {tuple(ij): k for k, ij in enumerate(np.rint(2 * ElementQuad2.doflocs).astype(int))}
    local = []
    for i in range(2):
        for j in range(2):
            a, b, c, e = grid[i, j], grid[i + 1, j], grid[i + 1, j + 1], grid[i, j + 1]
            local += [(a, b, c), (a, c, e)]
    return d.edofs[:9][np.array(local)].transpose(2, 0, 1).reshape(-1, 3)


@dataclass(frozen=True, eq=False)
class Profile:
    """Deformed outer and inner surfaces of one state, (2, n) arrays (r, z) / R from the
    axis; `stage` is "loading" or "relaxation" (at the fixed contact radius a)."""

    stage: str
    a: float
    delta: float
    P: float
    outer: np.ndarray
    inner: np.ndarray


@dataclass(frozen=True, eq=False)
class StressMap:
    """Deformed nodes (2, n2) / R, nodal von Mises stress / C10 (n2,) and the (T, 3)
    triangles over the nodes of one state."""

    stage: str
    a: float
    delta: float
    P: float
    nodes: np.ndarray
    von_mises: np.ndarray
    triangles: np.ndarray


def profile(d: Discretisation, state, stage: str) -> Profile:
    outer, inner = profiles(d, state.x)
    return Profile(stage, state.a, state.delta, state.P, outer, inner)


def stress_map(d: Discretisation, state, stage: str) -> StressMap:
    return StressMap(stage, state.a, state.delta, state.P, deformed_nodes(d, state.x),
                     nodal_von_mises(d, state.x), triangles(d))


def spread(states, n: int = N_PROFILES):
    """Up to n states evenly spaced in delta between the first and the last."""
    deltas = np.array([s.delta for s in states])
    targets = np.linspace(deltas[0], deltas[-1], n)
    picked = sorted({int(np.argmin(np.abs(deltas - t))) for t in targets})
    return [states[i] for i in picked]
