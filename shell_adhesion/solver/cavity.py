"""The closed cavity under the shell: a gauge pressure on the inner surface and the lid.

A rigid lid closes the cap at its rim (it moves with the held rim face).  The enclosed
volume is V = pi * integral of r^2 dz along the deformed inner surface from the inner apex
to the inner rim (the lid and the axis add nothing), evaluated exactly on the Q2 edges
(3-point Gauss: r^2 z' is a quintic).  Its gradient is the follower load of a unit pressure
on the inner surface plus the lid's pull on the rim (the boundary term pi r_i^2 dz), so a
gauge pressure p does the work p dV and the load is conservative (Maugis' method holds).
The lid is also a contact: the inner surface is pushed back where it would pass it
(solver.lid; its energy is part of `CavityLoad.energy`, zero where nothing reaches it).

Modes (DESIGN.md section 8):
- "open": no cavity (today's model);
- "pressure": prescribed gauge pressure p; potential -p (V - V0);
- "sealed": trapped gas, p_abs V^n = const, sealed at gauge p0 in the undeformed state,
  ambient p_atm; the gauge pressure p is one more unknown (the last entry of x), bordered
  onto the Newton system by the equation V(x) = V_gas(p).  The mixed potential
  L = U - p (V - V0) + Phi(p), Phi' = V_gas - V0, is stationary at equilibrium, where it
  equals U + E_gas(V), E_gas(V) = -int_V0^V p(V') dV' (the gas's energy against the
  atmosphere).
Dimensionless: pressures / C10, V / R^3, energies / (C10 R^3).  p > 0 inflates.
"""
from dataclasses import dataclass, replace
import math

import numpy as np

from skfem import MeshQuad2

from .contact import constraints
from .edge_quadrature import DN as _DN, GAUSS_W as _GAUSS_W, N as _N
from .forms import block_slots, discretise
from .lid import lid_of
from shell_adhesion.errors import InputError
from .path import Settings, Timer, _Problem
from shell_adhesion.errors import ConvergenceError

MODES = ("open", "pressure", "sealed")
P_ATM_KPA = 101.325           # standard atmosphere [kPa]



@dataclass(frozen=True)
class Cavity:
    """What fills the cavity, in units of C10 (hashable: part of a path set's identity).

    mode: one of MODES; p: prescribed gauge pressure ("pressure"); p0: gauge pressure at
    sealing, p_atm: ambient pressure, n: polytropic exponent ("sealed"; p_atm also bounds
    the prescribed p: the absolute pressure p + p_atm must stay >= 0).
    """

    mode: str = "open"
    p: float = 0.0
    p0: float = 0.0
    p_atm: float = 0.0
    n: float = 1.0

    def __post_init__(self):
        check_cavity(self.mode, self.p, self.p0, self.p_atm, self.n)

    @property
    def closed(self) -> bool:
        return self.mode != "open"

    @property
    def sealed(self) -> bool:
        return self.mode == "sealed"

    def as_dict(self) -> dict:
        return dict(mode=self.mode, p=self.p, p0=self.p0, p_atm=self.p_atm, n=self.n)


