"""Hyperelastic solids with ABAQUS's names and conventions, in units of C10.

Isochoric invariants I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2; x = I1bar - 3.  Strain energy
densities (ABAQUS's forms, so fitted coefficients carry over):

- neo_hooke:      W = C10 (I1bar - 3)
- mooney_rivlin:  W = C10 (I1bar - 3) + C01 (I2bar - 3)
- yeoh:           W = C10 x + C20 x^2 + C30 x^3
- gent:           W = -C10 Jm ln(1 - x / Jm)        (Gent 1996, shear modulus mu = 2 C10;
                  W -> C10 x as Jm -> infinity; states need x < Jm)

plus U = (J - 1)^2 / D1 (D1 in 1/MPa) for a compressible solid, any model; D1 = 0 is
incompressible.  Small-strain shear modulus mu0 = 2 (C10 + C01), bulk modulus K = 2 / D1.

The solver works with W / C10, so a `Material` holds the ratios C01/C10, C20/C10, C30/C10,
Jm and D1 C10.  The deformation gradient of an axisymmetric body is carried as the 5-vector
f = (F_rr, F_rz, F_zr, F_zz, F_tt) (F_tt = 1 + u_r / r, the hoop stretch).  Mixed u-p with
the multiplier p (units of C10): the Lagrangian density is the perturbed

    L(f, p) = W(f) + p (J - 1) - (D1 C10 / 4) p^2,

stationary in p at p = 2 (J - 1) / (D1 C10), where it equals W + (J - 1)^2 / (D1 C10); at
D1 = 0 it is the incompressible W + p (J - 1).  p adds p * I to the Cauchy stress (p = minus
the pressure).
"""
from dataclasses import asdict, dataclass
import math
import numbers

import numpy as np

from .geometry import shown
from shell_adhesion.errors import InputError

_RR, _RZ, _ZR, _ZZ, _TT = range(5)

MODELS = ("neo_hooke", "mooney_rivlin", "yeoh", "gent")
# coefficients (besides C10 and D1) of each model, as (field, ABAQUS name)
_COEFFICIENTS = {"neo_hooke": (), "mooney_rivlin": (("C01_over_C10", "C01"),),
                 "yeoh": (("C20_over_C10", "C20"), ("C30_over_C10", "C30")),
                 "gent": (("Jm", "Jm"),)}
STABILITY_STRETCHES = np.geomspace(0.2, 5.0, 401)   # Drucker check, homogeneous stretches
MODES = ("uniaxial", "equibiaxial", "planar")


