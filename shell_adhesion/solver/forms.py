"""Axisymmetric mixed (Q2 displacement / Q1 pressure) forms, total Lagrangian.

Unknowns, in units of R and C10: nodal u_r, u_z (Q2) and the multiplier p (Q1).
Global layout: x = [u_r (n2), u_z (n2), p (n1)].  Integrals carry the full 2 pi r weight,
so residual entries are forces over 360 degrees (units of C10 R^2) and the energy is in
units of C10 R^3.  The deformation gradient is linear in u, so the strain-displacement
operator B is assembled once and reused.  The material (`solver.material`) is part of the
discretisation; with a compressible one (D1 > 0) the pressure rows gain -(D1 C10 / 2) p, the
same sparsity.
"""
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from skfem import CellBasis, ElementQuad1, ElementQuad2

from .material import NEO_HOOKE, Material, energy, lagrangian_derivatives, limit_exceeded
from .material import lagrangian as lagrangian_density
from .mesh import CapMesh
from shell_adhesion.errors import ConvergenceError


@dataclass(frozen=True, eq=False)
class Discretisation:
    """Everything about the FE space that does not change with the solution."""

    capmesh: CapMesh
    n2: int              # Q2 nodes
    n1: int              # Q1 (pressure) nodes
    edofs: np.ndarray    # (22, E) global dofs of each element: 9 u_r, 9 u_z, 4 p
    B: np.ndarray        # (5, 18, E, Q) d f / d u_e
    Np: np.ndarray       # (4, E, Q) pressure shape functions
    w: np.ndarray        # (E, Q) quadrature weight * 2 pi r
    r_q: np.ndarray      # (E, Q) reference radius of the quadrature points
    z_q: np.ndarray
    csr_indptr: np.ndarray
    csr_indices: np.ndarray
    csr_slot: np.ndarray # (E * 22 * 22,) position of each element entry in the CSR data
    material: Material = NEO_HOOKE
    cavity: object = None  # solver.cavity.CavityLoad of a closed cavity (cavity.bind), else None
    edge: object = None    # solver.edge.EdgeAdhesion of a sliding held set's edge, else None

    @property
    def force_scale(self) -> float:
        """C10 * volume / size of the body: the natural force unit of round-off."""
        return float(self.w.sum() / self.capmesh.mesh.doflocs.max())

    @property
    def ndof(self) -> int:
        return 2 * self.n2 + self.n1 + (self.cavity.extra_dofs if self.cavity else 0)

    @cached_property
    def G(self) -> np.ndarray:
        """The nonzero rows of B, (3, 9, E, Q): dN/dr, dN/dz and N / r.  f_rr, f_rz, f_tt
        take them from u_r, f_zr, f_zz the first two from u_z."""
        return np.ascontiguousarray(self.B[[0, 1, 4], :9])

    @cached_property
    def G_e(self) -> np.ndarray:
        """G per element, (E, 3 * Q, 9), rows (row of G, point) (assembly of f)."""
        E, Q = self.w.shape
        return np.ascontiguousarray(self.G.transpose(2, 0, 3, 1)).reshape(E, 3 * Q, 9)

    @cached_property
    def Gw_e(self) -> np.ndarray:
        """(G w)^T per element, (E, 9, Q * 3), columns (point, row of G): sum_q G^T w X is
        then one matmul with X (E, Q * 3, k) (assembly of Ke and the residual)."""
        Gw = self.G * self.w                                   # (3, 9, E, Q)
        return np.ascontiguousarray(Gw.transpose(2, 1, 3, 0)).reshape(self.w.shape[0], 9, -1)

    @cached_property
    def Gw_z(self) -> np.ndarray:
        """As `Gw_e`, for the two rows of G that u_z enters: (E, 9, Q * 2)."""
        Gw = self.G[:2] * self.w
        return np.ascontiguousarray(Gw.transpose(2, 1, 3, 0)).reshape(self.w.shape[0], 9, -1)

    @cached_property
    def slots(self):
        """Where `tangent`'s element products go: (slot, mirror, mirror_source, pp).

        slot: for the u_r rows of each element (9 x 22: 9 u_r, 9 u_z, 4 p columns) then
        its u_z rows (9 x 13: 9 u_z, 4 p), the CSR data position of each entry.  The blocks
        below (u_z, u_r), (p, u_r), (p, u_z) are the transposes of those above, copied from
        positions mirror_source to mirror; pp (positions, values): the assembled
        sum_q Np Np^T w of the (p, p) block.
        """
        E, Q = self.w.shape
        nnz, n = len(self.csr_indices), len(self.csr_indptr) - 1
        slot = self.csr_slot.reshape(E, 22, 22)
        rows = np.repeat(np.arange(n, dtype=np.int64), np.diff(self.csr_indptr))
        cols = self.csr_indices.astype(np.int64)
        kind = np.minimum(np.arange(n) // self.n2, 2)           # 0 u_r, 1 u_z, 2 p
        mirror = np.flatnonzero(kind[rows] > kind[cols])
        source = np.searchsorted(rows * n + cols, cols[mirror] * n + rows[mirror])
        NpNp = np.einsum("beq,ceq,eq->ebc", self.Np, self.Np, self.w)
        slot_pp = slot[:, 18:, 18:].ravel()
        pp = np.unique(slot_pp)
        pp_values = np.bincount(slot_pp, weights=NpNp.ravel(), minlength=nnz)[pp]
        slot = np.concatenate([slot[:, :9, :].ravel(), slot[:, 9:18, 9:].ravel()])
        return slot, mirror, source, (pp, pp_values)

    def ur(self, nodes):
        return np.asarray(nodes)

    def uz(self, nodes):
        return self.n2 + np.asarray(nodes)


def discretise(capmesh: CapMesh, C10: float = 1.0,
               material: Material = NEO_HOOKE) -> Discretisation:
    """FE space of `capmesh` for `material`; `C10` scales it (1 = the dimensionless solver)."""
    mesh = capmesh.mesh
    bu = CellBasis(mesh, ElementQuad2(), intorder=4)
    bp = CellBasis(mesh, ElementQuad1(), quadrature=bu.quadrature)
    n2, n1 = bu.N, bp.N
    E, Q = bu.nelems, bu.X.shape[1]
    rq, zq = bu.mapping.F(bu.X)
    N = np.array([np.asarray(bu.basis[a][0]) for a in range(9)])
    dN = np.array([bu.basis[a][0].grad for a in range(9)])  # (9, 2, E, Q)
    B = np.zeros((5, 18, E, Q))
    B[0, :9] = dN[:, 0]
    B[1, :9] = dN[:, 1]
    B[4, :9] = N / rq
    B[2, 9:] = dN[:, 0]
    B[3, 9:] = dN[:, 1]
    Np = np.array([np.asarray(bp.basis[b][0]) for b in range(4)])
    edofs = np.vstack([bu.element_dofs, n2 + bu.element_dofs, 2 * n2 + bp.element_dofs])
    ndof = 2 * n2 + n1
    rows = np.broadcast_to(edofs.T[:, :, None], (E, 22, 22)).ravel()
    cols = np.broadcast_to(edofs.T[:, None, :], (E, 22, 22)).ravel()
    keys, slot = np.unique(rows.astype(np.int64) * ndof + cols, return_inverse=True)
    indices = (keys % ndof).astype(np.int32)
    indptr = np.searchsorted(keys // ndof, np.arange(ndof + 1)).astype(np.int32)
    return Discretisation(capmesh, n2, n1, edofs, B, Np, bu.dx * 2 * np.pi * rq * C10, rq, zq,
                          indptr, indices, slot.ravel(), material)


def with_couplings(d: Discretisation, rows, cols) -> Discretisation:
    """`d` with its CSR pattern extended by the entries (rows, cols) and their transposes
    (a load coupling dofs that share no element: the cavity's lid, solver.cavity); the
    element entries keep their values, the new ones start at zero."""
    ndof = len(d.csr_indptr) - 1
    old = _csr_keys(d)
    rows, cols = np.asarray(rows, dtype=np.int64), np.asarray(cols, dtype=np.int64)
    keys = np.union1d(old, np.concatenate([rows * ndof + cols, cols * ndof + rows]))
    if len(keys) == len(old):
        return d
    indices = (keys % ndof).astype(np.int32)
    indptr = np.searchsorted(keys // ndof, np.arange(ndof + 1)).astype(np.int32)
    slot = np.searchsorted(keys, old)[d.csr_slot]
    return replace(d, csr_indptr=indptr, csr_indices=indices, csr_slot=slot)


def _csr_keys(d: Discretisation) -> np.ndarray:
    """row * ndof + column of each stored entry of d's CSR pattern, in storage order
    (sorted)."""
    ndof = len(d.csr_indptr) - 1
    return (np.repeat(np.arange(ndof, dtype=np.int64), np.diff(d.csr_indptr)) * ndof
            + d.csr_indices)


def block_slots(d: Discretisation, dofs) -> np.ndarray:
    """(E, k * k) positions in d's CSR data of the blocks coupling the k dofs of each row
    of `dofs` (E, k), row-major; ValueError if a pair is not in the pattern."""
    dofs = np.asarray(dofs, dtype=np.int64)
    ndof, (E, k) = len(d.csr_indptr) - 1, dofs.shape
    keys = _csr_keys(d)
    pairs = (dofs[:, :, None] * ndof + dofs[:, None, :]).reshape(E, k * k)
    slots = np.searchsorted(keys, pairs)
    if not np.array_equal(keys[np.minimum(slots, len(keys) - 1)], pairs):
        raise ValueError("the dofs are not coupled in the FE sparsity pattern")
    return slots


def _fields(d: Discretisation, x):
    xe = x[d.edofs]                                   # (22, E)
    E, Q = d.w.shape
    G = d.G_e
    fr = np.matmul(G, xe[:9].T[:, :, None]).reshape(E, 3, Q)       # f_rr, f_rz, f_tt
    fz = np.matmul(G[:, :2 * Q], xe[9:18].T[:, :, None]).reshape(E, 2, Q)   # f_zr, f_zz
    f = np.empty((5, E, Q))
    f[[0, 1, 4]] = fr.transpose(1, 0, 2)
    f[[2, 3]] = fz.transpose(1, 0, 2)
    f[[0, 3, 4]] += 1.0
    p = np.einsum("beq,be->eq", d.Np, xe[18:])
    return f, p


def deformation(d: Discretisation, x):
    """Deformation 5-vector f (5, E, Q) and multiplier p (E, Q) at the quadrature points."""
    return _fields(d, x)


def _checked(d: Discretisation, f):
    """f, unless a Gent solid reaches its limit I1bar - 3 = Jm somewhere (ConvergenceError)."""
    ratio = limit_exceeded(f, d.material)
    if not ratio < 1.0 and np.isfinite(ratio):
        raise ConvergenceError(
            f"gent limit reached: I1bar - 3 = {ratio * d.material.Jm:.6g} >= Jm = "
            f"{d.material.Jm:g} (the solid locks up; lower delta or raise Jm)")
    return f


def strain_energy(d: Discretisation, x) -> float:
    """Strain energy / (C10 R^3), the integral of W over the deformed shell (360 degrees).

    For a compressible solid, the integral of the Lagrangian W + p (J - 1) - (D1 C10 / 4) p^2
    (p eliminated: W + U(J) in the discrete sense), whose derivative in delta is P.
    """
    f, p = _fields(d, x)
    f = _checked(d, f)
    W = (lagrangian_density(f, p, d.material) if d.material.compressible
         else energy(f, d.material))
    return float(np.sum(W * d.w))


def lagrangian(d: Discretisation, x) -> float:
    """The mixed form's Lagrangian / (C10 R^3), whose gradient is `residual`: the integral
    of `material.lagrangian` plus the cavity's and the held edge's energies; equal to
    `potential_energy` where J = 1.  The merit of a step that leaves J = 1 to first order
    only (`arclength._descend`)."""
    f, p = _fields(d, x)
    L = float(np.sum(lagrangian_density(_checked(d, f), p, d.material) * d.w))
    L = L if d.cavity is None else L + d.cavity.energy(x)
    return L if d.edge is None else L + d.edge.energy(x)


def residual(d: Discretisation, x):
    """Internal force vector dL/dx (units of C10 R^2; pressure rows: volume / R^3)."""
    f, p = _fields(d, x)
    dL, _, _, _, dLdp, _ = lagrangian_derivatives(_checked(d, f), p, d.material)
    r = _residual(d, dL, dLdp)
    return r if d.cavity is None else d.cavity.add_residual(x, r)   # solver.cavity


def _residual(d, dL, dLdp):
    """sum_q B^T w dL/df and sum_q Np w dL/dp, scattered to the dofs (without a cavity)."""
    E, Q = d.w.shape
    ur = np.matmul(d.Gw_e, dL[[0, 1, 4]].transpose(1, 2, 0).reshape(E, Q * 3, 1))
    uz = np.matmul(d.Gw_z, dL[[2, 3]].transpose(1, 2, 0).reshape(E, Q * 2, 1))
    return _scatter_vector(d, np.vstack([ur[:, :, 0].T, uz[:, :, 0].T]), dLdp * d.w)


def potential_energy(d: Discretisation, x) -> float:
    """Strain energy plus the energy of the cavity's pressure load (solver.cavity) and of
    a sliding held edge's adhesion (solver.edge), units of C10 R^3: the U_E of Maugis'
    method (with the edge: U_E - gamma pi r^2)."""
    U = strain_energy(d, x)
    U = U if d.cavity is None else U + d.cavity.energy(x)
    return U if d.edge is None else U + d.edge.energy(x)


def _scatter_vector(d, ru, jw):
    re = np.vstack([ru, np.einsum("beq,eq->be", d.Np, jw)])
    return np.bincount(d.edofs.ravel(), weights=re.ravel(), minlength=d.ndof)


def tangent_pattern(d: Discretisation):
    """CSR (indptr, indices) of every `tangent(d, x)`: the FE pattern, bordered by the gas
    unknown of a sealed cavity (solver.cavity)."""
    if d.cavity is not None and d.cavity.border:
        return d.cavity.border[1], d.cavity.border[2]
    return d.csr_indptr, d.csr_indices


def tangent(d: Discretisation, x):
    """Consistent tangent (CSR, symmetric indefinite) and residual at x."""
    return Linearisation(d, x).tangent()


class Linearisation:
    """The residual at x (`r`, as `residual` gives it) and, on demand, the tangent
    (`tangent()`, as the function gives it), from one evaluation of the material: a Newton
    iteration that needs only the residual skips the assembly of the tangent."""

    def __init__(self, d: Discretisation, x):
        f, p = _fields(d, x)
        self.d, self.x = d, np.array(x)      # the caller may move on from x
        self.derivatives = lagrangian_derivatives(_checked(d, f), p, d.material)
        dL, _, _, _, dLdp, _ = self.derivatives
        self._r = _residual(d, dL, dLdp)
        self.r = self._r if d.cavity is None else d.cavity.add_residual(x, self._r)
        if d.edge is not None:          # solver.edge
            self.r = d.edge.add_residual(x, self.r)

    def tangent(self):
        """(K, r): the consistent tangent (CSR, symmetric indefinite) and residual."""
        d, r = self.d, self._r
        K = _stiffness(d, *self.derivatives)
        if d.cavity is not None:
            K, r = d.cavity.add_tangent(K, r, self.x)       # solver.cavity
        if d.edge is not None:
            K, r = d.edge.add_tangent(K), self.r            # solver.edge
        return K, r


def _stiffness(d: Discretisation, dL, d2L, J, dJ, dLdp, d2Ldp2):
    """The FE tangent (CSR) from the derivatives of the Lagrangian at the points."""
    E, Q = d.w.shape
    G, Np = d.G, d.Np
    # per point, the rows of [D B | dJ Np^T] that B's nonzero rows meet: those of f_rr,
    # f_rz, f_tt against every column, those of f_zr, f_zz against the u_z and p columns
    Xr = np.empty((3, 22, E, Q))
    Xz = np.empty((2, 13, E, Q))
    for X, rows in ((Xr, (0, 1, 4)), (Xz, (2, 3))):
        z = X.shape[1] - 13                            # first u_z column
        for k, i in enumerate(rows):
            Y = X[k]
            if z:
                np.multiply(d2L[i, 0], G[0], out=Y[:9])
                Y[:9] += d2L[i, 1] * G[1]
                Y[:9] += d2L[i, 4] * G[2]
            np.multiply(d2L[i, 2], G[0], out=Y[z:z + 9])
            Y[z:z + 9] += d2L[i, 3] * G[1]
            np.multiply(dJ[i], Np, out=Y[z + 9:])
    # per element, sum_q (G w)^T X: the u_r rows (E, 9, 22) and u_z rows (E, 9, 13) of Ke,
    # in the order of `d.slots`
    W = np.empty(E * 9 * 35)
    np.matmul(d.Gw_e, np.ascontiguousarray(Xr.transpose(2, 3, 0, 1)).reshape(E, Q * 3, 22),
              out=W[:E * 9 * 22].reshape(E, 9, 22))
    np.matmul(d.Gw_z, np.ascontiguousarray(Xz.transpose(2, 3, 0, 1)).reshape(E, Q * 2, 13),
              out=W[E * 9 * 22:].reshape(E, 9, 13))
    slot, mirror, source, (pp, pp_values) = d.slots
    data = np.bincount(slot, weights=W, minlength=len(d.csr_indices))
    data[mirror] = data[source]                        # the blocks below: symmetry
    if d2Ldp2:
        data[pp] = d2Ldp2 * pp_values
    n = len(d.csr_indptr) - 1
    return sp.csr_matrix((data, d.csr_indices, d.csr_indptr), shape=(n, n))