def check_cavity(mode, p=0.0, p0=0.0, p_atm=0.0, n=1.0, names=None):
    """Raise InputError unless the cavity parameters are valid (units as the caller's).

    `names` maps mode, p, p0, p_atm, n to the caller's field names.
    """
    nm = {**dict(mode="cavity", p="p", p0="p0", p_atm="p_atm", n="gas_exponent"), **(names or {})}
    if mode not in MODES:
        raise InputError(f"{nm['mode']}: {mode!r} must be one of {', '.join(MODES)}")
    for key, value in (("p", p), ("p0", p0), ("p_atm", p_atm), ("n", n)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value):
            raise InputError(f"{nm[key]}: {value!r} must be a finite number")
    if mode != "pressure" and p != 0:
        raise InputError(f"{nm['p']}: {p:g} is given but {nm['mode']} is {mode!r} "
                         f"(a prescribed pressure needs {nm['mode']} pressure)")
    if mode != "sealed" and (p0 != 0 or n != 1):
        which = nm["p0"] if p0 != 0 else nm["n"]
        raise InputError(f"{which}: is given but {nm['mode']} is {mode!r} (it belongs to "
                         f"{nm['mode']} sealed)")
    if mode == "open":
        return
    if not p_atm >= 0:
        raise InputError(f"{nm['p_atm']}: {p_atm:g} must be >= 0 (an absolute pressure)")
    if mode == "pressure" and p + p_atm < 0:
        raise InputError(f"{nm['p']}: {p:g} gives a negative absolute pressure "
                         f"({nm['p_atm']} {p_atm:g}): p + p_atm must be >= 0")
    if mode == "sealed":
        if not p_atm > 0:
            raise InputError(f"{nm['p_atm']}: {p_atm:g} must be > 0 for a sealed cavity")
        if p0 + p_atm <= 0:
            raise InputError(f"{nm['p0']}: {p0:g} gives a negative absolute pressure "
                             f"({nm['p_atm']} {p_atm:g}): p0 + p_atm must be > 0")
        if not n >= 1:
            raise InputError(f"{nm['n']}: {n:g} must be >= 1 (1 isothermal, 1.4 adiabatic)")


OPEN = Cavity()


@dataclass(frozen=True, eq=False)
class CavityLoad:
    """A Cavity bound to a discretisation: the inner-surface edges and sparsity slots."""

    cavity: Cavity
    n_fe: int              # FE unknowns before the gas pressure
    dofs: np.ndarray       # (E, 6) u_r of the edge's 3 nodes, then u_z
    R0: np.ndarray         # (E, 3) reference r of the edge nodes
    Z0: np.ndarray         # (E, 3)
    slots: np.ndarray      # (E, 36) positions of the edge blocks in the FE CSR data
    V0: float              # enclosed volume of the undeformed cap (discrete)
    lid: object            # the lid's contact with the inner surface (solver.lid.Lid)
    border: tuple = ()     # sealed: (rows, indptr, indices, old_pos, col_pos, last_pos)

    @property
    def extra_dofs(self) -> int:
        return 1 if self.cavity.sealed else 0

    def pressure(self, x) -> float:
        """Gauge pressure / C10 in state x."""
        return float(x[self.n_fe]) if self.cavity.sealed else self.cavity.p

    def measure(self, x):
        """(V, p): enclosed volume / R^3 and gauge pressure / C10 of state x."""
        return self.volume(x), self.pressure(x)

    # ---------------------------------------------------------------- the volume
    def volume(self, x) -> float:
        """Enclosed volume / R^3 of state x (inner surface and lid)."""
        r, zp = self._trace(x)
        return float(np.pi * np.sum(_GAUSS_W * r * r * zp))

    def through_lid(self, x) -> bool:
        """Whether the inner surface of state x has passed the lid (`lid.Lid.through`)."""
        return self.lid.through(x)

    def _trace(self, x):
        u = x[self.dofs]
        r = (self.R0 + u[:, :3]) @ _N.T        # (E, Q)
        zp = (self.Z0 + u[:, 3:]) @ _DN.T
        return r, zp

    def volume_derivatives(self, x):
        """V, dV/dx per edge (E, 6) and d2V/dx2 per edge (E, 6, 6)."""
        r, zp = self._trace(x)
        w = np.pi * _GAUSS_W
        V = float(np.sum(w * r * r * zp))
        g = np.concatenate([np.einsum("q,eq,qa->ea", 2 * w, r * zp, _N),
                            np.einsum("q,eq,qa->ea", w, r * r, _DN)], axis=1)
        H = np.zeros((len(r), 6, 6))
        H[:, :3, :3] = np.einsum("q,eq,qa,qb->eab", 2 * w, zp, _N, _N)
        H[:, :3, 3:] = np.einsum("q,eq,qa,qb->eab", 2 * w, r, _N, _DN)
        H[:, 3:, :3] = H[:, :3, 3:].transpose(0, 2, 1)
        return V, g, H

    # ------------------------------------------------------------- the gas
    def gas_volume(self, p):
        """Sealed: the volume at which the gas has gauge pressure p, and its derivative."""
        c = self.cavity
        return gas_volume(p, self.V0, c.p0, c.p_atm, c.n)

    def gas_energy(self, V) -> float:
        """E_gas(V) = -int_V0^V p_gauge dV' (zero at V0; units of C10 R^3)."""
        c = self.cavity
        return gas_energy(V, self.V0, c.p0, c.p_atm, c.n)

    def energy(self, x) -> float:
        """Energy of the pressure load in state x, -p (V - V0) or E_gas(V) if sealed, plus
        the lid's contact energy (0 where nothing touches it)."""
        V = self.volume(x)
        E = self.gas_energy(V) if self.cavity.sealed else -self.cavity.p * (V - self.V0)
        return E + self.lid.energy(x)

    # ------------------------------------------------------- residual and tangent
    def add_residual(self, x, r):
        """r (FE internal forces, extended by the gas row if sealed) plus the load terms."""
        V, g, _ = self.volume_derivatives(x)
        p = self.pressure(x)
        r = self.lid.add_residual(x, r).copy()
        np.add.at(r, self.dofs.ravel(), -p * g.ravel())
        if self.cavity.sealed:
            r[self.n_fe] = self.gas_volume(p)[0] - V
        return r

    def add_tangent(self, K, r, x):
        """(K, r) of the FE forms plus the follower-load stiffness -p d2V, and, if sealed,
        the bordered gas row and column (-dV/dx, dV_gas/dp), and the lid's contact.  K's
        sparsity is kept."""
        K, r = self.lid.add_tangent(K, r, x)
        V, g, H = self.volume_derivatives(x)
        p = self.pressure(x)
        if not self.cavity.sealed:
            return pressure_tangent(K, r, self.dofs, self.slots, g, H, p)
        Vg, dVg = self.gas_volume(p)
        return pressure_tangent(K, r, self.dofs, self.slots, g, H, p, self.border,
                                (Vg - V, dVg), self.n_fe)


