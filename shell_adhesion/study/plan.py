"""The plan: which FE path sets a study needs (DESIGN.md section 3).

With an incompressible neo-Hookean solid, C10, R and gamma only rescale the results, so a
study needs one set of FE paths per distinct (t/R, h/R) (the interface, mesh and
delta_max / R are fixed per study).  The paths of a shell are fitted to what the study asks
of it (solver.request): they serve gamma / (C10 R) up to the largest its points ask, rounded
up to the ladder 1, 1.5, 2, 3, 5, 7 x 10^k (so that another C10, R or a nearby gamma shares
them), to the study's depth.  Only a set fitted to the same
request serves it from the catalogue, so the results do not depend on what else the
catalogue holds.
With error bars (the study's default), each shell has a companion on the next coarser mesh
(`Plan.error_shells`) and one on the mesh after it (`Plan.third_shells`): sets of their
own, keyed and stored like any other.  A companion relaxes contact fronts ending on the
node type its answer's set relaxed (solver.case.relaxation_starts: the two types converge
from different sides, so a mix measures no order); that type comes out of the answer's
loading, so the companion's key names its answer's set (`relaxation_family`: {"as":
fingerprint}), and study.run opens it once the answer's set is stored.

Another solid (`solver.material.Material`) enters the plan by its ratios to C10 (C01/C10,
C20/C10, C30/C10, Jm, D1 C10): they are FE dimensions and part of every shell's key, while
C10 stays the scaling modulus, so a C10 sweep at fixed ratios still needs one set of paths
per shell.  The study's `material:` block gives that solid; a study that sweeps a ratio
(`Study.swept_ratios`) plans one set per (t/R, h/R, ratios), and its points carry the swept
ratios after the four factors.

A closed cavity (the study's `cavity:` block, `solver.cavity.Cavity`) enters by its
pressures divided by C10 (p/C10, p0/C10, p_atm/C10) and its gas exponent: they are FE
dimensions and part of the shell's key, so a C10 sweep of a closed shell is NOT
post-processing: the plan holds one set of paths per (t/R, h/R, C10[, p_kPa]).  A swept
p_kPa (`Study.swept_cavity`) follows the four factors in the points; `Plan.cavities` gives
each point's Cavity and `Plan.for_cavity` the part of the plan of one (C10, p_kPa).
"""
from dataclasses import dataclass, replace

from shell_adhesion.catalogue import fingerprint
from shell_adhesion.solver.cavity import OPEN, Cavity
from shell_adhesion.solver.material import NEO_HOOKE, Material
from shell_adhesion.solver.mesh import coarser_mesh
from shell_adhesion.solver.path import Settings
from shell_adhesion.solver.request import Request, gamma_bucket
from shell_adhesion.solver.scaling import gamma_hat

from .config import FACTORS, Study, cavity_at, material_of, requested
from .keys import pathset_key

@dataclass(frozen=True, eq=False)
class Shell:
    """One FE path set of the plan."""

    t_over_R: float
    h_over_R: float
    gamma_hat_needed: float     # largest gamma / (C10 R) the study asks of this shell
    key: dict                   # catalogue key (gamma_max_hat: the ladder value)
    fingerprint: str
    material: Material = NEO_HOOKE
    cavity: Cavity = OPEN       # what fills the cavity (pressures / C10)
    answer: str = None          # an error-bar companion: its answer's set's fingerprint,
    #                             whose contact-front node type it relaxes

    @property
    def gamma_max_hat(self) -> float:
        return self.key["gamma_max_hat"]

    @property
    def request(self) -> Request:
        """What its paths must answer (solver.request): the ladder of gammas up to
        gamma_max_hat, to the study's delta_max (None: as deep as they need)."""
        delta_max = self.key["request"]["delta_max_over_R"]
        return Request.serving(self.gamma_max_hat, None if delta_max == "auto" else delta_max)


