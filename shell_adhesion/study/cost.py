"""A cost model of the FE work of a plan, for `run --dry-run` on a catalogue that has no
recorded timings: each path set costs about COST_S_PER_DOF_PATH x dofs x (relaxation
paths + LOADING_PATHS), the dofs and the paths counted on the mesh its request gives
(solver.request.initial_fit) before anything is solved.  An estimate, said as one.
"""
import math

import numpy as np

from ..solver.geometry import Cap
from ..solver.mesh import cap_mesh, mesh_spec
from ..solver.request import initial_fit

# measured on the paper's study (workflow.yaml, 33 path sets with the error-bar meshes,
# 114k dofs, 1558 paths counted so): 694 s of FE work on 2 cores that another solve
# shared (2026-12-03), so the estimate errs high; the base shell alone in one quiet
# process gives 1.9e-5 (benchmarks/pull_off.py default 1: 8.0 s, 5614 dofs, 66 paths)
COST_S_PER_DOF_PATH = 7.7e-5
LOADING_PATHS = 10          # the loading costs about as much as this many paths


def shell_size(cap: Cap, fit, mesh: str) -> tuple:
    """(dofs, relaxation paths) of one path set fitted as `fit` (solver.request.Fit),
    counted before solving: the mixed Q2/Q1 unknowns of its mesh and the element-corner
    nodes of the outer surface out to the contact radius its loading aims at (one
    relaxation path per contact event)."""
    cm = cap_mesh(cap, mesh_spec(mesh, fit.uniform))
    n2 = cm.nodes.shape[1]
    corners = np.unique(cm.mesh.t[:4]).size          # the Q1 pressure nodes
    dofs = 2 * n2 + corners
    a_end = fit.a_stop if fit.a_stop is not None else math.sqrt(min(2 * fit.delta_max, 1.0))
    r_outer = cm.nodes[0, cm.outer]
    paths = int(((r_outer <= a_end) & cm.outer_corner).sum())
    return dofs, paths


def estimate_s(shells) -> tuple:
    """(FE seconds on one core, dofs summed, paths summed) of the plan's shells to solve."""
    dofs_paths, dofs_all, paths_all = 0.0, 0, 0
    for s in shells:
        cap = Cap(s.t_over_R, s.h_over_R)
        dofs, paths = shell_size(cap, initial_fit(cap, s.request), s.key["mesh"])
        dofs_paths += dofs * (paths + LOADING_PATHS)
        dofs_all += dofs
        paths_all += paths
    return COST_S_PER_DOF_PATH * dofs_paths, dofs_all, paths_all