def gas_volume(p, V0, p0, p_atm, n):
    """(V, dV/dp): the volume / R^3 at which a gas sealed at volume V0 and gauge p0 (ambient
    p_atm, p_abs V^n constant; pressures / C10) has gauge pressure p.  An iterate with
    p_abs < 0 and n not 1 gives NaN (a failed Newton step), not a complex number."""
    ratio = (p0 + p_atm) / np.float64(p + p_atm)
    V = V0 * ratio ** (1.0 / n)
    return V, -V / (n * (p + p_atm))


def gas_energy(V, V0, p0, p_atm, n) -> float:
    """E_gas(V) = -int_V0^V p_gauge dV' (C10 R^3; zero at V0) of the gas of `gas_volume`:
    the gas's energy against the atmosphere."""
    dv = (V - V0) / V0
    L = math.log1p(dv)
    k = L if n == 1 else math.expm1((1.0 - n) * L) / (1.0 - n)
    return -(p0 + p_atm) * V0 * k + p_atm * V0 * dv


def pressure_tangent(K, r, dofs, slots, g, H, p, border=None, gas=None, n_fe=None,
                     coupled=True):
    """(K, r) plus the load of a gauge pressure p on a surface enclosing the volume V:
    r - p dV/dx and K - p d2V/dx2 (g = dV/dx per edge (E, 6) at `dofs`, H = d2V/dx2 (E, 6,
    6) at the CSR `slots`), K's pattern kept.  With `border` (`_border`'s layout) and
    gas = (row, dp): the gas unknown (entry n_fe) bordered on, r[n_fe] = row, diagonal dp,
    column and row -dV/dx (`coupled`) or 0 (a gas row that does not see V)."""
    data = K.data.copy()
    np.add.at(data, slots.ravel(), -p * H.ravel())
    r = r.copy()
    np.add.at(r, dofs.ravel(), -p * g.ravel())
    if border is None:
        return type(K)((data, K.indices, K.indptr), shape=K.shape), r
    rows, indptr, indices, old_pos, col_pos, last_pos = border
    if coupled:
        coupling = -np.bincount(dofs.ravel(), weights=g.ravel(), minlength=n_fe)[rows]
    else:
        coupling = np.zeros(len(rows))
    r[n_fe], dp = gas
    out = np.empty(len(indices))
    out[old_pos] = data
    out[col_pos] = coupling
    out[last_pos] = np.append(coupling, dp)
    n = n_fe + 1
    return type(K)((out, indices, indptr), shape=(n, n)), r


