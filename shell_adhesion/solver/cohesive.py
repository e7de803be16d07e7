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

Mixed mode (an option, `Interface.beta`; DESIGN.md section 10): the potential depends on
the gap g and on the radial slip s = r - r_a of the point from its anchor r_a (history,
per outer node, interpolated along the edge like r; the path following sets it, see
`anchors_at`) through one effective opening l:

    rho = sqrt(<g>^2 + beta^2 s^2 + eps^2),   rho0 = sqrt(<g>^2 + eps^2),
    l = g + rho - rho0,                       Phi = phi_D(l) + penalty(g),

phi_D the smoothed Dugdale potential above (continued with slope sigma0 below 0, as the
normal-only law is), eps = MIXED_EPS delta_c.  Where g > 0 and beta s >> eps, l = rho - eps
to within eps (DESIGN's effective opening); l = g wherever s = 0 or beta = 0, so beta = 0
(and any point that has not slipped) is the normal-only law exactly, its pull below the
plane included (DESIGN's l = rho - eps starts the normal traction from 0 at g = 0 and cannot
give that for any eps).  Phi(l -> inf) - Phi(0, 0) = gamma on every path: the toughness
does not depend on the mode mix; the peak tractions are sigma0 (normal) and beta sigma0
(shear, at g = 0, beta s >> eps).
"""
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from .forms import Discretisation, tangent_pattern
from .penalty import penalty

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
# the mixed-mode law's regulariser eps / delta_c (DESIGN.md: about 0.02): the shear
# traction rises to beta sigma0 over a slip of about eps / beta
MIXED_EPS = 0.02


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
        phi, sigma, dsigma = self.dugdale(g)
        pen = self._penalty(np.asarray(g, dtype=float))
        return phi + pen[0], sigma + pen[1], dsigma + pen[2]

    def dugdale(self, g):
        """(phi, sigma, dsigma/dg) of the smoothed Dugdale part alone (no penalty; below
        g = 0 it continues with slope sigma0)."""
        g = np.asarray(g, dtype=float)
        w = self.ramp * self.delta_c
        g1 = self.delta_c - 0.5 * w
        u = np.clip((g - g1) / w, 0.0, 1.0)
        s0 = self.sigma0
        phi = np.where(g <= g1, -self.gamma + s0 * g,
                       -self.gamma + s0 * (g1 + w * (u - u ** 3 + 0.5 * u ** 4)))
        sigma = s0 * (1 - 3 * u ** 2 + 2 * u ** 3)
        dsigma = -6 * s0 / w * (u - u ** 2)
        return phi, sigma, dsigma

    def _penalty(self, g):
        """(energy, stress, slope) of the penalty: slope k (g < -e), rising linearly from
        0 at g = 0 over -e < g < 0, e = PENALTY_ONSET delta_c (a continuous slope: Newton
        does not cycle on points that touch)."""
        return penalty(g, self.stiffness, PENALTY_ONSET * self.delta_c)


def mixed(law: CohesiveLaw, beta: float, g, s):
    """The mixed-mode potential (module docstring) at gaps g and slips s (units of R):
    (Phi, Phi_g, Phi_s, Phi_gg, Phi_gs, Phi_ss); Phi_g is the normal traction T_n
    (> 0 attractive, penalty included), Phi_s the shear traction T_t (opposes s)."""
    g, s = np.asarray(g, dtype=float), np.asarray(s, dtype=float)
    eps2 = (MIXED_EPS * law.delta_c) ** 2
    gp = np.maximum(g, 0.0)
    shear2 = beta * beta * s * s
    rho0 = np.sqrt(gp * gp + eps2)
    rho = np.sqrt(gp * gp + shear2 + eps2)
    l = g + (rho - rho0)
    l_g = 1.0 + (gp / rho - gp / rho0)
    l_s = beta * beta * s / rho
    # the second derivatives without the cancellation of 1 - g^2 / rho^2
    l_gg = np.where(g > 0, (shear2 + eps2) / rho ** 3 - eps2 / rho0 ** 3, 0.0)
    l_gs = -gp * l_s / (rho * rho)
    l_ss = beta * beta * (gp * gp + eps2) / rho ** 3
    phi, sig, dsig = law.dugdale(l)
    pe, ps, pk = law._penalty(g)
    return (phi + pe, sig * l_g + ps, sig * l_s, dsig * l_g * l_g + sig * l_gg + pk,
            dsig * l_g * l_s + sig * l_gs, dsig * l_s * l_s + sig * l_ss)


@dataclass(frozen=True, eq=False)
class Interface:
    """The cohesive law bound to the outer surface of a discretisation; `beta` (>= 0) the
    mixed-mode law's delta_c / delta_t (None: the normal-only law).  With beta the
    energy, forces and tangent take the anchors (`anchors_at`): deformed radii / R of the
    outer nodes (capmesh.outer's order) from which the slips are measured; they are
    history, passed with each call, never held here."""

    d: Discretisation
    law: CohesiveLaw
    beta: float = None

    def __post_init__(self):
        b = self.beta
        if b is not None and not (np.isfinite(b) and b >= 0):
            raise ValueError(f"cohesive interface: beta = {b!r} must be a finite number >= 0")

    def with_law(self, law) -> "Interface":
        """This interface with another law (same discretisation and beta), sharing the
        cached geometry and tangent slots."""
        new = replace(self, law=law)
        for name in ("edges", "edge_outer", "_quadrature", "dofs", "slots"):
            if name in self.__dict__:
                new.__dict__[name] = self.__dict__[name]
        return new

    @cached_property
    def edges(self) -> np.ndarray:
        """(3, n_edges) Q2 node indices of the outer edges, from the apex outwards."""
        outer = self.d.capmesh.outer
        k = np.arange(0, len(outer) - 2, 2)
        return np.stack([outer[k], outer[k + 1], outer[k + 2]])

    @cached_property
    def edge_outer(self) -> np.ndarray:
        """(3, n_edges) positions in capmesh.outer of each edge's nodes."""
        k = np.arange(0, len(self.d.capmesh.outer) - 2, 2)
        return np.stack([k, k + 1, k + 2])

    def radii(self, x) -> np.ndarray:
        """Deformed radii / R of the outer nodes (capmesh.outer's order)."""
        outer = self.d.capmesh.outer
        return self.d.capmesh.nodes[0, outer] + x[self.d.ur(outer)]

    def _slips(self, x, anchors):
        """Radial slips / R at the quadrature points, (n_edges, Q), from anchors per outer
        node (interpolated along the edge like r) or per quadrature point ((n_edges, Q),
        `point_anchors_at`)."""
        anchors = np.asarray(anchors, dtype=float)
        n_e, n_q = self.edges.shape[1], GAUSS_POINTS
        if anchors.shape == (n_e, n_q):
            return self._points(x)[0] - anchors
        if anchors.shape != (len(self.d.capmesh.outer),):
            raise ValueError(f"anchors: shape {anchors.shape} must be "
                             f"({len(self.d.capmesh.outer)},), one per outer node, or "
                             f"({n_e}, {n_q}), one per quadrature point")
        s_n = self.radii(x)[self.edge_outer] - anchors[self.edge_outer]
        return s_n.T @ self._quadrature[0]

    def _mixed(self, g, s):
        """The law's mixed potential and its derivatives (`mixed`'s tuple): the law's own
        `mixed(beta, g, s)` if it has one (snap.PenaltyContact: a sticking penalty),
        else the mixed-mode cohesive law."""
        own = getattr(self.law, "mixed", None)
        return own(self.beta, g, s) if own is not None else mixed(self.law, self.beta, g, s)

    def _history(self, anchors):
        """Check that anchors come with the mixed-mode law and only with it."""
        if (self.beta is None) != (anchors is None):
            raise ValueError("anchors: " + ("given to the normal-only law" if anchors is not None
                                            else f"needed by the mixed-mode law (beta = "
                                                 f"{self.beta:g})"))

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
        """(6, 6, n_edges) positions of the edge matrices in the tangent's CSR data (the
        FE pattern, bordered if the discretisation's load has an unknown)."""
        d = self.d
        rows = np.broadcast_to(self.dofs[:, None, :], (6, 6, self.dofs.shape[1]))
        cols = np.broadcast_to(self.dofs[None, :, :], rows.shape)
        indptr, indices = tangent_pattern(d)
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

    def energy(self, x, anchors=None) -> float:
        """Pi / (C10 R^3); `anchors` with the mixed-mode law only."""
        self._history(anchors)
        r, z, dr = self._points(x)
        phi = self.law(z)[0] if anchors is None else self._mixed(z, self._slips(x, anchors))[0]
        return float(2 * np.pi * np.sum(phi * r * dr * self._quadrature[2]))

    def residual(self, x, anchors=None) -> np.ndarray:
        """dPi/dx (units of C10 R^2), a full-length vector."""
        f = self._parts(x, anchors, False)[0]
        return np.bincount(self.dofs.ravel(), weights=f.ravel(), minlength=self.d.ndof)

    def add(self, x, K, r, anchors=None):
        """(K + d2Pi/dx2, r + dPi/dx): K the CSR FE tangent (pattern kept, a new matrix)."""
        f, k = self._parts(x, anchors, True)
        r = r + np.bincount(self.dofs.ravel(), weights=f.ravel(), minlength=self.d.ndof)
        K = K.copy()
        np.add.at(K.data, self.slots.ravel(), k.ravel())
        return K, r

    def _parts(self, x, anchors, with_tangent):
        self._history(anchors)
        if anchors is None:
            return self._element(x, with_tangent)
        return self._mixed_element(x, anchors, with_tangent)

    def _mixed_element(self, x, anchors, with_tangent):
        """Edge vectors and matrices of the mixed-mode law: the slip s = r - r_a moves
        with u_r as r does, so d/dr_a gains Phi_s N_a r r' and every r-derivative of
        Phi (N_a r' + r N_a') its Phi_s term."""
        N, dN, w = self._quadrature
        r, z, dr = self._points(x)
        Phi, Pg, Ps, Pgg, Pgs, Pss = self._mixed(z, self._slips(x, anchors))
        c = 2 * np.pi * w
        area = c * r * dr                                   # (e, q): 2 pi w r r'
        G = N[:, None, :] * dr[None] + dN[:, None, :] * r[None]     # d(r r')/dr_a
        fr = np.einsum("eq,aeq->ae", c * Phi, G) + np.einsum("eq,aq->ae", Ps * area, N)
        fz = np.einsum("eq,aq->ae", Pg * area, N)
        f = np.vstack([fr, fz])
        if not with_tangent:
            return f, None
        k = np.empty((6, 6) + r.shape[:1])
        NdN = np.einsum("aq,bq->abq", N, dN)
        sG = np.einsum("eq,aeq,bq->abe", c * Ps, G, N)
        k[:3, :3] = (np.einsum("eq,abq->abe", c * Phi, NdN + NdN.transpose(1, 0, 2))
                     + sG + sG.transpose(1, 0, 2)
                     + np.einsum("eq,aq,bq->abe", Pss * area, N, N))
        rz = (np.einsum("eq,aeq,bq->abe", c * Pg, G, N)
              + np.einsum("eq,aq,bq->abe", Pgs * area, N, N))
        k[:3, 3:] = rz
        k[3:, :3] = rz.transpose(1, 0, 2)
        k[3:, 3:] = np.einsum("eq,aq,bq->abe", Pgg * area, N, N)
        return f, k

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


def scaled(law: CohesiveLaw, factor: float) -> CohesiveLaw:
    """`law` with sigma0 and gamma times `factor` (> 0): the same range delta_c, smooth-step
    and penalty stiffness (the same contact); a small factor is adhesion-free contact."""
    return replace(law, sigma0=factor * law.sigma0, gamma=factor * law.gamma,
                   stiffness=law.stiffness)


def anchors_at(iface: Interface, x, anchors, held) -> np.ndarray:
    """The mixed-mode law's anchors after the converged state x: the outer nodes `held`
    (positions in capmesh.outer: held radially, in contact) and those beyond the law's
    reach (gap >= reach: Phi is flat there before and after) take their deformed radius;
    the others keep theirs (a point slips from where it last touched or last came
    within reach)."""
    out = np.array(anchors, dtype=float)
    d = iface.d
    outer = d.capmesh.outer
    free = d.capmesh.nodes[1, outer] + x[d.uz(outer)] >= iface.law.reach
    free[np.asarray(held, dtype=int)] = True
    out[free] = iface.radii(x)[free]
    return out


def point_anchors_at(iface: Interface, x, anchors=None) -> np.ndarray:
    """Anchors per quadrature point ((n_edges, Q), deformed radii / R) after the converged
    state x: a point off the plane (gap >= 0) takes its radius, one in contact keeps its
    anchor (the radius it had at the last converged state before it touched); None: every
    point takes its radius."""
    r, z, _ = iface._points(x)
    if anchors is None:
        return r
    return np.where(z >= 0.0, r, np.asarray(anchors, dtype=float))


def total(iface: Interface, x):
    """(K, r) of the FE solid plus the cohesive interface at x (forms.tangent's units)."""
    from .forms import tangent
    K, r = tangent(iface.d, x)
    return iface.add(x, K, r)