@dataclass(frozen=True, eq=False)
class Plan:
    """A study reduced to its requested points and its distinct FE path sets."""

    study: Study
    axes: dict          # factor -> sorted tuple: the union of the study's values (cube axes)
    points: tuple       # requested (C10_MPa, t_over_R, h_over_R, gamma_J_m2[, swept ratios])
    shells: tuple       # Shell, sorted by (t/R, h/R) (then by swept ratios)
    settings: Settings
    ratio_axes: dict = None     # swept ratio -> sorted tuple of its values (None: none swept)
    materials: dict = None      # swept ratio values (tuple) -> Material
    cavities: dict = None       # closed cavity: point -> Cavity (None: open)
    cavity_axes: dict = None    # swept cavity parameter (p_kPa) -> sorted tuple of values
    error_shells: tuple = ()    # each shell on the next coarser mesh (error bars), same order
    third_shells: tuple = ()    # and on the one after it (Richardson, solver.error_bars)

    @property
    def all_shells(self) -> tuple:
        """The FE path sets to serve: the shells, then their error-bar companions."""
        return self.shells + self.error_shells + self.third_shells

    def shell(self, t_over_R, h_over_R, material: Material = None) -> Shell:
        for s in self.shells:
            if ((s.t_over_R, s.h_over_R) == (t_over_R, h_over_R)
                    and (material is None or s.material == material)):
                return s
        raise KeyError((t_over_R, h_over_R))

    def for_ratios(self, values: tuple) -> "Plan":
        """The part of a plan with swept ratios at `values` (one value per swept ratio): its
        points without the ratios, the shells of that solid, the whole plan's axes."""
        m = self.materials[values]
        n = len(FACTORS)
        points = tuple(p[:n] for p in self.points if tuple(p[n:]) == tuple(values))
        shells = tuple(s for s in self.shells if s.material == m)
        errors = tuple(s for s in self.error_shells if s.material == m)
        third = tuple(s for s in self.third_shells if s.material == m)
        return replace(self, points=points, shells=shells, ratio_axes=None, materials=None,
                       error_shells=errors, third_shells=third)

    def for_cavity(self, C10_MPa, values: tuple = ()) -> "Plan":
        """The part of a closed-cavity plan at one C10 and swept cavity `values` (one per
        swept parameter): its points without those values, the shells of that Cavity, the
        C10 axis reduced to C10_MPa (the other axes the whole plan's)."""
        n = len(FACTORS)
        points = tuple(p[:n] for p in self.points
                       if p[0] == C10_MPa and tuple(p[n:]) == tuple(values))
        cavity = self.cavities[next(p for p in self.points
                                    if p[0] == C10_MPa and tuple(p[n:]) == tuple(values))]
        shells = tuple(s for s in self.shells if s.cavity == cavity)
        errors = tuple(s for s in self.error_shells if s.cavity == cavity)
        third = tuple(s for s in self.third_shells if s.cavity == cavity)
        return replace(self, points=points, shells=shells, cavities=None, cavity_axes=None,
                       axes={**self.axes, "C10_MPa": (C10_MPa,)}, error_shells=errors,
                       third_shells=third)

    def cavity_groups(self) -> list:
        """The (C10, swept cavity values) of a closed-cavity plan, sorted."""
        n = len(FACTORS)
        return sorted({(p[0], tuple(p[n:])) for p in self.points})


def shell_key(s: Shell) -> tuple:
    """Key of a served set in a run's `served` map: (t/R, h/R, Material), and the Cavity
    after them when it is closed (study.dataset.build reads it)."""
    key = (s.t_over_R, s.h_over_R, s.material)
    return key + (s.cavity,) if s.cavity.closed else key


def served_key(s: Shell, plan: Plan) -> tuple:
    """Key of a served set in the run's `served` map: `shell_key`, and "coarser" or
    "coarsest" after it for an error-bar companion (study.dataset.build reads it)."""
    key = shell_key(s)
    if s in plan.error_shells:
        return key + ("coarser",)
    return key + ("coarsest",) if s in plan.third_shells else key


def make_plan(study: Study, settings: Settings = Settings(),
              material: Material = None) -> Plan:
    """The distinct path sets of a validated study, with their catalogue keys; the solid
    is the study's (`material`, ratios to C10, overrides it when no ratio is swept)."""
    swept = study.swept_ratios
    solids = {}             # swept ratio values -> Material
    points = set()
    cavities = {}           # point -> Cavity (closed cavities only)
    for p in requested(study):
        values = tuple(p[r][0] if r in p else getattr(NEO_HOOKE, r) for r in swept)
        if values not in solids:
            solids[values] = (material if material is not None and not swept
                              else material_of(study, p))
        point = (tuple(p[f][0] for f in FACTORS) + values
                 + tuple(p[c][0] for c in study.swept_cavity))
        points.add(point)
        cavity = cavity_at(study, p)
        if cavity.closed:
            cavities[point] = cavity
    points = sorted(points)
    axes = {f: tuple(sorted({p[i] for p in points})) for i, f in enumerate(FACTORS)}
    need = {}
    for p in points:
        C10, t, h, gamma = p[:4]
        g = gamma_hat(gamma, C10, study.R_mm)
        at = (t, h, p[4:4 + len(swept)], cavities.get(p, OPEN))
        need[at] = max(need.get(at, 0.0), g)
    shells, errors, third = [], [], []
    for (t, h, values, cavity), g in sorted(
            need.items(), key=lambda kv: kv[0][:3] + (tuple(kv[0][3].as_dict().values()),)):
        m = solids[values]

        def shell(mesh, answer=None):
            key = pathset_key(t, h, study.interface, mesh, study.delta_max_over_R,
                              gamma_bucket(g), settings, m, cavity)
            if answer is not None:      # relaxed on the answer's node type (not known yet)
                key["relaxation_family"] = {"as": answer}
            return Shell(t, h, g, key, fingerprint(key), m, cavity, answer)

        shells.append(shell(study.mesh))
        if study.error_bars:    # the same shell on the next two coarser meshes: sets of their own
            answer = shells[-1].fingerprint
            errors.append(shell(coarser_mesh(study.mesh), answer))
            third.append(shell(coarser_mesh(coarser_mesh(study.mesh)), answer))
    ratio_axes = ({r: tuple(sorted({p[4 + j] for p in points})) for j, r in enumerate(swept)}
                  if swept else None)
    cavity_axes = ({c: tuple(sorted({p[4 + len(swept) + j] for p in points}))
                    for j, c in enumerate(study.swept_cavity)} or None)
    return Plan(study, axes, tuple(points), tuple(shells), settings, ratio_axes,
                solids if swept else None, cavities=cavities or None, cavity_axes=cavity_axes,
                error_shells=tuple(errors), third_shells=tuple(third))
