"""The noise-free test curves of `tests/test_fit_lab.py`, made on the default mesh (finer
than the coarse mesh the tests fit with, so a round trip carries the model's own
discretisation error): a displacement-controlled test (loading from contact to the turn,
the retraction along the relaxation and the fixed-grips equilibrium curve down to the
jump-off at delta_dagger; `solver.fit.simulated_curve` without detached points), written
as ``delta_mm,P_N`` to tests/data/fit_<name>.csv with the shell and the truth in a
``#`` comment line.

Run: python benchmarks/fit_curves.py [mesh [name ...]]   (default mesh; about a minute)
     python benchmarks/fit_curves.py table [mesh]          (the fit table, coarse mesh)

`lab_curve` dresses a stored curve as a lab records it (approach, drop, detached rows,
noise, baseline) and `write_csv` writes it with the units of a header; `CASES` are the
round trips of the tests and the table.
"""
import functools
import json
import pathlib
import sys
import time

import numpy as np

from shell_adhesion.solver.fit import simulated_curve
from shell_adhesion.solver.request import Request, gamma_bucket, solve_request

OUT = pathlib.Path(__file__).parent.parent / "tests" / "data"
DELTA0_MM = 0.05        # the contact point of the lab curves (measured delta = model + this)

# name: R, t, h [mm], C10 [MPa], gamma [J/m^2], depth from contact [mm], points per part
CURVES = {
    "base": (20.0, 3.0, 20.0, 0.3, 30.0, 2.0, 600),     # the paper's base shell (dense: the
                                                        # tests take every 4th point or all)
    "thin": (15.0, 1.5, 11.25, 0.5, 20.0, 1.5, 150),    # issue 39's thin shell
    "other": (40.0, 6.0, 40.0, 0.3, 30.0, 2.0, 150),    # the base shell x 2 (fitted as the base)
    "base_frictionless": (20.0, 3.0, 20.0, 0.3, 30.0, 2.0, 150),
}
INTERFACE = {"base_frictionless": "frictionless"}       # the others: no_slip


@functools.lru_cache(maxsize=None)
def stored(name):
    """(shell and truth dict, delta_mm, P_N) of a stored noise-free curve."""
    lines = (OUT / f"fit_{name}.csv").read_text().splitlines()
    truth = dict(item.split("=") for item in lines[0].lstrip("# ").split()[:6])
    d, P = np.loadtxt(lines[2:], delimiter=",", unpack=True)
    return {k: float(v) for k, v in truth.items()}, d, P


def lab_curve(name="base", every=4, jump=3, smeared=False, noise=0.0, seed=1, offset_N=0.0,
              drift_N_per_mm=0.0):
    """Columns (t_s, delta_mm, P_N) of a test: approach from 1 mm before contact, the stored
    attached curve (every `every`-th row of each part), `jump` rows on the drop from
    P_dagger to zero (at delta_dagger, or `smeared`: delta going on), 20 detached rows;
    Gaussian noise of `noise` x the largest force, a baseline offset + drift x delta."""
    truth, d, P = stored(name)
    turn = int(np.argmax(d))
    keep = np.unique(np.concatenate([np.arange(0, turn + 1, every), [turn],
                                     np.arange(len(d) - 1, turn, -every)]))
    d, P = d[keep], P[keep]
    step = d[-2] - d[-1]
    approach = np.linspace(-1.0, 0.0, 50, endpoint=False)
    k = np.arange(1, jump + 1)
    d_drop = d[-1] - step * k if smeared else np.full(jump, d[-1])
    P_drop = P[-1] * (1 - k / (jump + 1))
    d_free = (d_drop[-1] if jump else d[-1]) - step * np.arange(1, 21)
    delta = np.concatenate([approach, d, d_drop, d_free]) + DELTA0_MM
    force = np.concatenate([0 * approach, P, P_drop, 0 * d_free])
    force = force + offset_N + drift_N_per_mm * delta
    rng = np.random.default_rng(seed)
    force = force + noise * np.max(np.abs(force)) * rng.standard_normal(len(force))
    return {"t_s": 0.1 * np.arange(len(delta)), "delta_mm": delta, "P_N": force}


UNITS = {"delta_mm": ("delta_mm", 1.0), "delta_um": ("delta_mm", 1e3), "P_N": ("P_N", 1.0),
         "P_mN": ("P_N", 1e3), "P_uN": ("P_N", 1e6), "t_s": ("t_s", 1.0)}


def write_csv(path, cols, header=("delta_mm", "P_N"), bom=False, shuffle=False):
    """Write the columns under `header` (units converted, UNITS), rows shuffled if asked."""
    data = np.column_stack([cols[UNITS[h][0]] * UNITS[h][1] for h in header])
    if shuffle:
        data = data[np.random.default_rng(7).permutation(len(data))]
    text = ",".join(header) + "\n" + "".join(",".join(f"{v:.9g}" for v in row) + "\n"
                                             for row in data)
    path.write_text(("\ufeff" if bom else "") + text, encoding="utf-8")
    return path


