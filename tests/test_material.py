"""Material models at a point: closed-form homogeneous stresses, consistent derivatives,
parameter checks (Drucker stability), and the Material record itself.

Closed forms (incompressible, W(I1, I2), W1 = dW/dI1, W2 = dW/dI2, axis z):
uniaxial sigma_zz - sigma_rr = 2 (l^2 - 1/l)(W1 + W2/l); equibiaxial (r, theta)
sigma_rr - sigma_zz = 2 (l^2 - l^-4)(W1 + l^2 W2); simple shear F_rz = g:
sigma_rz = 2 g (W1 + W2), sigma_rr - sigma_zz = 2 g^2 (W1 + W2), sigma_zz - sigma_tt = -2 g^2 W2.
Compressible pure dilation F = l I: sigma = dU/dJ = 2 (J - 1) / D1.
"""
import json
import math
import pickle

import numpy as np
import pytest

from shell_adhesion.solver.geometry import check_cap
from shell_adhesion.errors import InputError
from shell_adhesion.solver.scaling import check_finite
from shell_adhesion.solver.material import (NEO_HOOKE, Material, UnstableMaterial,
                                            cauchy_stress, energy, homogeneous_stress,
                                            lagrangian, lagrangian_derivatives)

C10 = 0.3   # MPa, for the dimensional closed forms
# (Material, W1(I1), W2) in MPa, written independently of the solver
CASES = {
    "neo_hooke": (Material(), lambda I1: C10, 0.0),
    "mooney_rivlin": (Material("mooney_rivlin", C01_over_C10=0.25), lambda I1: C10, 0.075),
    "yeoh": (Material("yeoh", C20_over_C10=-0.03, C30_over_C10=0.004),
             lambda I1: C10 - 2 * 0.009 * (I1 - 3) + 3 * 0.0012 * (I1 - 3) ** 2, 0.0),
    "gent": (Material("gent", Jm=20.0), lambda I1: C10 * 20.0 / (20.0 - (I1 - 3)), 0.0),
}
MODELS = list(CASES)


def f_of(F):
    """The 5-vector of a 3x3 F in (r, z, theta) coordinates."""
    F = np.asarray(F, dtype=float)
    return np.array([F[0, 0], F[0, 1], F[1, 0], F[1, 1], F[2, 2]])


def stress(m, F, p=0.0):
    s_rr, s_zz, s_tt, s_rz = C10 * cauchy_stress(f_of(F), p, m)
    return s_rr, s_zz, s_tt, s_rz


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("lam", [0.5, 0.8, 1.4, 2.5])
def test_uniaxial_closed_form(model, lam):
    m, W1, W2 = CASES[model]
    s_rr, s_zz, s_tt, s_rz = stress(m, np.diag([lam ** -0.5, lam, lam ** -0.5]))
    I1 = lam ** 2 + 2 / lam
    expected = 2 * (lam ** 2 - 1 / lam) * (W1(I1) + W2 / lam)
    assert s_zz - s_rr == pytest.approx(expected, rel=1e-12, abs=1e-14)
    assert s_tt == pytest.approx(s_rr, abs=1e-14) and s_rz == 0
    # the solver's own closed form (used by the stability check) agrees
    assert homogeneous_stress(m, "uniaxial", lam)[0] * C10 == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("lam", [0.7, 1.3, 1.9])
def test_equibiaxial_closed_form(model, lam):
    m, W1, W2 = CASES[model]
    s_rr, s_zz, s_tt, _ = stress(m, np.diag([lam, lam ** -2, lam]))
    I1 = 2 * lam ** 2 + lam ** -4
    expected = 2 * (lam ** 2 - lam ** -4) * (W1(I1) + lam ** 2 * W2)
    assert s_rr - s_zz == pytest.approx(expected, rel=1e-12)
    assert s_tt == pytest.approx(s_rr, rel=1e-12)
    assert homogeneous_stress(m, "equibiaxial", lam)[0] * C10 == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("lam", [0.6, 1.5])
def test_planar_closed_form(model, lam):
    m, W1, W2 = CASES[model]
    s_rr, s_zz, s_tt, _ = stress(m, np.diag([lam, 1 / lam, 1.0]))   # theta held
    I1 = lam ** 2 + 1 + lam ** -2
    expected = 2 * (lam ** 2 - lam ** -2) * (W1(I1) + W2)
    assert s_rr - s_zz == pytest.approx(expected, rel=1e-12)
    assert homogeneous_stress(m, "planar", lam)[0] * C10 == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("g", [0.3, 1.2])
def test_simple_shear_closed_form(model, g):
    m, W1, W2 = CASES[model]
    s_rr, s_zz, s_tt, s_rz = stress(m, [[1, g, 0], [0, 1, 0], [0, 0, 1]], p=0.37)
    k = W1(3 + g * g) + W2
    assert s_rz == pytest.approx(2 * g * k, rel=1e-12)
    assert s_rr - s_zz == pytest.approx(2 * g * g * k, rel=1e-12)
    assert s_zz - s_tt == pytest.approx(-2 * g * g * W2, rel=1e-12, abs=1e-14)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("lam", [0.95, 1.02])