@dataclass(frozen=True)
class Material:
    """A hyperelastic solid in units of C10 (hashable, `as_dict` is JSON-able).

    `model` is one of MODELS; the ratios of the coefficients a model does not use stay 0
    (Jm None).  D1_times_C10 = D1 C10 >= 0 (0: incompressible).  Construction checks the
    parameters, including Drucker stability (see `stability_failure`), and raises InputError.
    """

    model: str = "neo_hooke"
    C01_over_C10: float = 0.0
    C20_over_C10: float = 0.0
    C30_over_C10: float = 0.0
    Jm: float = None
    D1_times_C10: float = 0.0

    def __post_init__(self):
        if self.model not in MODELS:
            raise InputError(f"material: {self.model!r} must be one of {', '.join(MODELS)}")
        used = {f for f, _ in _COEFFICIENTS[self.model]}
        for name in ("C01_over_C10", "C20_over_C10", "C30_over_C10", "Jm", "D1_times_C10"):
            value = getattr(self, name)
            if value is None and name == "Jm":
                if "Jm" in used:
                    raise InputError("Jm: the gent model needs Jm (a number > 0)")
                continue
            if not _is_number(value):
                raise InputError(f"{name}: {shown(value)} must be a finite number")
            object.__setattr__(self, name, float(value))
            if name not in used and name != "D1_times_C10" and value != 0:
                raise InputError(f"{name}: {value:g} is not a coefficient of the "
                                 f"{self.model} model (leave it out)")
        if self.Jm is not None and not self.Jm > 0:
            raise InputError(f"Jm: {self.Jm:g} must be > 0")
        if not self.D1_times_C10 >= 0:
            raise InputError(f"D1: {self.D1_times_C10:g} (times C10) must be >= 0")
        failure = stability_failure(self)
        if failure is not None:
            raise UnstableMaterial(self, *failure)

    @classmethod
    def from_MPa(cls, model="neo_hooke", C10_MPa=1.0, C01_MPa=0.0, C20_MPa=0.0, C30_MPa=0.0,
                 Jm=None, D1_per_MPa=0.0):
        """The Material of ABAQUS coefficients in MPa (D1 in 1/MPa); C10_MPa stays the scale."""
        if not _is_number(C10_MPa) or not C10_MPa > 0:
            raise InputError(f"C10_MPa: {shown(C10_MPa)} must be a number > 0")
        values = dict(C01=C01_MPa, C20=C20_MPa, C30=C30_MPa)
        for name, value in (*values.items(), ("D1", D1_per_MPa)):
            if not _is_number(value):
                raise InputError(f"{name}: {shown(value)} must be a finite number")
        if model in MODELS:
            used = [n for _, n in _COEFFICIENTS[model]]
            for name, value in (*values.items(), ("Jm", Jm)):
                if name not in used and value is not None and value != 0:
                    raise InputError(f"{name}: {shown(value)} is not a coefficient of the {model} "
                                     f"model ({', '.join(['C10', *used, 'D1'])})")
        if not D1_per_MPa >= 0:
            raise InputError(f"D1: {D1_per_MPa:g} /MPa must be >= 0 (0: incompressible)")
        try:
            return cls(model, C01_MPa / C10_MPa, C20_MPa / C10_MPa, C30_MPa / C10_MPa, Jm,
                       D1_per_MPa * C10_MPa)
        except UnstableMaterial as e:
            raise UnstableMaterial(e.material, e.mode, e.stretch, C10_MPa) from None

    @property
    def compressible(self) -> bool:
        return self.D1_times_C10 > 0

    @property
    def mu0(self) -> float:
        """Small-strain shear modulus / C10: 2 (1 + C01/C10)."""
        return 2.0 * (1.0 + self.C01_over_C10)

    @property
    def bulk_modulus(self) -> float:
        """Small-strain bulk modulus / C10: 2 / (D1 C10), inf if incompressible."""
        return 2.0 / self.D1_times_C10 if self.compressible else math.inf

    def coefficients(self, C10_MPa=None) -> str:
        """The model's coefficients as text, in MPa if C10_MPa is given, else as ratios."""
        if C10_MPa is None:
            parts = [f"{n}/C10 = {getattr(self, f):g}" if n != "Jm" else f"Jm = {self.Jm:g}"
                     for f, n in _COEFFICIENTS[self.model]]
            if self.compressible:
                parts.append(f"D1 C10 = {self.D1_times_C10:g}")
        else:
            parts = [f"C10 = {C10_MPa:g} MPa"]
            parts += [f"{n} = {getattr(self, f) * C10_MPa:g} MPa" if n != "Jm"
                      else f"Jm = {self.Jm:g}" for f, n in _COEFFICIENTS[self.model]]
            if self.compressible:
                parts.append(f"D1 = {self.D1_times_C10 / C10_MPa:g} /MPa")
        return f"{self.model}" + (f" ({', '.join(parts)})" if parts else "")

    def as_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict):
        return cls(**d)


def _is_number(value) -> bool:
    """A finite real number (numpy scalars included, booleans not)."""
    return (isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))
            and math.isfinite(value))


class UnstableMaterial(InputError):
    """A parameter set that fails Drucker's condition in a homogeneous test."""

    def __init__(self, material, mode, stretch, C10_MPa=None):
        self.material, self.mode, self.stretch = material, mode, stretch
        super().__init__(
            f"material: {material.coefficients(C10_MPa)} is unstable (Drucker): the "
            f"{mode} tangent stiffness d sigma / d stretch is <= 0 at stretch {stretch:.3g} "
            f"(checked over stretches 0.2 to 5)")


# ----------------------------------------------------------------- W as a function of x

def _dg(m: Material, x):
    """dW/dI1bar and d2W/dI1bar^2 (units of C10) at x = I1bar - 3; (1, 0) for neo-Hooke."""
    if m.model == "yeoh":
        c2, c3 = m.C20_over_C10, m.C30_over_C10
        return 1.0 + 2.0 * c2 * x + 3.0 * c3 * x * x, 2.0 * c2 + 6.0 * c3 * x
    if m.model == "gent":
        g1 = m.Jm / (m.Jm - x)
        return g1, g1 * g1 / m.Jm
    return 1.0, 0.0


def _g(m: Material, x):
    if m.model == "yeoh":
        return x + m.C20_over_C10 * x ** 2 + m.C30_over_C10 * x ** 3
    if m.model == "gent":
        return -m.Jm * np.log1p(-x / m.Jm)
    return x


# ------------------------------------------------------------- Drucker stability check

