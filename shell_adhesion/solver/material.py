"""Incompressible neo-Hookean solid, W = C10 (I1bar - 3), in units of C10.

The deformation gradient of an axisymmetric body is carried as the 5-vector
f = (F_rr, F_rz, F_zr, F_zz, F_tt) (F_tt = 1 + u_r / r, the hoop stretch).
Incompressibility is imposed by a multiplier p: the Lagrangian density is
W(f) + p (J - 1), so p adds p * I to the Cauchy stress (p = minus the pressure).
"""
import numpy as np

_RR, _RZ, _ZR, _ZZ, _TT = range(5)


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


def energy(f):
    """Strain energy density W / C10 = I1bar - 3."""
    J = (f[_RR] * f[_ZZ] - f[_RZ] * f[_ZR]) * f[_TT]
    return J ** (-2.0 / 3.0) * np.sum(f * f, axis=0) - 3.0


def lagrangian_derivatives(f, p):
    """First and second derivatives of W(f) + p (J - 1) with respect to f, and J, dJ.

    Shapes: f (5, ...), p (...); returns dL (5, ...), d2L (5, 5, ...), J (...), dJ (5, ...).
    """
    J, dJ, d2J = jacobian(f)
    I1 = np.sum(f * f, axis=0)
    Jm23 = J ** (-2.0 / 3.0)
    Jm53 = Jm23 / J
    dW = 2.0 * Jm23 * f - (2.0 / 3.0) * I1 * Jm53 * dJ
    eye = np.eye(5).reshape((5, 5) + (1,) * (f.ndim - 1))
    d2W = (2.0 * Jm23 * eye
           - (4.0 / 3.0) * Jm53 * (f[:, None] * dJ[None, :] + dJ[:, None] * f[None, :])
           + (10.0 / 9.0) * I1 * Jm53 / J * dJ[:, None] * dJ[None, :]
           - (2.0 / 3.0) * I1 * Jm53 * d2J)
    return dW + p * dJ, d2W + p * d2J, J, dJ


def cauchy_stress(f, p):
    """Cauchy stress / C10 as (sigma_rr, sigma_zz, sigma_tt, sigma_rz)."""
    J, dJ, _ = jacobian(f)
    I1 = np.sum(f * f, axis=0)
    # Kirchhoff tau = 2 J^{-2/3} (b - I1/3 I) + p J I ; b = F F^T
    b_rr = f[_RR] ** 2 + f[_RZ] ** 2
    b_zz = f[_ZR] ** 2 + f[_ZZ] ** 2
    b_rz = f[_RR] * f[_ZR] + f[_RZ] * f[_ZZ]
    b_tt = f[_TT] ** 2
    c = 2.0 * J ** (-2.0 / 3.0)
    iso = I1 / 3.0
    tau = np.stack([c * (b_rr - iso), c * (b_zz - iso), c * (b_tt - iso), c * b_rz])
    tau[:3] += p * J
    return tau / J


def von_mises(sigma):
    """Von Mises equivalent of (sigma_rr, sigma_zz, sigma_tt, sigma_rz)."""
    s_rr, s_zz, s_tt, s_rz = sigma
    return np.sqrt(0.5 * ((s_rr - s_zz) ** 2 + (s_zz - s_tt) ** 2 + (s_tt - s_rr) ** 2)
                   + 3.0 * s_rz ** 2)
