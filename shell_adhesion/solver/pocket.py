"""The pocket between a ring contact and the plane: gas trapped under the dimple.

Dimensionless as the solver: lengths / R, pressures / C10, volumes / R^3, energies /
(C10 R^3).  The gauge pressure p = p_abs - p_a > 0 pushes the shell off the plane.

Where the outer surface touches the plane in a ring around a lifted apex, the region
between the plane and the surface inside the ring is a pocket of volume

    V = integral of 2 pi r z+ dr along the deformed outer surface, from the axis to the
        inner edge of the outermost contact run (the seal),

z+ the gap where it is positive (a central disc or inner ring in contact bounds no gas;
the gaps between them are one pocket with the seal's gas).  On each Q2 edge r z r' is a
quintic in the edge's parameter: V is integrated exactly (3-point Gauss on each piece
between the roots of the quadratic z).  The seal is where z crosses 0 going down, so the
moving ends of the pieces add nothing to dV/dx; they add to d2V/dx2 the term
2 pi r r' N_a N_b / |z'| (u_z rows and columns) at each crossing.

Modes (`Pocket.mode`): "vented": the pocket is open to the ambient p_a (today's model: the
ambient acts all round and nothing is added).  "sealed": from the moment the ring closes,
the trapped gas obeys p_abs V^n = p_a V0^n (ambient at closing); p_abs = p_a (V0 / V)^n
stays > 0 (vacuum is its limit as V grows).  Its gauge pressure acts on the shell's outer
surface inside the seal as a follower load (`cavity.pressure_tangent`, the cavity's forms),
and on the plane, so the rim load P carries it.  The load is conservative: its potential
is the gas's energy against the atmosphere E_gas(V) = -int_V0^V p dV' (`cavity.gas_energy`),
and the work of P equals U + the contact penalty's energy + E_gas.  As in the sealed cavity,
p is one more unknown (the last entry of x), bordered onto the Newton system by V(x) =
V_gas(p); the unknown is there from the start (its row p = 0 until the pocket seals), so
the pattern does not change when it seals.

The shell's own cavity (solver.cavity) under a prescribed gauge pressure may act at the
same time (the depressurised gripper): `bind` keeps its load (`PocketLoad.shell`), whose
residual, tangent and energy -p_c (V_c - V_c0) are added to the pocket's (a sealed cavity,
a second gas unknown, is not built).
"""
from dataclasses import dataclass, replace
import math

import numpy as np

from shell_adhesion.errors import ConvergenceError, InputError

from .cavity import (P_ATM_KPA, Cavity, _border, first_touch, gas_energy, gas_volume,
                     pressure_tangent)
from .cavity import bind as bind_cavity
from .edge_quadrature import GAUSS_W as _GAUSS_W, GAUSS_X as _GAUSS_X
from .forms import block_slots

MODES = ("vented", "sealed")


@dataclass(frozen=True)
class Pocket:
    """The pocket's gas: `mode` one of MODES; `p_atm` the ambient pressure / C10 (> 0;
    `p_atm_over_C10` from kPa; needed when sealed); `n` the polytropic exponent (> 0; 1
    isothermal, 1.4 adiabatic air)."""

    mode: str = "vented"
    p_atm: float = None
    n: float = 1.0

    def __post_init__(self):
        check_pocket(self.mode, self.p_atm, self.n)

    @property
    def sealed(self) -> bool:
        return self.mode == "sealed"


def check_pocket(mode, p_atm, n, names=None):
    """Raise InputError (one line: field, value, rule) unless the pocket is valid.
    `names` maps mode, p_atm, n to the caller's field names."""
    nm = {**dict(mode="pocket", p_atm="p_atm", n="n"), **(names or {})}
    if mode not in MODES:
        raise InputError(f"{nm['mode']}: {mode!r} must be one of {', '.join(MODES)}")
    if p_atm is None:
        if mode == "sealed":
            raise InputError(f"{nm['p_atm']}: None must be given for a sealed {nm['mode']}: "
                             "the ambient pressure / C10 (> 0)")
        p_atm = 1.0         # vented: the ambient pressure plays no part
    for key, value in (("p_atm", p_atm), ("n", n)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value) or not value > 0:
            raise InputError(f"{nm[key]}: {value!r} must be a finite number > 0")