def bind(d, cavity: Cavity):
    """`d` (a forms.Discretisation) with `cavity` acting on it (d itself if open)."""
    if not cavity.closed:
        return replace(d, cavity=None)
    cm = d.capmesh
    if cm.cap.solid:
        raise InputError("cavity: a solid cap (t = R) has no cavity; use cavity open")
    r, z = cm.nodes[:, cm.inner]
    inner = cm.inner[np.argsort(np.arctan2(r, 1.0 - z))]
    if len(inner) % 2 != 1 or np.any(inner[1::2] < cm.mesh.nvertices):
        raise ValueError("inner surface nodes do not alternate corner / midside")
    nodes = np.stack([inner[0:-1:2], inner[1::2], inner[2::2]], axis=1)   # (E, 3)
    d, lid = lid_of(d, nodes)
    n_fe = 2 * d.n2 + d.n1
    dofs = np.concatenate([nodes, d.n2 + nodes], axis=1)
    slots = block_slots(d, dofs)
    load = CavityLoad(cavity, n_fe, dofs, cm.nodes[0, nodes], cm.nodes[1, nodes], slots, 1.0,
                      lid=lid)
    load = replace(load, V0=load.volume(np.zeros(n_fe + 1)))
    if cavity.sealed:
        load = replace(load, border=_border(d.csr_indptr, d.csr_indices, np.unique(dofs)))
    return replace(d, cavity=load)


def _border(indptr, indices, rows):
    """CSR layout of the FE pattern bordered by one row and column coupling `rows`."""
    n = len(indptr) - 1
    extra = np.zeros(n + 1, dtype=np.int64)
    extra[rows] = 1
    extra[n] = len(rows) + 1
    counts = np.append(np.diff(indptr), 0) + extra
    new_indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
    lengths = np.diff(indptr)
    row_of = np.repeat(np.arange(n), lengths)
    old_pos = new_indptr[row_of] + (np.arange(len(indices)) - indptr[row_of])
    col_pos = new_indptr[rows + 1] - 1
    last_pos = new_indptr[n] + np.arange(len(rows) + 1)
    new_indices = np.empty(new_indptr[-1], dtype=np.int32)
    new_indices[old_pos] = indices
    new_indices[col_pos] = n
    new_indices[last_pos] = np.append(rows, n)
    return rows, new_indptr, new_indices, old_pos, col_pos, last_pos


def start_vector(d):
    """The undeformed state: zeros, with the gas at its sealing pressure if sealed."""
    x = np.zeros(d.ndof)
    if d.cavity is not None and d.cavity.cavity.sealed:
        x[d.cavity.n_fe] = d.cavity.cavity.p0
    return x




class CavitySnap(InputError):
    """The free pressurised shell reaches a limit point (snaps) before it touches the plane."""

    def __init__(self, p_reached, p_target):
        self.p_reached, self.p_target = p_reached, p_target
        super().__init__(f"cavity: the free shell snaps (limit point) before contact: it "
                         f"holds p/C10 = {p_reached:.4g} of the {p_target:.4g} asked")


@dataclass(frozen=True, eq=False)
class Pressurised:
    """The free shell (rim held, no contact) under its cavity's pressure."""

    x: np.ndarray           # the state (rim at delta = 0)
    apex_uz: float          # u_z of the outer apex / R (< 0: it bulges toward the plane)
    ramp: tuple = ()        # (p, V, x) of each converged step of the pressure ramp