def homogeneous_stress(m: Material, mode: str, lam):
    """Closed-form incompressible Cauchy stress / C10 and its derivative in the stretch.

    uniaxial sigma = 2 (l^2 - 1/l)(W1 + W2/l); equibiaxial sigma = 2 (l^2 - l^-4)(W1 + l^2 W2);
    planar (pure shear) sigma = 2 (l^2 - l^-2)(W1 + W2); W1 = dW/dI1, W2 = dW/dI2 = C01.
    Returns (sigma, dsigma/dlam).
    """
    lam = np.asarray(lam, dtype=float)
    if mode == "uniaxial":
        I1, dI1 = lam ** 2 + 2 / lam, 2 * lam - 2 / lam ** 2
        s, ds = lam ** 2 - 1 / lam, 2 * lam + 1 / lam ** 2
        h, dh = 1 / lam, -1 / lam ** 2
    elif mode == "equibiaxial":
        I1, dI1 = 2 * lam ** 2 + lam ** -4, 4 * lam - 4 * lam ** -5
        s, ds = lam ** 2 - lam ** -4, 2 * lam + 4 * lam ** -5
        h, dh = lam ** 2, 2 * lam
    elif mode == "planar":
        I1, dI1 = lam ** 2 + 1 + lam ** -2, 2 * lam - 2 * lam ** -3
        s, ds = lam ** 2 - lam ** -2, 2 * lam + 2 * lam ** -3
        h, dh = np.ones_like(lam), np.zeros_like(lam)
    else:
        raise ValueError(f"mode {mode!r} must be one of {MODES}")
    W1, W11 = _dg(m, I1 - 3.0)
    W2 = m.C01_over_C10
    sigma = 2 * s * (W1 + h * W2)
    return sigma, 2 * ds * (W1 + h * W2) + 2 * s * (W11 * dI1 + dh * W2)


def stability_failure(m: Material, stretches=STABILITY_STRETCHES):
    """(mode, stretch) of the first homogeneous state with d sigma / d stretch <= 0, or None.

    Drucker's condition for the incompressible solid in uniaxial, equibiaxial and planar
    deformation (tension and compression) over `stretches`; a Gent solid is checked only
    where I1 - 3 < Jm (the states beyond are unreachable: W locks up).
    """
    for mode in MODES:
        lam = np.asarray(stretches, dtype=float)
        if m.model == "gent":
            I1 = homogeneous_invariant(mode, lam)
            lam = lam[I1 - 3.0 < m.Jm * (1 - 1e-9)]
        _, k = homogeneous_stress(m, mode, lam)
        bad = np.flatnonzero(~(k > 0))
        if len(bad):
            # the failing stretch nearest 1 (where the loss of stability begins)
            j = bad[np.argmin(np.abs(np.log(lam[bad])))]
            return mode, float(lam[j])
    return None


def homogeneous_invariant(mode, lam):
    """I1 of the incompressible homogeneous deformation `mode` at stretch lam."""
    lam = np.asarray(lam, dtype=float)
    return {"uniaxial": lambda: lam ** 2 + 2 / lam,
            "equibiaxial": lambda: 2 * lam ** 2 + lam ** -4,
            "planar": lambda: lam ** 2 + 1 + lam ** -2}[mode]()


NEO_HOOKE = Material()


# ------------------------------------------------------------------ kinematics and W

def jacobian(f):
    """J = det F and its first and second derivatives with respect to f."""
    j2 = f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]
    J = j2 * f[_TT]
    dJ = np.stack([f[_ZZ] * f[_TT], -f[_ZR] * f[_TT], -f[_RZ] * f[_TT], f[_RR] * f[_TT], j2])
    d2J = np.zeros((5, 5) + f.shape[1:])
    for a, b, v in ((_RR, _ZZ, f[_TT]), (_RZ, _ZR, -f[_TT]), (_RR, _TT, f[_ZZ]),
                    (_ZZ, _TT, f[_RR]), (_RZ, _TT, -f[_ZR]), (_ZR, _TT, -f[_RZ])):
        d2J[a, b] = v
        d2J[b, a] = v
    return J, dJ, d2J


