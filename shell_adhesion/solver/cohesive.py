"""Finite-range (cohesive, Maugis-Dugdale) adhesion of the outer surface to the plane z = 0.

Units as the rest of the solver: lengths / R, stresses / C10, gamma / (C10 R), energies
/ (C10 R^3), forces / (C10 R^2).  The gap g of a point of the deformed outer surface is its
height z above the plane.

The interface is conservative: its energy is

    Pi = integral over the deformed outer surface of phi(g) 2 pi r dr,

dr the deformed radial extent (the area projected on the plane), phi(0) = -gamma and
phi = 0 beyond the range.  Its first variation is a pressure phi'(g) = sigma(g) >= 0 on the
deformed surface along its normal (attractive: it pulls the surface towards the plane);
the z force per unit plane area is sigma(g).

Non-penetration is part of the same law: below g = 0 the plane pushes back with a stiff
penalty of slope k (`stiffness`, default PENALTY sigma0 / delta_c, so a contact pressure
of 10 sigma0 penetrates by about 1e-2 delta_c), its slope rising from 0 over the first
PENALTY_ONSET delta_c of penetration.  The interface stress -sigma
(> 0 compression) is then continuous, the contact radius a is where g crosses 0 and the
cohesive zone ends where g reaches delta_c: there are no contact events (node-wise
unilateral contact of the Q2 surface chatters: a corner node held at the contact edge
carries a tensile reaction under a compressive pressure).  The law is normal only: it
carries no shear (frictionless contact; `solver.arclength` holds touching nodes radially
for no_slip).

The law is Dugdale's (sigma = sigma0 for g < delta_c = gamma / sigma0, then 0) with the
step replaced by a cubic smooth-step of width w = `ramp` delta_c centred on delta_c:

    sigma = sigma0 + penalty(g)             g <= delta_c - w/2
    sigma = sigma0 (1 - 3 u^2 + 2 u^3)      u = (g - delta_c + w/2) / w in (0, 1)
    sigma = 0                               g >= delta_c + w/2

so the peak sigma0 and the work of separation gamma are Dugdale's exactly, and sigma and
its slope are continuous (Newton converges).  ramp -> 0 is Dugdale's law.
"""
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .forms import Discretisation

# the Tabor-Maugis parameters supported: DMT-like 0.05 to 3.  A path must resolve the
# cohesive zone at its contact edge, (m - 1) / m of the contact radius at a sphere's
# pull-off (Maugis): 1/15 at lambda = 3, 1/40 at 5; the base shell at lambda = 3 with four
# elements across it traces 1630 states (8.2 minutes), and the states grow as 1 / (m - 1),
# beyond the continuation's 3000 (arclength.ArcSettings.max_steps) well before lambda = 5
TABOR_RANGE = (0.05, 3.0)
# the penalty's slope in sigma0 / delta_c.  1e4 gave the base shell (lambda 1, default mesh)
# P* 0.09 % and a* 0.7 % smaller in 1.7 times as many Newton iterations (benchmarks/
# cohesive_speed.py); both well inside the mesh's error bars
PENALTY = 1e3
PENALTY_ONSET = 1e-3     # the penalty's slope rises over this fraction of delta_c
GAUSS_POINTS = 8        # per quadratic edge: the smooth-step spans part of an edge


@dataclass(frozen=True)
class CohesiveLaw:
    """Smoothed Dugdale law: peak stress sigma0 / C10, work of separation gamma / (C10 R),
    smooth-step width `ramp` (a fraction of delta_c, 0 < ramp <= 1), penalty `stiffness`
    below g = 0 (C10 / R; None: PENALTY sigma0 / delta_c)."""

    sigma0: float
    gamma: float
    ramp: float = 0.5
    stiffness: float = None

    def __post_init__(self):
        for name in ("sigma0", "gamma", "ramp", "stiffness"):
            v = getattr(self, name)
            if not (v is None and name == "stiffness" or np.isfinite(v) and v > 0):
                raise ValueError(f"cohesive law: {name} = {v!r} must be a finite number > 0")
        if self.stiffness is None:
            object.__setattr__(self, "stiffness", PENALTY * self.sigma0 / self.delta_c)
        if self.ramp > 1:
            raise ValueError(f"cohesive law: ramp = {self.ramp!r} must be <= 1")

    @property
    def delta_c(self) -> float:
        """Dugdale's range gamma / sigma0 (units of R)."""
        return self.gamma / self.sigma0

    @property
    def reach(self) -> float:
        """Gap beyond which the traction is exactly zero."""
        return self.delta_c * (1 + 0.5 * self.ramp)

    def __call__(self, g):
        """(phi, sigma = phi', dsigma/dg = phi'') at the gaps g."""
        g = np.asarray(g, dtype=float)
        w = self.ramp * self.delta_c
        g1 = self.delta_c - 0.5 * w
        u = np.clip((g - g1) / w, 0.0, 1.0)
        s0 = self.sigma0
        phi = np.where(g <= g1, -self.gamma + s0 * g,
                       -self.gamma + s0 * (g1 + w * (u - u ** 3 + 0.5 * u ** 4)))
        sigma = s0 * (1 - 3 * u ** 2 + 2 * u ** 3)
        dsigma = -6 * s0 / w * (u - u ** 2)
        pen = self._penalty(g)
        return phi + pen[0], sigma + pen[1], dsigma + pen[2]

    def _penalty(self, g):
        """(energy, stress, slope) of the penalty: slope k (g < -e), rising linearly from
        0 at g = 0 over -e < g < 0, e = PENALTY_ONSET delta_c (a continuous slope: Newton
        does not cycle on points that touch)."""
        k, e = self.stiffness, PENALTY_ONSET * self.delta_c
        h = np.clip(g, -e, 0.0)
        deep = np.minimum(g + e, 0.0)
        energy = -k * h ** 3 / (6 * e) + k * (deep * (deep / 2 - e / 2))
        stress = -k * h ** 2 / (2 * e) + k * deep
        slope = np.where(g < -e, k, -k * h / e)
        return energy, stress, slope