def p_atm_over_C10(p_atm_kPa: float = P_ATM_KPA, C10_kPa: float = 300.0) -> float:
    """The ambient pressure in units of C10 (both given in kPa)."""
    for name, v in (("p_atm_kPa", p_atm_kPa), ("C10_kPa", C10_kPa)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or not v > 0:
            raise InputError(f"{name}: {v!r} must be a finite number > 0 (kPa)")
    return p_atm_kPa / C10_kPa


@dataclass(frozen=True, eq=False)
class PocketLoad:
    """A Pocket bound to a discretisation (in its `cavity` slot: forms adds its residual,
    tangent and energy): the outer edges from the apex, their dofs and sparsity slots.
    V0 is the volume / R^3 at which the gas was sealed (None: not sealed, vented)."""

    pocket: Pocket
    n_fe: int
    dofs: np.ndarray       # (E, 6) u_r of the edge's 3 nodes, then u_z
    R0: np.ndarray         # (E, 3) reference r, z of the edge nodes
    Z0: np.ndarray
    slots: np.ndarray      # (E, 36) positions of the edge blocks in the FE CSR data
    border: tuple          # the gas unknown's row and column (cavity._border)
    V0: float = None
    shell: object = None   # the shell's own cavity under a prescribed pressure
                           # (cavity.CavityLoad, mode "pressure"), or None

    extra_dofs = 1

    @property
    def sealed(self) -> bool:
        return self.V0 is not None

    def pressure(self, x) -> float:
        """Gauge pressure / C10 of the pocket's gas in state x (0 unless sealed)."""
        return float(x[self.n_fe]) if self.sealed else 0.0

    def measure(self, x):
        """(V, p, r_seal): pocket volume / R^3, gauge pressure / C10, deformed radius / R
        of the seal's inner edge (with no ring around a gap: V = 0, r_seal NaN)."""
        V, r_seal = self._pieces(x, False)[:2]
        return V, self.pressure(x), r_seal

    def volume(self, x) -> float:
        return self._pieces(x, False)[0]

    def is_open(self, x) -> bool:
        """No contact ring around a gap: nothing seals the pocket."""
        return not math.isfinite(self._pieces(x, False)[1])

    def volume_derivatives(self, x):
        """(V, edges, g, H): V / R^3 and, per piece of surface in the pocket, its edge
        (index into dofs) with dV/dx (n, 6) and d2V/dx2 (n, 6, 6)."""
        V, _, edges, g, H = self._pieces(x, True)
        return V, edges, g, H

    def _pieces(self, x, derivatives):
        u = x[self.dofs]
        rn, zn = self.R0 + u[:, :3], self.Z0 + u[:, 3:]
        a = 2 * zn[:, 0] - 4 * zn[:, 1] + 2 * zn[:, 2]        # z = a s^2 + b s + c
        b = -3 * zn[:, 0] + 4 * zn[:, 1] - zn[:, 2]
        c = zn[:, 0]
        crossings = []                                       # (edge, s, dz/ds)
        with np.errstate(divide="ignore", invalid="ignore"):
            vertex = np.where((a > 0) & (-b > 0) & (-b < 2 * a), c - b * b / (4 * a), np.inf)
        low = np.minimum(np.minimum(zn[:, 0], zn[:, 2]), vertex)
        for e in np.flatnonzero(low <= 0):
            for s in _roots(a[e], b[e], c[e]):
                crossings.append((e, s, 2 * a[e] * s + b[e]))
        down = [k for k, cr in enumerate(crossings) if cr[2] < 0]
        if not down:
            return (0.0, math.nan) + ((np.zeros(0, int), np.zeros((0, 6)), np.zeros((0, 6, 6)))
                                      if derivatives else ())
        seal = crossings[down[-1]]
        ends = {}
        for e, s, _ in crossings[:down[-1] + 1]:
            ends.setdefault(e, []).append(s)
        # the pieces [s0, s1] of each edge up to the seal where z > 0
        pieces = []
        for e in range(seal[0] + 1):
            cuts = [0.0] + sorted(ends.get(e, [])) + [1.0]
            if e == seal[0]:
                cuts = [s for s in cuts if s <= seal[1]]
            for s0, s1 in zip(cuts[:-1], cuts[1:]):
                m = 0.5 * (s0 + s1)
                if s1 > s0 and a[e] * m * m + b[e] * m + c[e] > 0:
                    pieces.append((e, s0, s1))
        pe = np.array([p[0] for p in pieces], dtype=int)
        s0 = np.array([p[1] for p in pieces])
        L = np.array([p[2] for p in pieces]) - s0
        xi = s0[:, None] + L[:, None] * _GAUSS_X[None, :]             # (n, Q)
        N, dN = _shape(xi)                                              # (n, Q, 3)
        r = np.einsum("nqa,na->nq", N, rn[pe])
        z = np.einsum("nqa,na->nq", N, zn[pe])
        dr = np.einsum("nqa,na->nq", dN, rn[pe])
        w = 2 * np.pi * _GAUSS_W[None, :] * L[:, None]                  # (n, Q)
        V = float(np.sum(w * r * z * dr))
        Ns, dNs = _shape(np.array([seal[1]]))
        r_seal = float(Ns[0] @ rn[seal[0]])
        if not derivatives:
            return V, r_seal
        g = np.concatenate([np.einsum("nq,nqa->na", w * z * dr, N)
                            + np.einsum("nq,nqa->na", w * r * z, dN),
                            np.einsum("nq,nqa->na", w * r * dr, N)], axis=1)
        H = np.zeros((len(pe), 6, 6))
        NdN = np.einsum("nqa,nqb->nqab", N, dN)
        H[:, :3, :3] = np.einsum("nq,nqab->nab", w * z, NdN + NdN.transpose(0, 1, 3, 2))
        H[:, :3, 3:] = (np.einsum("nq,nqa,nqb->nab", w * dr, N, N)
                        + np.einsum("nq,nqa,nqb->nab", w * r, dN, N))
        H[:, 3:, :3] = H[:, :3, 3:].transpose(0, 2, 1)
        # the moving ends: 2 pi r r' N_a N_b / |z'| at each crossing bounding the pocket
        ce = np.array([cr[0] for cr in crossings[:down[-1] + 1]], dtype=int)
        cs = np.array([cr[1] for cr in crossings[:down[-1] + 1]])
        cz = np.abs([cr[2] for cr in crossings[:down[-1] + 1]])
        Nc, dNc = _shape(cs)                                            # (m, 3)
        rc = np.einsum("ma,ma->m", Nc, rn[ce])
        drc = np.einsum("ma,ma->m", dNc, rn[ce])
        Hc = np.zeros((len(ce), 6, 6))
        Hc[:, 3:, 3:] = (2 * np.pi * rc * drc / cz)[:, None, None] * Nc[:, :, None] * Nc[:, None, :]
        return (V, r_seal, np.concatenate([pe, ce]),
                np.concatenate([g, np.zeros((len(ce), 6))]), np.concatenate([H, Hc]))

    # --------------------------------------------------------- the gas
    def gas(self, p):
        """(V_gas, dV_gas/dp) of the sealed gas at gauge pressure p."""
        return gas_volume(p, self.V0, 0.0, self.pocket.p_atm, self.pocket.n)

    def energy(self, x) -> float:
        """E_gas(V) / (C10 R^3) of the sealed gas (0 unless sealed), plus the energy of the
        shell's own cavity's pressure load -p_c (V_c - V_c0) if it has one."""
        E = 0.0 if self.shell is None else self.shell.energy(x)
        if not self.sealed:
            return E
        return E + gas_energy(self.volume(x), self.V0, 0.0, self.pocket.p_atm, self.pocket.n)

    def on_gas_law(self, x):
        """x with the gas unknown set to the pressure the sealed gas has at the pocket's
        volume in x, p = p_a ((V0 / V)^n - 1) (x itself unless sealed): a damped descent
        (arclength._descend) moves the shell and keeps the gas on its law.  Raises
        PocketOpened where no ring around a gap is left in x."""
        if not self.sealed:
            return x
        V = self.volume(x)
        if not V > 0:
            raise PocketOpened("the sealed pocket opened")
        y = x.copy()
        y[self.n_fe] = self.pocket.p_atm * ((self.V0 / V) ** self.pocket.n - 1.0)
        return y

    # ------------------------------------------------- residual and tangent
    def add_residual(self, x, r):
        return self.add_tangent(None, r, x)[1]

    def add_tangent(self, K, r, x):
        """(K, r) of the FE forms plus the pressure's follower load and the bordered gas
        row (V_gas(p) - V once sealed; before, p itself, uncoupled), plus the shell's own
        cavity's load if it has one.  K None: r alone."""
        if self.shell is not None:
            if K is None:
                r = self.shell.add_residual(x, r)
            else:
                K, r = self.shell.add_tangent(K, r, x)
        p = self.pressure(x)
        if not self.sealed:
            if K is None:
                r = r.copy()
                r[self.n_fe] = x[self.n_fe]
                return None, r
            return pressure_tangent(K, r, self.dofs[:0], self.slots[:0], np.zeros((0, 6)),
                                    np.zeros((0, 6, 6)), 0.0, self.border,
                                    (x[self.n_fe], 1.0), self.n_fe, coupled=False)
        V, edges, g, H = self.volume_derivatives(x)
        Vg, dVg = self.gas(p)
        if K is None:
            r = r.copy()
            np.add.at(r, self.dofs[edges].ravel(), -p * g.ravel())
            r[self.n_fe] = Vg - V
            return None, r
        return pressure_tangent(K, r, self.dofs[edges], self.slots[edges], g, H, p,
                                self.border, (Vg - V, dVg), self.n_fe)


class PocketOpened(ConvergenceError):
    """A state reached (by a step or a descent) has lost the ring around the sealed pocket."""


def _roots(a, b, c):
    """Roots of a s^2 + b s + c strictly inside (0, 1), ascending."""
    if abs(a) < 1e-14 * (abs(b) + abs(c)):
        out = [-c / b] if b != 0 else []
    else:
        disc = b * b - 4 * a * c
        if disc < 0:
            return []
        q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
        out = [q / a] + ([c / q] if q != 0 else [])
    return sorted(s for s in out if 0.0 < s < 1.0)


def _shape(xi):
    """Q2 shape functions and derivatives (nodes at 0, 1/2, 1) at xi: (..., 3) each."""
    xi = np.asarray(xi, dtype=float)[..., None]
    N = np.concatenate([2 * (xi - 0.5) * (xi - 1), -4 * xi * (xi - 1), 2 * xi * (xi - 0.5)], -1)
    dN = np.concatenate([4 * xi - 3, 4 - 8 * xi, 4 * xi - 1], -1)
    return N, dN


def bind(d, pocket: Pocket):
    """`d` (a forms.Discretisation, its own cavity open or under a prescribed pressure:
    cavity.bind) with the pocket's gas unknown and load (not sealed yet)."""
    if not isinstance(pocket, Pocket):
        raise InputError(f"pocket: {pocket!r} must be a Pocket")
    shell = d.cavity
    if isinstance(shell, PocketLoad):
        raise InputError("pocket: the discretisation is bound to a pocket already")
    if shell is not None and shell.cavity.mode != "pressure":
        raise InputError("pocket: the shell's own cavity is sealed; the pocket with a sealed "
                         "cavity is not built (use cavity pressure or open)")
    cm = d.capmesh
    outer = cm.outer
    k = np.arange(0, len(outer) - 2, 2)
    nodes = np.stack([outer[k], outer[k + 1], outer[k + 2]], axis=1)      # (E, 3)
    dofs = np.concatenate([d.ur(nodes), d.uz(nodes)], axis=1)
    n_fe = 2 * d.n2 + d.n1
    load = PocketLoad(pocket, n_fe, dofs, cm.nodes[0, nodes], cm.nodes[1, nodes],
                      block_slots(d, dofs), _border(d.csr_indptr, d.csr_indices, np.unique(dofs)),
                      shell=shell)
    return replace(d, cavity=load)


def bind_depressurised(d, pocket: Pocket, cavity: Cavity):
    """(d, x0, pressurised): the shell `d` (no cavity bound) with its own cavity held at
    the prescribed gauge pressure of `cavity` (mode "pressure"), the free shell
    pressurised and moved so that it just touches the plane at delta = 0
    (cavity.first_touch; raises its CavitySnap if the free shell snaps first), then bound
    to `pocket`; x0 is the start state for snap.trace_loading (the pocket's gas unknown
    appended, 0) and `pressurised` the free shell (cavity.Pressurised)."""
    if not (isinstance(cavity, Cavity) and cavity.mode == "pressure"):
        raise InputError(f"cavity: {cavity!r} must be a Cavity with mode 'pressure'")
    touching, x0, pressurised = first_touch(bind_cavity(d, cavity))
    return bind(touching, pocket), np.append(x0, 0.0), pressurised


def seal(d, x):
    """`d` with its pocket sealed in state x (ambient pressure at the volume V(x)); raises
    ValueError if nothing encloses a pocket there."""
    load = d.cavity
    V = load.volume(x)
    if not V > 0:
        raise ValueError("pocket: no ring contact encloses a gap: nothing to seal")
    return replace(d, cavity=replace(load, V0=V))