def _I2(f):
    """I2 = det(C_2d) + F_tt^2 tr(C_2d) of the axisymmetric F and its derivatives."""
    j2 = f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]
    s2 = f[_RR] ** 2 + f[_RZ] ** 2 + f[_ZR] ** 2 + f[_ZZ] ** 2
    t2 = f[_TT] ** 2
    I2 = j2 * j2 + t2 * s2
    dj2 = np.stack([f[_ZZ], -f[_ZR], -f[_RZ], f[_RR]])
    dI2 = np.concatenate([2.0 * j2 * dj2 + 2.0 * t2 * f[:4], [2.0 * f[_TT] * s2]])
    d2I2 = np.zeros((5, 5) + f.shape[1:])
    d2I2[:4, :4] = 2.0 * dj2[:, None] * dj2[None, :]
    for k in range(4):
        d2I2[k, k] += 2.0 * t2
    for a, b, v in ((_RR, _ZZ, 1.0), (_RZ, _ZR, -1.0)):
        d2I2[a, b] += 2.0 * j2 * v
        d2I2[b, a] += 2.0 * j2 * v
    d2I2[:4, _TT] = 4.0 * f[_TT] * f[:4]
    d2I2[_TT, :4] = d2I2[:4, _TT]
    d2I2[_TT, _TT] = 2.0 * s2
    return I2, dI2, d2I2


def limit_exceeded(f, m: Material):
    """Largest (I1bar - 3) / Jm over f for a Gent solid (a state needs < 1); 0 otherwise."""
    if m.model != "gent":
        return 0.0
    J = (f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]) * f[_TT]
    with np.errstate(invalid="ignore", divide="ignore"):
        x = J ** (-2.0 / 3.0) * np.sum(f * f, axis=0) - 3.0
    return float(np.nanmax(x, initial=-np.inf)) / m.Jm   # NaN: an inverted point


def limit_state(f, m: Material):
    """Where a Gent solid is nearest its limit: ((I1bar - 3) / Jm, I1bar, largest principal
    stretch) at the worst point of f; None for another model or where every point is
    inverted.  A state needs (I1bar - 3) / Jm < 1."""
    if m.model != "gent":
        return None
    J = (f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]) * f[_TT]
    with np.errstate(invalid="ignore", divide="ignore"):
        I1bar = J ** (-2.0 / 3.0) * np.sum(f * f, axis=0)
    if not np.isfinite(I1bar).any():
        return None
    k = np.unravel_index(np.nanargmax(I1bar), I1bar.shape)
    F = f[(slice(None),) + k]
    # in-plane stretches: singular values of [[F_rr, F_rz], [F_zr, F_zz]]; F_tt the hoop one
    s_in = np.linalg.svd(np.array([[F[_RR], F[_RZ]], [F[_ZR], F[_ZZ]]]), compute_uv=False)
    return (float(I1bar[k] - 3.0) / m.Jm, float(I1bar[k]),
            float(max(s_in.max(), abs(F[_TT]))))


def energy(f, m: Material = NEO_HOOKE):
    """Isochoric strain energy density W / C10 (for neo-Hooke, I1bar - 3)."""
    J = (f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]) * f[_TT]
    x = J ** (-2.0 / 3.0) * np.sum(f * f, axis=0) - 3.0
    W = _g(m, x)
    if m.C01_over_C10:
        W = W + m.C01_over_C10 * (J ** (-4.0 / 3.0) * _I2(f)[0] - 3.0)
    return W


def lagrangian(f, p, m: Material = NEO_HOOKE):
    """L / C10 = W + p (J - 1) - (D1 C10 / 4) p^2."""
    J = (f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]) * f[_TT]
    return energy(f, m) + p * (J - 1.0) - 0.25 * m.D1_times_C10 * p * p


