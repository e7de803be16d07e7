"""The rigid lid that closes a shell's cavity at its rim, as a contact for the inner surface.

The lid is the plane of the rim's inner edge (it moves with the held rim face, whose u_z is
-delta).  A point of the deformed inner surface above it penetrates: its gap

    g = (Z_rim + u_z,rim) - z     (units of R; > 0 below the lid, clear of it)

is pushed back by the contact penalty of the plane (`penalty.penalty`: slope
CONTACT_STIFFNESS C10 / R, rising from 0 over the first CONTACT_ONSET R of penetration),
integrated over the reference inner surface (3 Gauss points per Q2 edge, weight 2 pi R dS).
The energy sum_q w phi(g_q) is exact in u (g is linear in it), so the contact is
conservative and the energy method's balance holds with it.  Where nothing reaches the lid
it adds exactly nothing.  Its tangent couples every inner node's u_z with the rim's, which
share no element: `lid_of` extends the FE pattern (`forms.with_couplings`).

Units: lengths / R, energies / (C10 R^3), forces / (C10 R^2).  Pure functions.
"""
from dataclasses import dataclass

import numpy as np

from .edge_quadrature import DN as _DN, GAUSS_W as _GAUSS_W, GAUSS_X as _GAUSS_X, N as _N
from .forms import block_slots, with_couplings
from .penalty import CONTACT_ONSET, CONTACT_STIFFNESS, penalty

LID_THROUGH = 10 * CONTACT_ONSET   # a penetration beyond this is a failure, not a contact (it
#                                    would carry a contact pressure of 9.5 C10)

_DG = np.concatenate([-_N, np.ones((len(_GAUSS_X), 1))], axis=1)   # (Q, 4): dg / du


@dataclass(frozen=True, eq=False)
class Lid:
    """The lid's contact on the inner-surface edges of one discretisation."""

    dofs: np.ndarray     # (E, 4) u_z of each edge's 3 nodes, then the rim's u_z
    Z0: np.ndarray       # (E, 3) reference z of the edge nodes
    Z_rim: float         # reference z of the rim's inner edge (the lid's plane at delta 0)
    w: np.ndarray        # (E, Q) 2 pi R dS times the Gauss weight, reference
    slots: np.ndarray    # (E, 16) positions of the (4 x 4) edge blocks in the CSR data
    stiffness: float = CONTACT_STIFFNESS
    onset: float = CONTACT_ONSET

    def gaps(self, x) -> np.ndarray:
        """g / R at the Gauss points (E, Q): the lid's height above each point."""
        u = x[self.dofs]
        return (self.Z_rim + u[:, 3:4]) - (self.Z0 + u[:, :3]) @ _N.T

    def penetration(self, x) -> float:
        """The deepest penetration / R of the inner surface into the lid (0 if none)."""
        return float(max(0.0, -self.gaps(x).min()))

    def through(self, x) -> bool:
        """Whether the inner surface of state x has passed the lid by more than
        LID_THROUGH: not an equilibrium the contact can vouch for (its penalty failed)."""
        return self.penetration(x) > LID_THROUGH

    def energy(self, x) -> float:
        """The penalty's energy / (C10 R^3) in state x."""
        return float(np.sum(self.w * penalty(self.gaps(x), self.stiffness, self.onset)[0]))

    def _in_contact(self, x):
        """(edges with a point above the lid, w dphi/dg and w d2phi/dg2 there (E_c, Q))."""
        g = self.gaps(x)
        edges = np.flatnonzero((g < 0.0).any(axis=1))
        _, stress, slope = penalty(g[edges], self.stiffness, self.onset)
        return edges, stress * self.w[edges], slope * self.w[edges]

    def add_residual(self, x, r):
        """r plus the lid's forces dE/dx (a copy; r itself where nothing touches)."""
        edges, s, _ = self._in_contact(x)
        return self._with_forces(r, edges, s)

    def _with_forces(self, r, edges, s):
        if not len(edges):
            return r
        r = r.copy()
        np.add.at(r, self.dofs[edges].ravel(), (s @ _DG).ravel())
        return r

    def add_tangent(self, K, r, x):
        """(K, r) plus the lid's forces and stiffness d2E/dx2 (K's pattern: `lid_of`)."""
        edges, s, k = self._in_contact(x)
        if not len(edges):
            return K, r
        r = self._with_forces(r, edges, s)
        data = K.data.copy()
        np.add.at(data, self.slots[edges].ravel(),
                  np.einsum("eq,qa,qb->eab", k, _DG, _DG).ravel())
        return type(K)((data, K.indices, K.indptr), shape=K.shape), r


def own_lid(d):
    """The Lid of the shell's own cavity in `d` (its cavity bound alone or beside a
    pocket: solver.pocket), None without one."""
    load = getattr(d.cavity, "shell", d.cavity)
    return getattr(load, "lid", None)


def lid_of(d, nodes: np.ndarray):
    """(d with its pattern extended, Lid) for the inner-surface edges `nodes` (E, 3),
    ordered from the apex to the rim (the last node is the rim's inner edge)."""
    cm = d.capmesh
    rim = int(nodes[-1, 2])
    uz = d.n2 + nodes
    inner = np.unique(uz)
    d = with_couplings(d, inner, np.full(len(inner), d.n2 + rim))
    dofs = np.concatenate([uz, np.full((len(nodes), 1), d.n2 + rim)], axis=1)
    R0, Z0 = cm.nodes[0, nodes], cm.nodes[1, nodes]
    dS = np.hypot(R0 @ _DN.T, Z0 @ _DN.T)                      # |dX / dxi| (E, Q)
    w = 2 * np.pi * (R0 @ _N.T) * dS * _GAUSS_W
    return d, Lid(dofs, Z0, float(cm.nodes[1, rim]), w, block_slots(d, dofs))
