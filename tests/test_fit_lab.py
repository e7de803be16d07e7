"""`fit` on curves as a lab records them (issues 40 and 39): the jump-off sampled by 1, 3 or 20
points, noise, a baseline offset and drift, units in the header, rows out of order, a BOM,
instrument exports; the misfit verdict; intervals that hold the model's error.

The curves come from the default mesh (tests/data/fit_*.csv, `benchmarks/fit_curves.py`:
no stored CalculiX or FElupe curve has a retraction of these shells) and are fitted on the
coarse mesh, so every round trip carries the model's own discretisation error (one, made
on the fine mesh, is fitted on the default mesh).  Around the
stored attached curve each test adds a non-contact approach (1 mm, 50 rows), the drop and
20 detached rows, an offset delta0 = 0.05 mm of the contact point, and what it tests
(`fit_curves.lab_curve`); `python benchmarks/fit_curves.py table` prints the table."""
import functools
import importlib.util
import pathlib

import numpy as np
import pytest

from shell_adhesion import fit_curve
from shell_adhesion.cli import main
from shell_adhesion.errors import InputError
from shell_adhesion.solver import fit as solver_fit
from shell_adhesion.solver.fit import Misfit

CURVES = pathlib.Path(__file__).parent.parent / "benchmarks" / "fit_curves.py"
_spec = importlib.util.spec_from_file_location("fit_curves", CURVES)
fit_curves = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fit_curves)
stored, lab_curve, write_csv = fit_curves.stored, fit_curves.lab_curve, fit_curves.write_csv
DELTA0_MM = fit_curves.DELTA0_MM
C10_TOL, GAMMA_TOL = 0.015, 0.04      # issue 40: C10 within 1.5 %, gamma within 4 %
DELTA0_TOL_MM = 0.05                  # the contact point: a fiftieth of the loading depth


@pytest.fixture(autouse=True, scope="module")
def paths_solved_once():
    """Every fit here solves the same few path sets (one shell, the coarse mesh, the depth
    and gamma buckets its curves share): each is solved once for the module and handed to
    each fit that asks for it (the solve is deterministic; the fits do not modify it)."""
    from shell_adhesion.study import fit as study_fit
    solved = functools.lru_cache(maxsize=None)(study_fit._paths)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(study_fit, "_paths", solved)
        yield


def fit_file(path, name="base", **kw):
    truth = stored(name)[0]
    return fit_curve(truth["R_mm"], truth["t_mm"], truth["h_mm"], path, mesh="coarse", **kw)


def check_round_trip(result, name="base"):
    """C10 within 1.5 %, gamma within 4 %, the contact point delta0 within DELTA0_TOL_MM,
    each truth inside its interval."""
    truth = stored(name)[0]
    out = result.to_dict()
    print(f"\nC10 {out['C10_MPa']:.5g} {out['C10_MPa_ci95']}, gamma {out['gamma_J_m2']:.5g} "
          f"{out['gamma_J_m2_ci95']}, delta0 {out['delta0_mm']:.4g} {out['delta0_mm_ci95']}, "
          f"ratio {out['verdict']['ratio']:.2f}, used {out['points_used']}")
    assert abs(out["C10_MPa"] / truth["C10_MPa"] - 1) < C10_TOL
    assert abs(out["gamma_J_m2"] / truth["gamma_J_m2"] - 1) < GAMMA_TOL
    for key, true in (("C10_MPa", truth["C10_MPa"]), ("gamma_J_m2", truth["gamma_J_m2"]),
                      ("delta0_mm", DELTA0_MM)):
        lo, hi = out[f"{key}_ci95"]
        assert lo < true < hi, key
    assert abs(out["delta0_mm"] - DELTA0_MM) < DELTA0_TOL_MM
    assert not out["verdict"]["misfit"]
    return out


CASES = fit_curves.CASES


