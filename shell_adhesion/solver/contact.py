"""Contact of the outer surface with the rigid plane z = 0, and the rim load.

Interface models (DESIGN.md section 1):
- "no_slip": a node that touches the plane sticks where it touched (r and z held),
  under compression and tension alike (the paper's cohesive contact);
- "frictionless": a touching node keeps z = 0 and slides in r; while loading, a node
  whose reaction turns tensile is released (unilateral contact); while relaxing at
  fixed contact, held nodes stay on the plane.
Rim face: u_r = 0 and u_z = -delta.  Axis: u_r = 0.
Signs: a positive z reaction at a held node is compression (the plane pushes up).
"""
from dataclasses import dataclass

import numpy as np

from .forms import Discretisation
from shell_adhesion.errors import InputError

INTERFACES = ("no_slip", "frictionless")


def check_interface(name: str) -> str:
    if name not in INTERFACES:
        raise InputError(f"interface: {name!r} must be one of {', '.join(INTERFACES)}")
    return name


@dataclass(frozen=True, eq=False)
class Constraints:
    """Prescribed dofs: x[fixed] keeps its value except x[rimz] = -delta."""

    fixed: np.ndarray
    free: np.ndarray
    rimz: np.ndarray
    free_pos: np.ndarray  # position of each dof within `free` (-1 if fixed)


def constraints(d: Discretisation, interface: str, held) -> Constraints:
    """Constraint set for the held outer nodes (indices into capmesh.outer)."""
    cm = d.capmesh
    nodes = cm.outer[np.asarray(held, dtype=int)]
    parts = [d.ur(cm.axis), d.ur(cm.rim), d.uz(cm.rim), d.uz(nodes)]
    if interface == "no_slip":
        parts.append(d.ur(nodes))
    fixed = np.unique(np.concatenate(parts))
    mask = np.ones(d.ndof, dtype=bool)
    mask[fixed] = False
    free = np.flatnonzero(mask)
    free_pos = np.full(d.ndof, -1)
    free_pos[free] = np.arange(len(free))
    return Constraints(fixed, free, d.uz(cm.rim), free_pos)


def gaps(d: Discretisation, x, outer_index=None):
    """Deformed height z of outer nodes above the plane (units of R)."""
    cm = d.capmesh
    nodes = cm.outer if outer_index is None else cm.outer[outer_index]
    return cm.nodes[1, nodes] + x[d.uz(nodes)]


def deformed_radius(d: Discretisation, x, outer_index):
    cm = d.capmesh
    nodes = cm.outer[outer_index]
    return cm.nodes[0, nodes] + x[d.ur(nodes)]


def rim_load(d: Discretisation, r_int) -> float:
    """P / (C10 R^2), positive in compression: minus the z internal force on the rim."""
    return -float(np.sum(r_int[d.uz(d.capmesh.rim)]))


def contact_reactions(d: Discretisation, r_int, held):
    """z reactions of the plane on the held nodes (> 0 compression), units of C10 R^2."""
    return r_int[d.uz(d.capmesh.outer[np.asarray(held, dtype=int)])]