@dataclass(frozen=True, eq=False)
class Interface:
    """The cohesive law bound to the outer surface of a discretisation."""

    d: Discretisation
    law: CohesiveLaw

    @cached_property
    def edges(self) -> np.ndarray:
        """(3, n_edges) Q2 node indices of the outer edges, from the apex outwards."""
        outer = self.d.capmesh.outer
        k = np.arange(0, len(outer) - 2, 2)
        return np.stack([outer[k], outer[k + 1], outer[k + 2]])

    @cached_property
    def _quadrature(self):
        xi, w = np.polynomial.legendre.leggauss(GAUSS_POINTS)
        N = np.stack([0.5 * xi * (xi - 1), 1 - xi ** 2, 0.5 * xi * (xi + 1)])
        dN = np.stack([xi - 0.5, -2 * xi, xi + 0.5])
        return N, dN, w

    @cached_property
    def dofs(self) -> np.ndarray:
        """(6, n_edges) global dofs of each edge: u_r of its 3 nodes, then u_z."""
        return np.vstack([self.d.ur(self.edges), self.d.uz(self.edges)])

    @cached_property
    def slots(self) -> np.ndarray:
        """(6, 6, n_edges) positions of the edge matrices in the tangent's CSR data."""
        d = self.d
        rows = np.broadcast_to(self.dofs[:, None, :], (6, 6, self.dofs.shape[1]))
        cols = np.broadcast_to(self.dofs[None, :, :], rows.shape)
        indptr, indices = d.csr_indptr, d.csr_indices
        out = np.empty(rows.shape, dtype=np.int64)
        for idx in np.ndindex(*rows.shape):
            i, j = rows[idx], cols[idx]
            lo, hi = indptr[i], indptr[i + 1]
            k = lo + np.searchsorted(indices[lo:hi], j)
            if k >= hi or indices[k] != j:
                raise ValueError("a cohesive edge entry is outside the FE tangent pattern")
            out[idx] = k
        return out

    def _points(self, x):
        """Deformed r, z, dr/dxi at the quadrature points, (n_edges, Q) each."""
        cm = self.d.capmesh
        N, dN, _ = self._quadrature
        r_n = cm.nodes[0, self.edges] + x[self.d.ur(self.edges)]     # (3, n_edges)
        z_n = cm.nodes[1, self.edges] + x[self.d.uz(self.edges)]
        return r_n.T @ N, z_n.T @ N, r_n.T @ dN

    def energy(self, x) -> float:
        """Pi / (C10 R^3)."""
        r, z, dr = self._points(x)
        phi = self.law(z)[0]
        return float(2 * np.pi * np.sum(phi * r * dr * self._quadrature[2]))

    def residual(self, x) -> np.ndarray:
        """dPi/dx (units of C10 R^2), a full-length vector."""
        return np.bincount(self.dofs.ravel(), weights=self._element(x, False)[0].ravel(),
                           minlength=self.d.ndof)

    def add(self, x, K, r):
        """(K + d2Pi/dx2, r + dPi/dx): K the CSR FE tangent (pattern kept, a new matrix)."""
        f, k = self._element(x, True)
        r = r + np.bincount(self.dofs.ravel(), weights=f.ravel(), minlength=self.d.ndof)
        K = K.copy()
        np.add.at(K.data, self.slots.ravel(), k.ravel())
        return K, r

    def _element(self, x, with_tangent):
        """Edge vectors (6, n_edges) and matrices (6, 6, n_edges)."""
        N, dN, w = self._quadrature
        r, z, dr = self._points(x)
        phi, sig, dsig = self.law(z)
        c = 2 * np.pi * w                                   # (Q,)
        # d/dr_a: phi (N_a r' + r N_a'); d/dz_a: sigma N_a r r'
        fr = np.einsum("eq,aq->ae", c * phi * dr, N) + np.einsum("eq,aq->ae", c * phi * r, dN)
        fz = np.einsum("eq,aq->ae", c * sig * r * dr, N)
        f = np.vstack([fr, fz])
        if not with_tangent:
            return f, None
        k = np.empty((6, 6) + r.shape[:1])
        NdN = np.einsum("aq,bq->abq", N, dN)
        k[:3, :3] = np.einsum("eq,abq->abe", c * phi, NdN + NdN.transpose(1, 0, 2))
        # d2/dr_a dz_b: sigma N_b (N_a r' + r N_a')
        rz = (np.einsum("eq,aq,bq->abe", c * sig * dr, N, N)
              + np.einsum("eq,aq,bq->abe", c * sig * r, dN, N))
        k[:3, 3:] = rz
        k[3:, :3] = rz.transpose(1, 0, 2)
        k[3:, 3:] = np.einsum("eq,aq,bq->abe", c * dsig * r * dr, N, N)
        return f, k


def total(iface: Interface, x):
    """(K, r) of the FE solid plus the cohesive interface at x (forms.tangent's units)."""
    from .forms import tangent
    K, r = tangent(iface.d, x)
    return iface.add(x, K, r)