@pytest.mark.parametrize("case", sorted(CASES))
def test_round_trip(case, tmp_path):
    """Each lab feature of issue 40, fitted back within tolerance with the truth inside."""
    curve, fmt = CASES[case]
    path = write_csv(tmp_path / "curve.csv", lab_curve(**curve), **fmt)
    out = check_round_trip(fit_file(path))
    if case.startswith("jump"):
        assert out["points_used"]["after_pull_off"] >= 20 + int(case.split("_")[1]) - 2
    if case == "baseline":
        assert abs(out["baseline"]["offset_N"] - 0.3) < 0.05
        assert abs(out["baseline"]["drift_N_per_mm"] + 0.2) < 0.05
    if case == "shuffled_time":
        assert "ordered by t_s" in out["input"]["rows"]


@functools.lru_cache(maxsize=None)
def noise_free(name, tmp):
    path = write_csv(pathlib.Path(tmp) / f"{name}.csv",
                     lab_curve(name, every=1 if name == "thin" else 4))
    return fit_file(path, name)


@pytest.mark.parametrize("name", ["base", "thin"])
def test_noise_free_truth_inside(name, tmp_path_factory):
    """Issue 39 item 5: a noise-free curve of the default mesh fitted on the coarse one: the
    truth inside each interval (the model's error from the coarser mesh included)."""
    check_round_trip(noise_free(name, str(tmp_path_factory.getbasetemp())), name)


@pytest.mark.parametrize("name", ["base", "thin"])
def test_noise_free_width(name, tmp_path_factory):
    """Issue 39 item 5: each interval of a noise-free curve no wider than 3 % of the value."""
    out = noise_free(name, str(tmp_path_factory.getbasetemp())).to_dict()
    for key in ("C10_MPa", "gamma_J_m2"):
        lo, hi = out[f"{key}_ci95"]
        assert (hi - lo) / out[key] < 0.03, key


def test_default_mesh_fits_a_fine_mesh_curve(tmp_path):
    """Issue 39 item 5 on the fit's default mesh: the base shell's noise-free curve made on
    the fine mesh (tests/data/fit_base_fine.csv: `python benchmarks/fit_curves.py fine
    base`) fitted on the default mesh: each truth inside its interval, each interval below
    3 % wide, C10 within 0.1 % and gamma within 0.3 % (docs/fit.md: -0.04 % and +0.24 %;
    the joint fit's gamma interval missed the truth here)."""
    truth = stored("base_fine")[0]
    path = write_csv(tmp_path / "fine.csv", lab_curve("base_fine"))
    out = fit_curve(truth["R_mm"], truth["t_mm"], truth["h_mm"], path,
                    mesh="default").to_dict()
    print(out["C10_MPa"], out["C10_MPa_ci95"], out["gamma_J_m2"], out["gamma_J_m2_ci95"])
    for key, true in (("C10_MPa", truth["C10_MPa"]), ("gamma_J_m2", truth["gamma_J_m2"]),
                      ("delta0_mm", DELTA0_MM)):
        lo, hi = out[f"{key}_ci95"]
        assert lo < true < hi, key
    for key, tol in (("C10_MPa", 0.001), ("gamma_J_m2", 0.003)):
        lo, hi = out[f"{key}_ci95"]
        assert (hi - lo) / out[key] < 0.03, key
        assert abs(out[key] / truth[key] - 1) < tol, key


def test_frictionless_round_trip(tmp_path):
    """The frictionless interface's noise-free round trip: the base shell's frictionless
    curve of the default mesh (tests/data/fit_base_frictionless.csv) fitted on the coarse
    mesh: each truth inside its interval, each below 3 % wide (the joint fit's C10 and gamma
    intervals missed the truth here: docs/fit.md)."""
    path = write_csv(tmp_path / "f.csv", lab_curve("base_frictionless", every=1))
    out = check_round_trip(fit_file(path, "base_frictionless", interface="frictionless"),
                           "base_frictionless")
    for key in ("C10_MPa", "gamma_J_m2"):
        lo, hi = out[f"{key}_ci95"]
        assert (hi - lo) / out[key] < 0.03, key


INSTRUMENTS = {
    # a rheometer: the gap falls as the shell is pressed
    "rheometer": ("Point No.,Normal Force [N],Gap [mm],Time [s]",
                  lambda c, i: [i + 1, c["P_N"][i], 3.0 - c["delta_mm"][i], c["t_s"][i]]),
    "testing_machine": ("Time (s),Extension (mm),Load (N)",
                        lambda c, i: [c["t_s"][i], c["delta_mm"][i], c["P_N"][i]]),
}