CASES = {
    # name: (lab_curve arguments, write_csv arguments)
    "jump_1": (dict(jump=1, noise=0.01), {}),
    "jump_3": (dict(jump=3, noise=0.01), {}),
    "jump_20_smeared": (dict(jump=20, smeared=True, noise=0.01), {}),
    "noise_1": (dict(noise=0.01, every=1), {}),
    "noise_5": (dict(noise=0.05, every=1), {}),
    "baseline": (dict(noise=0.01, offset_N=0.3, drift_N_per_mm=-0.2), {}),
    "mN_um": (dict(noise=0.01), dict(header=("delta_um", "P_mN"))),
    "shuffled_time": (dict(noise=0.01), dict(header=("P_N", "t_s", "delta_mm"), shuffle=True)),
    "bom": (dict(noise=0.01), dict(bom=True)),
}


def make(name, mesh="default"):
    """(delta_mm, P_N, wall s) of curve `name` on `mesh`."""
    R, t, h, C10, gamma, depth, n = CURVES[name]
    g_hat = gamma * 1e-3 / (C10 * R)
    top = gamma_bucket(1.5 * g_hat)
    t0 = time.perf_counter()
    ps, _, _ = solve_request(t / R, h / R, Request.serving(top, depth / R), top,
                             INTERFACE.get(name, "no_slip"), mesh)
    x, p = simulated_curve(ps, C10, g_hat, depth / R, n, n, n_detached=0)
    return x * R, p * R ** 2, time.perf_counter() - t0


def write(name, mesh="default"):
    d, P, wall = make(name, mesh)
    R, t, h, C10, gamma, depth, _ = CURVES[name]
    path = OUT / (f"fit_{name}.csv" if mesh == "default" else f"fit_{name}_{mesh}.csv")
    lines = [f"# R_mm={R:g} t_mm={t:g} h_mm={h:g} C10_MPa={C10:g} gamma_J_m2={gamma:g} "
             f"depth_mm={depth:g} mesh={mesh} interface={INTERFACE.get(name, 'no_slip')} "
             "(benchmarks/fit_curves.py)",
             "delta_mm,P_N"] + [f"{a:.9g},{b:.9g}" for a, b in zip(d, P)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"{path}: {len(d)} rows, {wall:.1f} s")


TABLE_CASES = dict(
    {name: (curve, fmt, "base") for name, (curve, fmt) in CASES.items()},
    noise_free_base=(dict(), {}, "base"),
    noise_free_thin=(dict(every=1), {}, "thin"),
    noise_free_frictionless=(dict(every=1), {}, "base_frictionless"),
    shuffled_no_time=(dict(noise=0.01), dict(shuffle=True), "base"),
    other_shell=(dict(noise=0.01), {}, "other"),        # R 40 mm (base x 2) fitted as the base
    mN_read_as_N=(dict(noise=0.01, force_scale=1e3), {}, "base"),
)


def table(mesh="coarse") -> str:
    """The fit table (case, true, fitted, 95 % interval, exit code and verdict) of every
    TABLE_CASES curve through `shell-adhesion fit --json` (the package on the path)."""
    import contextlib
    import io
    import tempfile

    from shell_adhesion.cli import main

    lines = ["| case | C10 true / fitted [95 %] MPa | gamma true / fitted [95 %] J/m^2 | "
             "exit: verdict |", "| --- | --- | --- | --- |"]
    with tempfile.TemporaryDirectory() as tmp:
        for case, (curve, fmt, name) in TABLE_CASES.items():
            curve = dict(curve)
            scale = curve.pop("force_scale", 1.0)
            cols = lab_curve(name, **curve)
            cols["P_N"] = cols["P_N"] * scale
            path = write_csv(pathlib.Path(tmp) / f"{case}.csv", cols, **fmt)
            truth = stored("base" if name == "other" else name)[0]
            fitted_as = stored("base")[0] if name == "other" else truth
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = main(["fit", "--R", f"{fitted_as['R_mm']:g}", "--t",
                             f"{fitted_as['t_mm']:g}", "--h", f"{fitted_as['h_mm']:g}",
                             "--curve", str(path), "--mesh", mesh, "--json",
                             "--interface", INTERFACE.get(name, "no_slip")])
            if code == 0:
                r = json.loads(out.getvalue())
                c_lo, c_hi = r["C10_MPa_ci95"]
                g_lo, g_hi = r["gamma_J_m2_ci95"]
                verdict = r.get("verdict", {})
                ratio = f", rms/allowed {verdict['ratio']:.2f}" if verdict else ""
                lines.append(f"| {case} | {truth['C10_MPa']:g} / {r['C10_MPa']:.4g} "
                             f"[{c_lo:.4g}, {c_hi:.4g}] | {truth['gamma_J_m2']:g} / "
                             f"{r['gamma_J_m2']:.4g} [{g_lo:.4g}, {g_hi:.4g}] | 0: fits"
                             f"{ratio} |")
            else:
                why = err.getvalue().strip().replace(str(path), path.name).replace("|", "/")
                why = why.replace("shell-adhesion: ", "")[:150]
                lines.append(f"| {case} | {truth['C10_MPa']:g} / - | {truth['gamma_J_m2']:g} "
                             f"/ - | {code}: {why} |")
    return "\n".join(lines)


if __name__ == "__main__":
    if sys.argv[1:2] == ["table"]:
        print(table(*sys.argv[2:3]))
        sys.exit(0)
    mesh = sys.argv[1] if len(sys.argv) > 1 else "default"
    for name in sys.argv[2:] or CURVES:
        write(name, mesh)