def lagrangian_derivatives(f, p, m: Material = NEO_HOOKE):
    """Derivatives of L(f, p) = W(f) + p (J - 1) - (D1 C10 / 4) p^2 (units of C10).

    Shapes: f (5, ...), p (...).  Returns dL/df (5, ...), d2L/df2 (5, 5, ...), J (...),
    dJ (5, ...) (= d2L/df dp), dL/dp (...) and d2L/dp2 (a number).
    """
    # d2L = (dense outer products) + c_eye * I + c_J * d2J: the identity and the sparse d2J
    # (six symmetric pairs) are added entry by entry, not as (5, 5, ...) arrays
    j2 = f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]
    J = j2 * f[_TT]
    dJ = np.stack([f[_ZZ] * f[_TT], -f[_ZR] * f[_TT], -f[_RZ] * f[_TT], f[_RR] * f[_TT], j2])
    I1 = np.sum(f * f, axis=0)
    Jm23 = J ** (-2.0 / 3.0)
    Jm53 = Jm23 / J
    # I1bar: the whole of neo-Hooke
    dW = 2.0 * Jm23 * f - (2.0 / 3.0) * I1 * Jm53 * dJ
    a = (4.0 / 3.0) * Jm53
    d2W = dJ[:, None] * ((10.0 / 9.0) * I1 * Jm53 / J * dJ - a * f)[None, :]
    d2W -= (a * f)[:, None] * dJ[None, :]
    c_eye, c_J = 2.0 * Jm23, -(2.0 / 3.0) * I1 * Jm53
    if m.model in ("yeoh", "gent"):
        g1, g2 = _dg(m, Jm23 * I1 - 3.0)
        d2W *= g1
        d2W += g2 * dW[:, None] * dW[None, :]
        c_eye, c_J = g1 * c_eye, g1 * c_J
        dW = g1 * dW
    if m.C01_over_C10:
        c = m.C01_over_C10
        I2, dI2, d2I2 = _I2(f)
        Jm43 = Jm23 * Jm23
        Jm73 = Jm43 / J
        dW = dW + c * (Jm43 * dI2 - (4.0 / 3.0) * I2 * Jm73 * dJ)
        d2W += c * (Jm43 * d2I2
                    - (4.0 / 3.0) * Jm73 * (dI2[:, None] * dJ[None, :]
                                            + dJ[:, None] * dI2[None, :])
                    + (28.0 / 9.0) * I2 * Jm73 / J * dJ[:, None] * dJ[None, :])
        c_J = c_J - c * (4.0 / 3.0) * I2 * Jm73
    for k in range(5):
        d2W[k, k] += c_eye
    c_J = c_J + p                                      # p d2J: the multiplier's part
    for i, j, v in ((_RR, _ZZ, f[_TT]), (_RZ, _ZR, -f[_TT]), (_RR, _TT, f[_ZZ]),
                    (_ZZ, _TT, f[_RR]), (_RZ, _TT, -f[_ZR]), (_ZR, _TT, -f[_RZ])):
        cv = c_J * v
        d2W[i, j] += cv
        d2W[j, i] += cv
    if m.compressible:
        dLdp, d2Ldp2 = (J - 1.0) - 0.5 * m.D1_times_C10 * p, -0.5 * m.D1_times_C10
    else:
        dLdp, d2Ldp2 = J - 1.0, 0.0
    return dW + p * dJ, d2W, J, dJ, dLdp, d2Ldp2


def cauchy_stress(f, p, m: Material = NEO_HOOKE):
    """Cauchy stress / C10 as (sigma_rr, sigma_zz, sigma_tt, sigma_rz).

    Kirchhoff tau = 2 W1 dev(bbar) + 2 W2 dev(I1bar bbar - bbar^2) + p J I, bbar = J^(-2/3) F F^T,
    W1 = dW/dI1bar, W2 = dW/dI2bar.
    """
    J, dJ, _ = jacobian(f)
    I1 = np.sum(f * f, axis=0)
    b_rr = f[_RR] ** 2 + f[_RZ] ** 2
    b_zz = f[_ZR] ** 2 + f[_ZZ] ** 2
    b_rz = f[_RR] * f[_ZR] + f[_RZ] * f[_ZZ]
    b_tt = f[_TT] ** 2
    c = 2.0 * J ** (-2.0 / 3.0)
    if m.model in ("yeoh", "gent"):
        c = c * _dg(m, 0.5 * c * I1 - 3.0)[0]
    iso = I1 / 3.0
    tau = np.stack([c * (b_rr - iso), c * (b_zz - iso), c * (b_tt - iso), c * b_rz])
    if m.C01_over_C10:
        # bbar^2 of the block-diagonal b
        s = J ** (-2.0 / 3.0)
        I1b = s * I1
        bb = s * np.stack([b_rr, b_zz, b_tt, b_rz])
        bb2 = np.stack([bb[0] ** 2 + bb[3] ** 2, bb[1] ** 2 + bb[3] ** 2, bb[2] ** 2,
                        bb[3] * (bb[0] + bb[1])])
        A = I1b * bb - bb2
        A[:3] -= (A[0] + A[1] + A[2]) / 3.0
        tau = tau + 2.0 * m.C01_over_C10 * A
    tau[:3] += p * J
    return tau / J


def von_mises(sigma):
    """Von Mises equivalent of (sigma_rr, sigma_zz, sigma_tt, sigma_rz)."""
    s_rr, s_zz, s_tt, s_rz = sigma
    return np.sqrt(0.5 * ((s_rr - s_zz) ** 2 + (s_zz - s_tt) ** 2 + (s_tt - s_rr) ** 2)
                   + 3.0 * s_rz ** 2)
