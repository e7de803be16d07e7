"""Catalogue keys of the FE work of a study (DESIGN.md section 3).

`pathset_key` is the key of one set of FE paths: the dimensionless shell, the interface,
the mesh, how far the paths go (delta_max / R, the largest gamma / (C10 R) they serve),
the solver tolerances and relaxation rule, the stored layout, the package version and a
hash of the source of the modules that compute a path set (`pathset_modules`), and for a solid other than the incompressible neo-Hookean one
its `solver.material.Material.as_dict()` (the ratios C01/C10, C20/C10, C30/C10, Jm and
D1 C10: FE dimensions; neo-Hookean keys carry no material field, as before).  C10, R and
gamma are not in it, except
through a closed cavity: its `solver.cavity.Cavity.as_dict()` (mode, p/C10, p0/C10,
p_atm/C10, n) is the key's `cavity` field, so each C10 of a closed shell is its own set
(open keys carry no cavity field, as before).  `relaxation_part` names one
relaxation path of a set by its loaded start state, so a set killed half-way keeps its
finished paths (catalogue parts stored under the set's fingerprint).
"""
import ast
from dataclasses import asdict
from functools import lru_cache
import hashlib
from pathlib import Path

from shell_adhesion import solver
from shell_adhesion.catalogue import fingerprint
from shell_adhesion.solver import case, request
from shell_adhesion.solver.cavity import OPEN, Cavity
from shell_adhesion.solver.geometry import Cap, delta_bound
from shell_adhesion.solver.material import NEO_HOOKE, Material
from shell_adhesion.solver.mesh import mesh_spec
from shell_adhesion.solver.path import Settings, State
from shell_adhesion.solver.pathset_dataset import LAYOUT


# the solver modules that compute and store an energy-method path set: the key hashes them
# and every module of the package they import (the cohesive interface, arc-length continuation,
# curve fitting and the closed forms are outside it, so work on those keeps stored path sets)
PATHSET_ROOTS = ("solver.request", "solver.case", "solver.pathset_dataset")


def _imported(module: str) -> set:
    """The package's modules (dotted, below shell_adhesion) that `module`'s source imports."""
    package_root = Path(solver.__file__).parent.parent
    path = package_root.joinpath(*module.split(".")).with_suffix(".py")
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level:                      # relative: from .x import ... inside a subpackage
            base = module.split(".")[: -node.level]
            name = ".".join(base + ([node.module] if node.module else []))
        elif (node.module or "").startswith("shell_adhesion."):
            name = node.module.removeprefix("shell_adhesion.")
        else:
            continue
        if package_root.joinpath(*name.split(".")).with_suffix(".py").is_file():
            out.add(name)
    return out


def imported_closure(roots) -> tuple:
    """`roots` and every package module they import, transitively (sorted)."""
    seen, todo = set(), list(roots)
    while todo:                             # bounded: each module enters `seen` once
        m = todo.pop()
        if m not in seen:
            seen.add(m)
            todo.extend(_imported(m) - seen)
    return tuple(sorted(seen))


def pathset_modules() -> tuple:
    """PATHSET_ROOTS and every package module they import, transitively (sorted)."""
    return imported_closure(PATHSET_ROOTS)


def source_sha256(modules: tuple) -> str:
    """sha256 over the names and sources of `modules` (dotted, below shell_adhesion)."""
    package_root = Path(solver.__file__).parent.parent
    h = hashlib.sha256()
    for m in modules:
        p = package_root.joinpath(*m.split(".")).with_suffix(".py")
        h.update(m.encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()


@lru_cache(maxsize=1)
def solver_source_sha256() -> str:
    """sha256 over the names and sources of `pathset_modules()`."""
    return source_sha256(pathset_modules())


def pathset_key(t_over_R, h_over_R, interface, mesh, delta_max_over_R, gamma_max_hat,
                settings: Settings = None, material: Material = NEO_HOOKE,
                cavity: Cavity = OPEN) -> dict:
    """Key of the FE path set of one dimensionless shell (validated names and values).

    The set is fitted to its request (solver.request.Request.serving): the ladder of gammas
    up to gamma_max_hat and delta_max / R (None: as deep as they need, within
    solver.geometry.delta_bound, which is then the key's delta_max_over_R), under the
    request's rules; the even zone and the loading depth it ends with are stored with it,
    not keyed."""
    settings = settings if settings is not None else Settings()
    key = {
        "kind": "shell-adhesion path set",
        "layout": LAYOUT,
        "t_over_R": float(t_over_R),
        "h_over_R": float(h_over_R),
        "interface": str(interface),
        "mesh": str(mesh),
        "mesh_spec": asdict(mesh_spec(mesh)),
        "delta_max_over_R": float(delta_bound(Cap(t_over_R, h_over_R))
                                  if delta_max_over_R is None else delta_max_over_R),
        "gamma_max_hat": float(gamma_max_hat),
        # in the family too: a set fitted to another depth never serves
        "request": {"delta_max_over_R": "auto" if delta_max_over_R is None
                    else float(delta_max_over_R), "rules": request.rules()},
        "settings": asdict(settings),
        "relaxation_rule": {"G_SAFETY": case.G_SAFETY},
        "version": solver.__version__,
        "solver_source": solver_source_sha256(),
    }
    if material != NEO_HOOKE:
        key["material"] = material.as_dict()
    if cavity.closed:       # pressures / C10 are FE parameters
        key["cavity"] = cavity.as_dict()
    return key


def relaxation_part(start: State, views: bool, reach: float = 1.0,
                    uniform: float = None) -> str:
    """Name of the relaxation path from the loaded state `start` (with its views or not,
    relaxed to `reach`, on the mesh even out to `uniform` of arc) among the parts of a path
    set: a fingerprint of the start state and of those."""
    return fingerprint({"delta": start.delta, "a": start.a, "held": list(start.held),
                        "views": bool(views), "reach": float(reach),
                        "uniform": None if uniform is None else float(uniform)})