@pytest.mark.parametrize("kind", sorted(INSTRUMENTS))
def test_instrument_export(kind, tmp_path):
    """The instruments' headers, columns in their order (the rheometer's rows reversed in
    the file, its Point No. puts them back)."""
    header, row = INSTRUMENTS[kind]
    cols = lab_curve(noise=0.01)
    rows = [row(cols, i) for i in range(len(cols["t_s"]))]
    if kind == "rheometer":
        rows = rows[::-1]
    path = tmp_path / "export.csv"
    path.write_text(header + "\n" + "".join(",".join(f"{v:.9g}" for v in r) + "\n"
                                            for r in rows), encoding="utf-8")
    out = fit_file(path).to_dict()
    # the gap's zero is the first gap: delta0 moves by it, C10 and gamma do not
    truth = stored("base")[0]
    assert abs(out["C10_MPa"] / truth["C10_MPa"] - 1) < C10_TOL
    assert abs(out["gamma_J_m2"] / truth["gamma_J_m2"] - 1) < GAMMA_TOL
    assert not out["verdict"]["misfit"]


def test_two_segments(tmp_path):
    """A two-segment file (`segment` approach / retract, each with its own time from 0)."""
    cols = lab_curve(noise=0.01)
    turn = int(np.argmax(cols["delta_mm"]))
    seg = np.where(np.arange(len(cols["t_s"])) <= turn, "approach", "retract")
    t = np.where(seg == "approach", cols["t_s"], cols["t_s"] - cols["t_s"][turn + 1])
    order = np.random.default_rng(3).permutation(len(t))
    text = "segment,t_s,delta_mm,P_N\n" + "".join(
        f"{seg[i]},{t[i]:.4f},{cols['delta_mm'][i]:.9g},{cols['P_N'][i]:.9g}\n" for i in order)
    path = tmp_path / "segments.csv"
    path.write_text(text, encoding="utf-8")
    out = check_round_trip(fit_file(path))
    assert "by segment" in out["input"]["rows"]


def test_other_shell_is_a_misfit(tmp_path, capsys):
    """A curve of R = 40 mm, t = 6, h = 40 (the base shell x 2) fitted as the base shell R = 20:
    one line, exit 1."""
    path = write_csv(tmp_path / "other.csv", lab_curve("other", noise=0.01))
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(path),
                 "--mesh", "coarse"])
    err = capsys.readouterr().err
    print(err)
    assert code == 1 and err.count("\n") == 1 and "misfit" in err
    with pytest.raises(Misfit) as caught:
        fit_file(path)
    assert caught.value.result.verdict.ratio > caught.value.result.verdict.factor


def test_a_retraction_that_never_recedes_is_refused(tmp_path, capsys):
    """A curve stopped 20 rows into its retraction, before the held contact recedes: those
    points do not depend on gamma (the fit returned 0.057 J/m^2 for 30, with an infinite
    interval): one line, exit 1."""
    _, d, P = stored("base")
    stop = int(np.argmax(d)) + 21
    path = write_csv(tmp_path / "short.csv", {"delta_mm": d[:stop] + DELTA0_MM, "P_N": P[:stop]})
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(path),
                 "--mesh", "coarse"])
    err = capsys.readouterr().err
    assert code == 1 and err.count("\n") == 1 and "do not depend on gamma" in err


def test_force_unit_off(tmp_path, capsys):
    """Forces in mN under the header P_N (1000 x): the curve's shape is the right one
    (exact scaling), C10 = 300 MPa is not a soft solid's: one line, exit 1."""
    cols = lab_curve(noise=0.01)
    cols["P_N"] = cols["P_N"] * 1e3
    path = write_csv(tmp_path / "mN.csv", cols)
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(path),
                 "--mesh", "coarse"])
    err = capsys.readouterr().err
    assert code == 1 and err.count("\n") == 1 and "not a soft solid" in err and "P_mN" in err


def test_cli_prints_verdict_and_baseline(tmp_path, capsys):
    path = write_csv(tmp_path / "curve.csv", lab_curve(noise=0.01, offset_N=0.3))
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(path),
                 "--mesh", "coarse"])
    out = capsys.readouterr().out
    assert code == 0
    assert "baseline: offset" in out and "fits (a misfit above 2 x)" in out
    assert "the contact point" in out