def test_compressible_dilation(model, lam):
    """Pure dilation: the multiplier that makes dL/dp = 0 is dU/dJ, the stress is p I."""
    base = CASES[model][0]
    D1 = 0.05                                          # 1/MPa
    m = Material(base.model, base.C01_over_C10, base.C20_over_C10, base.C30_over_C10,
                 base.Jm, D1 * C10)
    f = f_of(np.eye(3) * lam)
    J = lam ** 3
    p = 2 * (J - 1) / (D1 * C10)                       # units of C10
    *_, dLdp, d2Ldp2 = lagrangian_derivatives(f, np.float64(p), m)
    assert abs(dLdp) < 1e-14 and d2Ldp2 == -0.5 * D1 * C10
    s = stress(m, np.eye(3) * lam, p)
    np.testing.assert_allclose(s[:3], 2 * (J - 1) / D1, rtol=1e-12)
    assert abs(s[3]) < 1e-15
    # eliminating p leaves W + (J - 1)^2 / D1
    L = C10 * lagrangian(f, p, m)
    assert L == pytest.approx(C10 * energy(f, m) + (J - 1) ** 2 / D1, rel=1e-12)


def _random_states(n=7, seed=3):
    rng = np.random.default_rng(seed)
    f = np.eye(3)[[0, 0, 1, 1, 2], [0, 1, 0, 1, 2]][:, None] + 0.3 * rng.standard_normal((5, n))
    f[4] = 1 + 0.3 * rng.random(n)
    f[0] = np.abs(f[0]) + 0.5
    f[3] = np.abs(f[3]) + 0.5
    return f, rng.standard_normal(n)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("D1_C10", [0.0, 0.2])
