"""Benchmark: the frictionless loading curve of the base shell in FElupe, for a side-by-side
time with ours (issue 11).  Needs the `bench` extra: python -m pip install -e ".[bench]".

The same problem as `benchmarks/loading.py ... frictionless`: the hemispherical shell
R = h = 20 mm, t = 3 mm, incompressible neo-Hooke C10 = 0.3 MPa (FElupe: three-field
u/p/J with a bulk modulus 5000 mu), axisymmetric, the rim face pushed down by 5 mm with
u_r = 0 there, u_r = 0 on the axis, frictionless contact with the rigid plane under the
apex (FElupe: `ContactRigidPlane`, a penalty scaled by the solid's mean stiffness).  Mesh:
biquadratic quads (Quad9), 64 along the meridian (even in the polar angle) by 8 through
the thickness; 20 equal load steps, FElupe's Newton tolerance 1e-8 (its residual norm, N).
FElupe's axisymmetric fields take x as the axial coordinate and y as the radius.

Run: python benchmarks/felupe_loading.py [n_arc n_thick steps]
"""
import sys
import time

import numpy as np

R_MM, T_MM, C10_MPA, DELTA_MM = 20.0, 3.0, 0.3, 5.0


def felupe_loading(n_arc=64, n_thick=8, steps=20):
    """(dofs, Newton iterations, wall s, P(delta) in N for every step) of FElupe's run;
    ImportError if FElupe is not installed."""
    import felupe as fem

    t0 = time.perf_counter()
    mesh = fem.Rectangle(n=(n_arc + 1, n_thick + 1)).convert(order=2, calc_midfaces=True)
    s, d = mesh.points.T                           # s: along the meridian, d = 1: outer
    theta = 0.5 * np.pi * s
    rho = R_MM - T_MM * (1.0 - d)
    points = np.column_stack([R_MM - rho * np.cos(theta), rho * np.sin(theta)])
    points[np.isclose(s, 0.0), 1] = 0.0            # exactly on the axis
    points[np.isclose(s, 1.0), 0] = R_MM           # exactly on the rim plane
    plane = len(points)                            # the plane's reference point (no cell)
    mesh.update(points=np.vstack([points, [[0.0, -R_MM]]]))

    region = fem.RegionBiQuadraticQuad(mesh)
    field = fem.FieldsMixed(region, n=3, axisymmetric=True)
    mu = 2.0 * C10_MPA
    solid = fem.SolidBody(fem.ThreeFieldVariation(fem.NeoHooke(mu=mu, bulk=5000.0 * mu)), field)
    outer = np.flatnonzero(np.isclose(d, 1.0))
    contact = fem.ContactRigidPlane(field, outer, plane, normal=[1.0, 0.0], friction=0.0,
                                    items=[solid])
    boundaries = {
        "axis": fem.Boundary(field[0], fy=0.0, skip=(True, False)),
        "rim_r": fem.Boundary(field[0], fx=R_MM, skip=(True, False)),
        "rim_z": fem.Boundary(field[0], fx=R_MM, skip=(False, True)),
        "plane": fem.Boundary(field[0], mask=np.arange(mesh.npoints) == plane),
    }
    ramp = {boundaries["rim_z"]: -np.linspace(0.0, DELTA_MM, steps + 1)[1:]}
    P_N, iterations = [], []

    def record(context, state):
        forces = solid.assemble.vector(field)
        P_N.append(-fem.tools.force(field, forces, boundaries["rim_z"])[0])
        iterations.append(context.substep.iterations)

    step = fem.Step(items=[solid, contact], ramp=ramp, boundaries=boundaries)
    fem.Job(steps=[step], plugins=[record]).evaluate(verbose=0, tol=1e-8)
    wall = time.perf_counter() - t0
    dofs = sum(f.values.size for f in field.fields)
    return dofs, sum(iterations), wall, np.array(P_N)


def main(n_arc="64", n_thick="8", steps="20"):
    dofs, newton, wall, P_N = felupe_loading(int(n_arc), int(n_thick), int(steps))
    print(f"FElupe, Quad9 {n_arc}x{n_thick}, {steps} steps: {dofs} dofs, {newton} Newton "
          f"iterations, {wall:.2f} s, P({DELTA_MM:g} mm) = {P_N[-1]:.4f} N")


if __name__ == "__main__":
    main(*sys.argv[1:])