BAD_HEADERS = {
    "Force (lbf)": "delta_mm,Force (lbf)\n0,0\n",
    "P [N]": "\ufeffdelta_mm,P [N]\n0,0\n",
}


@pytest.mark.parametrize("column", sorted(BAD_HEADERS))
def test_unknown_header(column, tmp_path, capsys):
    """An unknown column: one line naming it and the accepted names, exit 2."""
    path = tmp_path / "bad.csv"
    path.write_text(BAD_HEADERS[column], encoding="utf-8")
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(path)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert repr(column) in err and "P_mN" in err and "Gap [mm]" in err


def test_bad_segment_value(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("segment,delta_mm,P_N\napproach,0,0\nunload,0.1,0\n", encoding="utf-8")
    with pytest.raises(InputError, match="row 3: segment: 'unload' must be one of"):
        fit_file(path)


def test_shuffled_without_time(tmp_path, capsys):
    """Rows out of order with nothing to sort them by: one line, exit 2, before any
    computation (before: the turn was taken at the first deepest row and the rest fitted)."""
    path = write_csv(tmp_path / "shuffled.csv", lab_curve(noise=0.01), shuffle=True)
    code = main(["fit", "--R", "20", "--t", "3", "--h", "20", "--curve", str(path)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1
    assert "not in time order" in err and "t_s, index" in err


def test_noise_sd_from_the_data():
    """White noise of sd 0.05 on a smooth curve (with a jump in it): found within 10 %."""
    x = np.linspace(0.0, 1.0, 800)
    p = np.sin(3 * x) + np.where(x > 0.7, -1.0, 0.0)
    noisy = p + 0.05 * np.random.default_rng(5).standard_normal(len(x))
    assert abs(solver_fit.noise_sd(noisy) / 0.05 - 1) < 0.1
    assert solver_fit.noise_sd(p) < 1e-3


@pytest.mark.parametrize("rows", [1, 3, 20])
def test_jump_off_cut_at_the_drop(rows):
    """A retraction whose least force is followed by a drop sampled by `rows` rows: the first
    cut lies inside the drop, and the fitted attached curve moves it to the drop's start."""
    up = np.linspace(0.0, 1.0, 50)
    down = np.linspace(1.0, -0.3, 60)[1:]
    attached = lambda d: 2 * np.clip(d, 0, None) ** 1.5 - 0.8 * np.clip(1 - d, 0, None) ** 0.5
    p = np.concatenate([2 * up ** 1.5, attached(down)])
    x = np.concatenate([up, down])
    start = len(x)
    k = np.arange(1, rows + 1)
    x = np.concatenate([x, np.full(rows, x[-1]), x[-1] - 0.02 * np.arange(1, 11)])
    p = np.concatenate([p, p[-1] * (1 - k / (rows + 1)), np.zeros(10)])
    first = solver_fit.split_curve(x, p)
    assert start <= first.detached[0] <= start + rows
    model = np.concatenate([2 * up ** 1.5, attached(np.minimum(x[50:], 1.0))])
    model[start:] = p[start - 1]                 # the attached curve held at its end
    cut = solver_fit.refine_jump(first, p, model, 0.0)
    assert cut == start
    final = solver_fit.split_curve(x, p, cut)
    # on the drop: the rows above an eighth of the least force (the last of 20 are below)
    assert final.retraction[-1] == start - 1 and rows - 2 <= final.drop <= rows


def test_rows_out_of_order_measured():
    d = np.concatenate([np.linspace(0, 1, 20), np.linspace(1, -0.2, 20)])
    assert solver_fit.backtrack_share(d) == 0.0
    assert solver_fit.backtrack_share(np.random.default_rng(1).permutation(d)) > 0.3


def test_noisy_displacement_is_in_order():
    """A densely sampled displacement with noise larger than its step is still in order."""
    d = np.concatenate([np.linspace(0, 1, 5000), np.linspace(1, -0.2, 5000)])
    noisy = d + 1e-3 * np.random.default_rng(2).standard_normal(len(d))
    assert solver_fit.backtrack_share(noisy) < solver_fit.MAX_BACKTRACK
