"""Validation 3: the JKR limit.  Solid hemisphere t = h = R = 20 mm, C10 = 0.3 MPa,
gamma = 1 J/m^2 (gamma / (C10 R) = 1.7e-4, so a*/R = 0.04: small strain).

Each case's deviations from JKR are the README's (Validation), held at twice the stated
value: the coarse mesh in every run (a few seconds each), the default mesh `slow`.  The
frictionless interface and the Mooney-Rivlin solid (JKR with E* = 8 (C10 + C01)) get the
same independent reference as the paper's no-slip neo-Hookean shell.
"""
import functools

import pytest

from shell_adhesion.solver import solve_paths
from shell_adhesion.solver.material import NEO_HOOKE, Material
from shell_adhesion.solver.scaling import gamma_hat

from validation import deviations_within, jkr_deviations

R_MM, C10, GAMMA = 20.0, 0.3, 1.0
MOONEY_RIVLIN = Material("mooney_rivlin", C01_over_C10=0.5)

# (mesh, interface, material): the README's deviations from JKR, P*, a*, P_dagger, a0
STATED = {
    ("coarse", "no_slip", "neo_hooke"): (-0.0055, -0.0070, -0.0185, -0.0058),
    ("coarse", "frictionless", "neo_hooke"): (-0.0042, -0.0052, -0.0182, -0.0044),
    ("coarse", "no_slip", "mooney_rivlin"): (-0.0238, -0.0295, -0.0176, -0.0237),
    ("default", "no_slip", "neo_hooke"): (-0.0020, -0.0035, -0.0221, -0.0018),
    ("default", "frictionless", "neo_hooke"): (-0.0010, -0.0021, -0.0215, -0.0007),
    ("default", "no_slip", "mooney_rivlin"): (-0.0032, -0.0036, -0.0205, -0.0031),
}
MATERIALS = {"neo_hooke": NEO_HOOKE, "mooney_rivlin": MOONEY_RIVLIN}


@functools.lru_cache(maxsize=None)
def jkr_pull_off(mesh, interface, material):
    """The solid hemisphere's pull-off at GAMMA (solved once per process: two tests read
    the coarse neo-Hookean one)."""
    g = gamma_hat(GAMMA, C10, R_MM)
    ps, _, _ = solve_paths(1.0, 1.0, interface, mesh, delta_max=0.011, gamma_max=1.25 * g,
                           material=material)
    return ps.pull_off(g)[1]


@pytest.mark.parametrize("case", [pytest.param(k, marks=[pytest.mark.slow] * (k[0] != "coarse"),
                                               id="-".join(k)) for k in STATED])
def test_pull_off_follows_jkr(case):
    mesh, interface, model = case
    material = MATERIALS[model]
    po = jkr_pull_off(mesh, interface, material)
    dev = jkr_deviations(po, R_MM, C10, GAMMA, material)
    print(case, {k: f"{100 * v:+.3f} %" for k, v in dev.items()})
    deviations_within(f"JKR {case}", dev, dict(zip(("P_star", "a_star", "P_dagger", "a0"),
                                                   STATED[case])))
    assert po.a_dagger < po.a_star < po.a0 and po.delta_dagger < po.delta_star


def test_jkr_check_fails_on_a_wrong_modulus():
    """The check can fail: the coarse neo-Hookean pull-off against JKR with a modulus 10 %
    too high (E* of C01 = 0.1 C10): JKR's a* and a0 move by 3 %, its P* does not (it is
    gamma's alone)."""
    po = jkr_pull_off("coarse", "no_slip", NEO_HOOKE)
    dev = jkr_deviations(po, R_MM, C10, GAMMA, Material("mooney_rivlin", C01_over_C10=0.1))
    with pytest.raises(AssertionError, match="a_star") as failed:
        deviations_within("JKR with E* x 1.1", dev, dict(zip(
            ("P_star", "a_star", "P_dagger", "a0"), STATED[("coarse", "no_slip", "neo_hooke")])))
    print(failed.value)
