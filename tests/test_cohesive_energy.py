"""Energy balance along a cohesive path (issue 23): the work of the rim load, the integral
of P d delta (P > 0 compression, delta > 0 approach) from the shell lifted clear of the
plane, equals the strain energy plus the interface energy (cohesion and the contact
penalty) at every state of the whole S (approach, jump-in, contact, retraction, pull-off,
separation), to 1e-4 of the path's energy scale max U + max |Pi|.

The work is integrated by solver.arclength.work (cubic Hermite steps with the path
tangents).  The path is traced with steps of at most 1/16 delta_c of gap change: with the
default 1/4 the quadrature error is itself 1e-4 (the penalty onset and the smooth-step are
kinks on that scale), with 1/16 it is 6e-6 (the trapezoidal rule: 1e-3).
"""
import numpy as np

from shell_adhesion.solver import maugis_dugdale as md
from shell_adhesion.solver.arclength import ArcSettings, trace, work
from shell_adhesion.solver.cohesive import CohesiveLaw, Interface
from shell_adhesion.solver.forms import discretise
from shell_adhesion.solver.geometry import Cap
from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

GAMMA_HAT, K_HAT, LAMBDA = 1.7e-4, 32 / 3, 0.3


def test_work_of_the_load_is_strain_plus_interface_energy():
    d = discretise(cap_mesh(Cap(1.0, 1.0), mesh_spec("coarse")))
    law = CohesiveLaw(md.sigma0_of(LAMBDA, GAMMA_HAT, 1.0, K_HAT), GAMMA_HAT)
    path = trace(Interface(d, law), 2e-3, settings=ArcSettings(dx_max=1 / 16))
    assert path.ended_by == "left the cohesive range" and path.turn > 0
    U, Pi = path.array("U"), path.array("Pi")
    assert np.all(np.isfinite(U)) and np.all(np.isfinite(Pi))
    E = (U - U[0]) + (Pi - Pi[0])
    W = work(path)
    scale = np.abs(U).max() + np.abs(Pi).max()
    # both energies matter: leaving either out would break the balance by far more than 1e-4
    assert U.max() > 0.1 * scale and -Pi.min() > 0.1 * scale and np.abs(E).max() > 0.3 * scale
    # contact is reached: the penalty is part of the balance
    assert path.states[path.turn].a > 0
    err = np.abs(W - E)
    print(f"{len(path.states)} states: max |W - (U + Pi)| = {err.max() / scale:.2e} of "
          f"max U + max |Pi| = {scale:.4g} C10 R^3")
    assert np.all(np.isfinite(W)) and err.max() <= 1e-4 * scale


def test_work_passes_folds():
    """An S with two folds in delta: delta = s^3 - s, P = s, so the integral of P d delta
    is 3 s^4 / 4 - s^2 / 2; a cubic Hermite per step is exact to the step's fourth power."""
    from shell_adhesion.solver.arclength import ArcPath, ArcState
    from shell_adhesion.solver.linear import Timer

    for n, tol in ((41, 1e-5), (161, 1e-7)):     # measured 2.3e-6, 8.9e-9
        s = np.linspace(-1.5, 1.5, n)
        states = tuple(ArcState(q ** 3 - q, q, 0.0, 0.0, 0.0, 0.0, 0, (3 * q * q - 1, 1.0))
                       for q in s)
        W = work(ArcPath(states, -1, "test", Timer()))
        exact = 0.75 * s ** 4 - 0.5 * s ** 2 - (0.75 * s[0] ** 4 - 0.5 * s[0] ** 2)
        assert np.abs(W - exact).max() <= tol * np.abs(exact).max()
