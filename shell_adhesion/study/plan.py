"""The plan: which FE path sets a study needs (DESIGN.md section 3).

With an incompressible neo-Hookean solid, C10, R and gamma only rescale the results, so a
study needs one set of FE paths per distinct (t/R, h/R) (the interface, mesh and
delta_max / R are fixed per study).  The paths of a shell must serve the largest
gamma / (C10 R) asked of it; that value is rounded up to the ladder 1, 2, 5 x 10^k, so
studies with nearby values share their paths.  The catalogue may serve a key with a set
that reaches further (larger delta_max or gamma_max); `restrict` cuts such a set back to
the requested delta_max, so the results do not depend on what else the catalogue holds.
With error bars (the study's default), each shell has a companion on the next coarser mesh
(`Plan.error_shells`): a set of its own, keyed and stored like any other.

Another solid (`solver.material.Material`) enters the plan by its ratios to C10 (C01/C10,
C20/C10, C30/C10, Jm, D1 C10): they are FE dimensions and part of every shell's key, while
C10 stays the scaling modulus, so a C10 sweep at fixed ratios still needs one set of paths
per shell.  The study's `material:` block gives that solid; a study that sweeps a ratio
(`Study.swept_ratios`) plans one set per (t/R, h/R, ratios), and its points carry the swept
ratios after the four factors.
"""
from dataclasses import dataclass, replace
import math

from shell_adhesion.catalogue import fingerprint
from shell_adhesion.solver.case import PathSet
from shell_adhesion.solver.material import NEO_HOOKE, Material
from shell_adhesion.solver.mesh import coarser_mesh
from shell_adhesion.solver.path import Settings
from shell_adhesion.solver.scaling import gamma_hat

from .config import FACTORS, Study, material_of, requested
from .keys import pathset_key

LADDER = (1, 2, 5)
_REL_TOL = 1e-9


def gamma_max_bucket(g: float) -> float:
    """The smallest value of the ladder 1, 2, 5 x 10^k that is >= g (to 1e-9 relative)."""
    if not g > 0:
        raise ValueError(f"gamma/(C10 R) = {g!r} must be > 0")
    k = math.floor(math.log10(g)) - 1
    while True:
        for m in LADDER:
            v = float(f"{m}e{k}")
            if v >= g * (1 - _REL_TOL):
                return v
        k += 1


@dataclass(frozen=True, eq=False)
class Shell:
    """One FE path set of the plan."""

    t_over_R: float
    h_over_R: float
    gamma_hat_needed: float     # largest gamma / (C10 R) the study asks of this shell
    key: dict                   # catalogue key (gamma_max_hat: the ladder value)
    fingerprint: str
    material: Material = NEO_HOOKE

    @property
    def gamma_max_hat(self) -> float:
        return self.key["gamma_max_hat"]


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
    error_shells: tuple = ()    # each shell on the next coarser mesh (error bars), same order

    @property
    def all_shells(self) -> tuple:
        """The FE path sets to serve: the shells, then their error-bar companions."""
        return self.shells + self.error_shells

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
        return replace(self, points=points, shells=shells, ratio_axes=None, materials=None,
                       error_shells=errors)


def served_key(s: Shell, plan: Plan) -> tuple:
    """Key of a served set in the run's `served` map: (t/R, h/R, Material), and
    "coarser" after them for an error-bar companion (study.dataset.build reads it)."""
    key = (s.t_over_R, s.h_over_R, s.material)
    return key + ("coarser",) if s in plan.error_shells else key


def make_plan(study: Study, settings: Settings = Settings(),
              material: Material = None) -> Plan:
    """The distinct path sets of a validated study, with their catalogue keys; the solid
    is the study's (`material`, ratios to C10, overrides it when no ratio is swept)."""
    swept = study.swept_ratios
    solids = {}             # swept ratio values -> Material
    points = set()
    for p in requested(study):
        values = tuple(p[r][0] if r in p else getattr(NEO_HOOKE, r) for r in swept)
        if values not in solids:
            solids[values] = (material if material is not None and not swept
                              else material_of(study, p))
        points.add(tuple(p[f][0] for f in FACTORS) + values)
    points = sorted(points)
    axes = {f: tuple(sorted({p[i] for p in points})) for i, f in enumerate(FACTORS)}
    need = {}
    for p in points:
        C10, t, h, gamma = p[:4]
        g = gamma_hat(gamma, C10, study.R_mm)
        need[t, h, p[4:]] = max(need.get((t, h, p[4:]), 0.0), g)
    shells, errors = [], []
    for (t, h, values), g in sorted(need.items()):
        m = solids[values]
        key = pathset_key(t, h, study.interface, study.mesh, study.delta_max_over_R,
                          gamma_max_bucket(g), settings, m)
        shells.append(Shell(t, h, g, key, fingerprint(key), m))
        if study.error_bars:    # the same shell on the next coarser mesh: a set of its own
            key = pathset_key(t, h, study.interface, coarser_mesh(study.mesh),
                              study.delta_max_over_R, gamma_max_bucket(g), settings, m)
            errors.append(Shell(t, h, g, key, fingerprint(key), m))
    ratio_axes = ({r: tuple(sorted({p[4 + j] for p in points})) for j, r in enumerate(swept)}
                  if swept else None)
    return Plan(study, axes, tuple(points), tuple(shells), settings, ratio_axes,
                solids if swept else None, tuple(errors))


def restrict(ps: PathSet, delta_max: float) -> PathSet:
    """The part of a path set a run to `delta_max` computes: loading states and
    relaxation starts with delta <= delta_max (identical to a run that stops there,
    apart from that run's last, clipped loading step), and the views inside that range
    (a run that stops there keeps others: views are illustrations, not results)."""
    if ps.delta_max <= delta_max * (1 + _REL_TOL):
        return ps
    lim = delta_max * (1 + _REL_TOL)
    keep = ps.loading_delta <= lim
    relaxations = tuple(r for r in ps.relaxations if r.delta[0] <= lim)
    held = {r.a for r in relaxations}
    views = tuple(v for v in ps.views
                  if (v.delta <= lim if v.stage == "loading" else v.a in held))
    return replace(ps, delta_max=delta_max, loading_delta=ps.loading_delta[keep],
                   loading_P=ps.loading_P[keep], loading_a=ps.loading_a[keep],
                   loading_U=ps.loading_U[keep], loading_joined=ps.loading_joined[keep],
                   relaxations=relaxations, views=views)
