r"""Fitting C10 and gamma to a measured curve
=========================================

Fit C10 and gamma back from a synthetic test, and what a half-space JKR fit makes of it.

A displacement-controlled test of the shell R = 20 mm, t = 3 mm, h = 20 mm (t/R = 0.15,
h/R = 1) with C10 = 0.25 MPa and gamma = 25 J/m^2 (gamma / (C10 R) = 0.005) is made by the
solver's own model of the test (`solver.fit.simulated_curve`): loading to 2 mm from contact,
retraction at the held contact radius, then along the fixed-grips equilibrium curve to the
jump-off at delta_dagger, and a few points of the detached shell.  It gets Gaussian noise of
1 % of its largest force (seed 1) and a contact offset delta0 = 0.05 mm (measured delta =
model delta + delta0).  `fit_curve` solves the shell's paths once (its own depth and gamma
range, so another mesh fit than the one that made the data) and fits C10, gamma and delta0.

    python examples/ex04_fit_curve.py [coarse|default] [test.csv]

prints the table (true, fitted, 95 % interval, half-space JKR) and, given a file name,
writes the synthetic curve there (the CSV that `shell-adhesion fit --curve` reads).
"""
import sys

import numpy as np

from shell_adhesion import fit_curve
from shell_adhesion.solver.fit import simulated_curve
from shell_adhesion.solver.request import Request, gamma_bucket, solve_request

R_MM, T_MM, H_MM = 20.0, 3.0, 20.0
C10_MPA, GAMMA_J_M2, DELTA0_MM = 0.25, 25.0, 0.05
DEPTH_MM, NOISE, SEED = 2.0, 0.01, 1


def synthetic_curve(mesh="coarse"):
    """(delta_mm, P_N) of the synthetic test, in time order."""
    g_hat = GAMMA_J_M2 * 1e-3 / (C10_MPA * R_MM)
    top = gamma_bucket(1.5 * g_hat)
    ps, _, _ = solve_request(T_MM / R_MM, H_MM / R_MM, Request.serving(top, DEPTH_MM / R_MM),
                             top, "no_slip", mesh)
    x, p = simulated_curve(ps, C10_MPA, g_hat, DEPTH_MM / R_MM)
    P_N = p * R_MM ** 2
    rng = np.random.default_rng(SEED)
    P_N = P_N + NOISE * np.max(np.abs(P_N)) * rng.standard_normal(len(P_N))
    return x * R_MM + DELTA0_MM, P_N


def write_csv(path, delta_mm, P_N):
    lines = ["delta_mm,P_N"] + [f"{d:.6f},{P:.6f}" for d, P in zip(delta_mm, P_N)]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def round_trip(mesh="coarse"):
    """(FitResult, rows): rows of (quantity, true, fitted, (low, high), half-space JKR)."""
    result = fit_curve(R_MM, T_MM, H_MM, synthetic_curve(mesh), mesh=mesh)
    out = result.to_dict()
    jkr = out["jkr"]
    rows = [("C10 [MPa]", C10_MPA, out["C10_MPa"], out["C10_MPa_ci95"], jkr["C10_MPa"]),
            ("gamma [J/m^2]", GAMMA_J_M2, out["gamma_J_m2"], out["gamma_J_m2_ci95"],
             jkr["gamma_J_m2"]),
            ("delta0 [mm]", DELTA0_MM, out["delta0_mm"], out["delta0_mm_ci95"],
             jkr["delta0_mm"])]
    return result, rows


def table(rows) -> str:
    lines = ["| quantity | true | fitted | 95 % interval | half-space JKR |",
             "| --- | --- | --- | --- | --- |"]
    lines += [f"| {q} | {t:g} | {f:.4g} | [{lo:.4g}, {hi:.4g}] | {j:.4g} |"
              for q, t, f, (lo, hi), j in rows]
    return "\n".join(lines)


if __name__ == "__main__":
    mesh = sys.argv[1] if len(sys.argv) > 1 else "coarse"
    if len(sys.argv) > 2:
        write_csv(sys.argv[2], *synthetic_curve(mesh))
    result, rows = round_trip(mesh)
    print(table(rows))
    print(f"fit: {result.provenance['wall_s']:.1f} s ({result.provenance['solves']})")