def test_derivatives_match_finite_differences(model, D1_C10):
    base = CASES[model][0]
    m = Material(base.model, base.C01_over_C10, base.C20_over_C10, base.C30_over_C10,
                 base.Jm, D1_C10)
    f, p = _random_states()
    dL, d2L, J, dJ, dLdp, d2Ldp2 = lagrangian_derivatives(f, p, m)
    eps = 1e-6
    for k in range(5):
        e = np.zeros_like(f)
        e[k] = eps
        fd = (lagrangian(f + e, p, m) - lagrangian(f - e, p, m)) / (2 * eps)
        np.testing.assert_allclose(dL[k], fd, rtol=1e-7, atol=1e-8)
        dp, dm = lagrangian_derivatives(f + e, p, m)[0], lagrangian_derivatives(f - e, p, m)[0]
        np.testing.assert_allclose(d2L[:, k], (dp - dm) / (2 * eps), rtol=1e-6, atol=1e-7)
    fd = (lagrangian(f, p + eps, m) - lagrangian(f, p - eps, m)) / (2 * eps)
    np.testing.assert_allclose(dLdp, fd, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(dJ, (lagrangian_derivatives(f, p + eps, m)[0]
                                    - lagrangian_derivatives(f, p - eps, m)[0]) / (2 * eps),
                               rtol=1e-7, atol=1e-8)
    assert np.allclose(d2L, d2L.transpose(1, 0, 2), rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("model", MODELS)
def test_stress_is_the_derivative_of_W(model):
    """sigma = (dL/dF) F^T / J, with dL/dF the solver's own derivative."""
    m = CASES[model][0]
    f, p = _random_states()
    P = lagrangian_derivatives(f, p, m)[0]
    J = (f[0] * f[3] - f[1] * f[2]) * f[4]
    expected = np.stack([(P[0] * f[0] + P[1] * f[1]) / J, (P[2] * f[2] + P[3] * f[3]) / J,
                         P[4] * f[4] / J, (P[0] * f[2] + P[1] * f[3]) / J])
    np.testing.assert_allclose(cauchy_stress(f, p, m), expected, rtol=1e-11, atol=1e-12)


def test_reductions_at_a_point():
    f, p = _random_states()
    nh = lagrangian_derivatives(f, p)
    for m in (Material("mooney_rivlin"), Material("yeoh")):
        for a, b in zip(nh, lagrangian_derivatives(f, p, m)):
            assert np.array_equal(a, b)
    for Jm, tol in ((1e3, 1e-2), (1e6, 1e-5)):
        g = lagrangian_derivatives(f, p, Material("gent", Jm=Jm))
        assert np.abs(g[1] - nh[1]).max() < tol * np.abs(nh[1]).max()


def test_material_record():
    m = Material("mooney_rivlin", C01_over_C10=0.2, D1_times_C10=3e-6)
    assert m == Material.from_dict(json.loads(json.dumps(m.as_dict())))
    assert m == pickle.loads(pickle.dumps(m))      # shipped to relaxation tasks
    assert hash(m) == hash(Material("mooney_rivlin", 0.2, 0, 0, None, 3e-6))
    assert Material() == NEO_HOOKE and NEO_HOOKE.mu0 == 2.0 and not NEO_HOOKE.compressible
    assert m.mu0 == pytest.approx(2.4) and m.bulk_modulus == pytest.approx(2 / 3e-6)
    mp = Material.from_MPa("mooney_rivlin", C10_MPa=0.3, C01_MPa=0.06, D1_per_MPa=1e-5)
    assert mp.C01_over_C10 == pytest.approx(0.2) and mp.D1_times_C10 == pytest.approx(3e-6)


@pytest.mark.parametrize("kwargs, message", [
    (dict(model="ogden"), "material: 'ogden' must be one of"),
    (dict(model="yeoh", C01_over_C10=0.1), "C01_over_C10: 0.1 is not a coefficient of the yeoh"),
    (dict(model="gent"), "Jm: the gent model needs Jm"),
    (dict(model="gent", Jm=-3.0), "Jm: -3 must be > 0"),
    (dict(model="yeoh", C20_over_C10=math.nan), "C20_over_C10: nan must be a finite number"),
    (dict(D1_times_C10=-1e-3), "D1: -0.001 (times C10) must be >= 0"),
])
def test_bad_parameters_refused(kwargs, message):
    with pytest.raises(InputError) as e:
        Material(**kwargs)
    assert message in str(e.value) and "\n" not in str(e.value)


@pytest.mark.parametrize("kwargs, message", [
    (dict(model="yeoh", C01_MPa=0.05), "C01: 0.05 is not a coefficient of the yeoh model "
                                       "(C10, C20, C30, D1)"),
    (dict(model="neo_hooke", Jm=20), "Jm: 20 is not a coefficient of the neo_hooke model"),
    (dict(C10_MPa=0.0), "C10_MPa: 0.0 must be a number > 0"),
    (dict(D1_per_MPa=-0.01), "D1: -0.01 /MPa must be >= 0"),
    (dict(model="gent", Jm="20"), "Jm: '20' must be a finite number"),
])
def test_bad_coefficients_in_MPa_refused(kwargs, message):
    with pytest.raises(InputError) as e:
        Material.from_MPa(**({"C10_MPa": 0.3} | kwargs))
    assert message in str(e.value) and "\n" not in str(e.value)


def test_numpy_scalars_are_numbers():
    m = Material.from_MPa("mooney_rivlin", C10_MPa=np.float32(0.3), C01_MPa=np.int64(0))
    assert m == Material("mooney_rivlin") and type(m.C01_over_C10) is float


@pytest.mark.parametrize("call, message", [
    (lambda: Material("yeoh", C20_over_C10=np.float64(np.nan)),
     "C20_over_C10: nan must be a finite number"),
    (lambda: Material.from_MPa("neo_hooke", C10_MPa=np.float64(-0.3)),
     "C10_MPa: -0.3 must be a number > 0"),
    (lambda: Material.from_MPa("yeoh", C10_MPa=0.3, C01_MPa=np.float64(0.05)),
     "C01: 0.05 is not a coefficient of the yeoh model"),
    (lambda: check_cap(np.float64(np.inf), 1.0), "t/R: inf must be a finite number"),
    (lambda: check_finite(np.float32(np.nan), "gamma"), "gamma: nan must be a finite number"),
])
def test_numpy_scalars_print_as_plain_numbers(call, message):
    """Messages show numbers as numbers, never numpy's repr (np.float64(...))."""
    with pytest.raises(InputError) as e:
        call()
    assert message in str(e.value) and "np." not in str(e.value)


def test_unstable_sets_refused_with_the_stretch():
    # Yeoh with a strongly negative C20: W1 = C10 + 2 C20 (I1 - 3) vanishes in tension
    with pytest.raises(UnstableMaterial) as e:
        Material.from_MPa("yeoh", C10_MPa=0.3, C20_MPa=-0.05, C30_MPa=0.0)
    msg = str(e.value)
    assert "yeoh (C10 = 0.3 MPa, C20 = -0.05 MPa, C30 = 0 MPa)" in msg and "\n" not in msg
    assert e.value.mode in ("uniaxial", "equibiaxial", "planar")
    # the reported stretch is a real loss of stiffness: stiff just inside, not at it
    m = e.value.material
    _, k = homogeneous_stress(m, e.value.mode, e.value.stretch)
    assert k <= 0
    assert f"at stretch {e.value.stretch:.3g}" in msg
    # Mooney-Rivlin with C10 + C01 <= 0 has no small-strain stiffness
    with pytest.raises(UnstableMaterial, match=r"mooney_rivlin \(C01/C10 = -1\).*stretch 1"):
        Material("mooney_rivlin", C01_over_C10=-1.0)
    # typical fitted silicone sets are accepted
    Material.from_MPa("yeoh", C10_MPa=0.3, C20_MPa=-0.01, C30_MPa=0.002)
    Material.from_MPa("mooney_rivlin", C10_MPa=0.3, C01_MPa=0.05)
    Material.from_MPa("gent", C10_MPa=0.3, Jm=20)
