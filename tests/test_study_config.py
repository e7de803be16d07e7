"""Study files: every bad file gives one line naming its place, exit code 2, nothing written."""
from pathlib import Path

import pytest

from shell_adhesion.solver.geometry import check_cap
from shell_adhesion.errors import InputError
from shell_adhesion.study.config import MAX_BYTES, StudyError, load_study
from shell_adhesion.study.plan import make_plan
from shell_adhesion.cli import main

REPO = Path(__file__).resolve().parents[1]

GOOD = """\
name: tiny
R_mm: 20
base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}
sweeps:
  C10_MPa: [0.2, 0.3]
  t_over_R: [0.15, 0.2]
mesh: coarse
delta_max_over_R: 0.1
"""

PWNED = "/tmp/shell-adhesion-yaml-tag-was-executed"


def cap_message(t, h, t_place, h_place):
    """The solver's cap rule for (t, h), named with the study file's places."""
    with pytest.raises(InputError) as e:
        check_cap(t, h, t_place, h_place)
    return str(e.value)


# (name, file text, text the one-line message must contain)
BAD = [
    ("unknown key", GOOD + "mesh_size: 3\n", "mesh_size: unknown key"),
    ("unknown factor", GOOD + "grid:\n  E_MPa: [1.0]\n", "grid.E_MPa: unknown factor"),
    ("wrong type", GOOD.replace("R_mm: 20", "R_mm: twenty"), "R_mm: 'twenty' must be a number"),
    ("bool as number", GOOD.replace("R_mm: 20", "R_mm: true"), "R_mm: True must be a number"),
    ("R beyond its range", GOOD.replace("R_mm: 20", "R_mm: 1e200"),
     "R_mm: 1e+200 must be from 0.001 to 10000 mm"),
    ("nan", GOOD.replace("R_mm: 20", "R_mm: .nan"), "R_mm: nan must be a finite number"),
    ("unknown key near a valid one", GOOD + "interfce: no_slip\n",
     "interfce: unknown key; did you mean interface?"),
    ("YAML 1.1 boolean is text", GOOD + "outputs:\n  loading_curves: yes\n",
     "outputs.loading_curves: 'yes' must be true or false"),
    ("t > R", GOOD.replace("t_over_R: [0.15, 0.2]", "t_over_R: [0.15, 0.2, 0.3, 1.2]"),
     cap_message(1.2, 1.0, "sweeps.t_over_R[3]", "base.h_over_R")),
    ("h <= t", GOOD + "grid:\n  h_over_R: [0.5, 0.1]\n",
     "grid.h_over_R[1]: 0.1 must be > t"),
    ("C10 <= 0", GOOD.replace("C10_MPa: [0.2, 0.3]", "C10_MPa: [0.2, -0.3]"),
     "sweeps.C10_MPa[1]: -0.3 must be > 0"),
    ("repeated value", GOOD.replace("C10_MPa: [0.2, 0.3]", "C10_MPa: [0.2, 0.3, 0.2]"),
     "sweeps.C10_MPa[2]: 0.2 repeats sweeps.C10_MPa[0]"),
    ("empty list", GOOD.replace("C10_MPa: [0.2, 0.3]", "C10_MPa: []"),
     "sweeps.C10_MPa: [] must be a non-empty list of numbers"),
    ("bad interface", GOOD + "interface: sticky\n",
     "interface: 'sticky' must be one of no_slip, frictionless"),
    ("bad mesh", GOOD.replace("mesh: coarse", "mesh: ultra"),
     "mesh: 'ultra' must be one of coarse, default, fine"),
    ("name with a path", GOOD.replace("name: tiny", "name: ../escape"),
     "name: '../escape' must be a plain file stem"),
    ("absolute name", GOOD.replace("name: tiny", "name: /tmp/escape"),
     "name: '/tmp/escape' must be a plain file stem"),
    ("missing name", GOOD.replace("name: tiny\n", ""), "name: missing"),
    ("sweeps without a base factor",
     GOOD.replace("base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}",
                  "base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0}"),
     "base.gamma_J_m2: missing"),
    ("gamma beyond the paths", GOOD + "grid:\n  gamma_J_m2: [30, 1000]\n",
     "grid.gamma_J_m2[1]: 1000 J/m^2 with C10 = 0.3 MPa (base.C10_MPa)"),
    ("delta_max too large", GOOD.replace("delta_max_over_R: 0.1", "delta_max_over_R: 0.6"),
     "delta_max_over_R: 0.6 is outside the supported domain delta/R <= 0.25"),
    ("delta_max beyond a shallow cap",
     GOOD.replace("delta_max_over_R: 0.1", "delta_max_over_R: 0.22")
     + "grid:\n  h_over_R: [0.2]\n  t_over_R: [0.15]\n",
     "delta_max_over_R: 0.22 must be < h/R (0.2, grid.h_over_R[0])"),
    ("outputs flag", GOOD + "outputs:\n  loading_curves: 3\n",
     "outputs.loading_curves: 3 must be true or false"),
    ("duplicate key", GOOD + "R_mm: 25\n", "duplicate key 'R_mm'"),
    ("python object tag",
     f"name: !!python/object/apply:os.system ['touch {PWNED}']\nR_mm: 20\n",
     "could not determine a constructor for the tag"),
    ("yaml syntax", GOOD + "grid: [unclosed\n", "yaml: line"),
    ("not a mapping", "- 1\n- 2\n", "the study must be a YAML mapping"),
    ("base not a mapping", GOOD.replace(
        "base: {C10_MPa: 0.3, t_over_R: 0.15, h_over_R: 1.0, gamma_J_m2: 30}", "base: 3"),
     "base: 3 must be a mapping"),
    ("material without a model", GOOD + "material: {C01_over_C10: 0.2}\n",
     "material.model: missing"),
    ("unknown material model", GOOD + "material: {model: ogden}\n",
     "material.model: 'ogden' must be one of neo_hooke, mooney_rivlin, yeoh, gent"),
    ("unknown material key", GOOD + "material: {model: mooney_rivlin, C01: 0.05}\n",
     "material.C01: unknown key; did you mean C01_MPa?"),
    ("ratio not of the model", GOOD + "material: {model: yeoh, C01_over_C10: 0.2}\n",
     "material: C01_over_C10: 0.2 is not a coefficient of the yeoh model"),
    ("gent without Jm", GOOD + "material: {model: gent}\n",
     "material: Jm: the gent model needs Jm"),
    ("negative D1 C10", GOOD + "material: {model: neo_hooke, D1_times_C10: -0.1}\n",
     "material: D1: -0.1 (times C10) must be >= 0"),
    ("unstable swept ratio", GOOD + "material: {model: yeoh}\n"
     "grid:\n  C20_over_C10: [0, -0.3]\n",
     "grid.C20_over_C10[1]: material: yeoh (C20/C10 = -0.3, C30/C10 = 0) is unstable (Drucker): the uniaxial tangent stiffness d sigma / d stretch is <= 0 at stretch 1.53"),
    ("coefficient twice in the block",
     GOOD + "material: {model: mooney_rivlin, C01_MPa: 0.05, C01_over_C10: 0.1}\n",
     "material.C01_over_C10: the same coefficient is given as material.C01_MPa; give each "
     "coefficient once, in MPa or as a ratio to C10"),
    ("coefficient swept in the other form",
     GOOD + "material: {model: mooney_rivlin, C01_over_C10: 0.1}\ngrid:\n  C01_MPa: [0.03]\n",
     "material.C01_over_C10: the same coefficient is given as grid.C01_MPa"),
    ("MPa coefficient not of the model", GOOD + "material: {model: yeoh, C01_MPa: 0.05}\n",
     "material.C01_MPa: not a coefficient of the yeoh model (it has C10_MPa, C20_MPa, "
     "C30_MPa, D1_per_MPa"),
    ("unstable in MPa", GOOD + "material: {model: mooney_rivlin, C01_MPa: -0.2}\n",
     "material.C01_MPa: material: mooney_rivlin (C10 = 0.3 MPa, C01 = -0.2 MPa) is unstable "
     "(Drucker)"),
    ("swept MPa coefficient unstable", GOOD + "material: {model: yeoh}\n"
     "grid:\n  C20_MPa: [0, -0.03]\n",
     "grid.C20_MPa[1]: material: yeoh (C10 = 0.3 MPa, C20 = -0.03 MPa, C30 = 0 MPa) is "
     "unstable (Drucker)"),
    ("C10 in base and material", GOOD + "material: {model: neo_hooke, C10_MPa: 0.3}\n",
     "material.C10_MPa: C10 is given in base.C10_MPa too (0.3 MPa); give it once"),
    ("swept ratio of neo-Hooke", GOOD.replace("  t_over_R: [0.15, 0.2]\n",
                                              "  C01_over_C10: [0, 0.2]\n"),
     "sweeps.C01_over_C10[1]: C01_over_C10: 0.2 is not a coefficient of the neo_hooke model"),
]