def _at(d, s):
    """`d` with its cavity's pressure (prescribed p, or sealing p0) scaled by s."""
    c = d.cavity.cavity
    return replace(d, cavity=replace(d.cavity, cavity=replace(c, p=s * c.p, p0=s * c.p0)))


def pressurise(d, settings: Settings = Settings(), c=None, steps: int = 4,
               max_steps: int = 200) -> Pressurised:
    """Ramp the cavity's pressure on the free shell (constraints `c`: default the rim held
    at delta = 0 and no contact), in about `steps` steps.

    A step that fails, or whose volume change jumps (more than 4 times the last step's
    per unit of load, or reverses), is halved; below 1e-3 of the load the shell is taken
    to have passed a limit point and CavitySnap says how far it got.
    """
    load = d.cavity
    target = load.cavity.p if not load.cavity.sealed else load.cavity.p0
    c = c if c is not None else constraints(d, "no_slip", [])
    x = start_vector(_at(d, 0.0))
    apex = d.n2 + d.capmesh.outer[0]
    if target == 0:
        return Pressurised(start_vector(d), 0.0, ())
    s, h, slope = 0.0, 1.0 / steps, None
    x_prev, h_prev = None, None
    ramp = []
    for _ in range(max_steps):
        if s >= 1.0 - 1e-12:
            break
        h = 1.0 - s if s + h > 1.0 - 1e-9 else h
        guess = x if x_prev is None else x + (x - x_prev) * (h / h_prev)
        ds = _at(d, s + h)
        try:
            with np.errstate(invalid="ignore", divide="ignore"):
                xn = _Problem(ds, "no_slip", settings, Timer()).newton(c, guess, 0.0)[0]
            jump = slope is not None and not 0 < (
                (ds.cavity.volume(xn) - load.volume(x)) / h) / slope < 4.0
        except ConvergenceError:
            jump = True
        if jump:
            h /= 2
            if h < 1e-3:
                raise CavitySnap(s * target, target)
            continue
        slope = (ds.cavity.volume(xn) - load.volume(x)) / h
        x_prev, h_prev, x, s = x, h, xn, s + h
        ramp.append((ds.cavity.pressure(xn), ds.cavity.volume(xn), xn))
        h = min(2 * h, 1.0 / steps)
    else:
        raise ConvergenceError(f"cavity: pressure ramp not done after {max_steps} steps")
    return Pressurised(x, float(x[apex]), tuple(ramp))


def lifted(d, dz: float):
    """`d` on its mesh moved up by dz (units of R), with the same cavity and material."""
    cm = d.capmesh
    mesh = MeshQuad2(np.ascontiguousarray(cm.mesh.doflocs + np.array([[0.0], [dz]])),
                     cm.mesh.t)
    moved = discretise(replace(cm, mesh=mesh), material=d.material)
    return moved if d.cavity is None else bind(moved, d.cavity.cavity)


def first_touch(d, settings: Settings = Settings()):
    """(d_touch, x0, pressurised): the pressurised free shell and its discretisation moved
    so that its apex just touches the plane at delta = 0 (delta is measured from there).

    Raises CavitySnap if the pressure makes the free shell snap, InputError if the
    pressurised shell's lowest point is off the axis (a dimpled apex touches first in a
    ring, which the loading does not start from).
    """
    if d.cavity is None:
        return d, np.zeros(d.ndof), Pressurised(np.zeros(d.ndof), 0.0)
    pr = pressurise(d, settings)
    cm = d.capmesh
    z = cm.nodes[1, cm.outer] + pr.x[d.n2 + cm.outer]
    if z.min() < z[0] - 1e-9:
        raise InputError(f"cavity: the pressurised shell's lowest point is off the axis (its "
                         f"apex dimples by {z[0] - z.min():.3g} R at p/C10 = "
                         f"{d.cavity.pressure(pr.x):.4g}); ring contact is not supported")
    return (d if pr.apex_uz == 0.0 else lifted(d, -pr.apex_uz)), pr.x, pr