@pytest.mark.parametrize("text, expected", [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_study_exit_2_one_line_nothing_written(tmp_path, capsys, text, expected):
    path = tmp_path / "study.yaml"
    path.write_text(text)
    out, cat = tmp_path / "results", tmp_path / "catalogue"
    code = main(["run", str(path), "--out", str(out), "--catalogue", str(cat), "--quiet"])
    err = capsys.readouterr().err
    assert code == 2
    assert expected in err
    assert err.strip().count("\n") == 0, err
    assert not out.exists() and not cat.exists()
    assert not Path(PWNED).exists()


def test_missing_file(tmp_path, capsys):
    assert main(["run", str(tmp_path / "nope.yaml"), "--out", str(tmp_path / "out"),
                 "--catalogue", str(tmp_path / "c")]) == 2
    assert "cannot read the study file" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_good_study_values(tmp_path):
    path = tmp_path / "s.yaml"
    path.write_text(GOOD)
    s = load_study(path)
    assert s.name == "tiny" and s.R_mm == 20.0 and s.mesh == "coarse"
    assert s.interface == "no_slip" and s.outputs.loading_curves
    assert s.sweeps == {"C10_MPa": (0.2, 0.3), "t_over_R": (0.15, 0.2)}
    assert len(s.sha256) == 64


def test_yaml_12_numbers(tmp_path):
    """Plain scalars resolve as YAML 1.2: 2e1 and 3E-1 are numbers, 017 is 17."""
    path = tmp_path / "s.yaml"
    path.write_text(GOOD.replace("R_mm: 20", "R_mm: 2e1").replace("C10_MPa: [0.2, 0.3]",
                                                                 "C10_MPa: [2e-1, 3E-1]")
                    .replace("gamma_J_m2: 30}", "gamma_J_m2: 030}"))
    s = load_study(path)
    assert s.R_mm == 20.0 and s.sweeps["C10_MPa"] == (0.2, 0.3) and s.base["gamma_J_m2"] == 30


def test_study_file_over_1_MB(tmp_path):
    path = tmp_path / "big.yaml"
    path.write_text(GOOD + "#" * MAX_BYTES + "\n")
    with pytest.raises(StudyError, match=r"^the study file is over 1 MB"):
        load_study(path)


def test_workflow_is_the_papers_study():
    s = load_study(REPO / "workflow.yaml")
    assert s.R_mm == 20 and s.interface == "no_slip" and s.mesh == "default"
    assert s.base == dict(C10_MPa=0.3, t_over_R=0.15, h_over_R=1.0, gamma_J_m2=30)
    assert s.sweeps["t_over_R"] == (0.1, 0.125, 0.15, 0.175, 0.225, 0.5, 1.0)
    plan = make_plan(s)
    assert len(plan.shells) == 11          # DESIGN.md section 4
    assert len(plan.points) == 19          # base + 4 + 6 + 4 + 4 sweep values off base
    assert {f: len(v) for f, v in plan.axes.items()} == dict(
        C10_MPa=5, t_over_R=7, h_over_R=5, gamma_J_m2=5)


def test_error_is_a_value_error():
    with pytest.raises(StudyError, match=r"^R_mm: -1 must be > 0$"):
        from shell_adhesion.study.config import validate
        validate(dict(name="x", R_mm=-1))
