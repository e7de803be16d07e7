"""Quadratic quadrilateral mesh of the cap's meridian cross-section (units of R).

A shell (t < 1) is one mapped block: polar angle along the meridian, radius through the
thickness.  A solid cap (t = 1) is three transfinite-interpolation blocks around the
apex, the rim and the axis.  Element sizes grow geometrically from the apex, where
contact forms, toward the rim; through the thickness they grow from the outer surface.
Nodes (Q2, 9 per element) lie exactly on the spheres.
"""
from dataclasses import dataclass, replace

import numpy as np
from skfem import MeshQuad1, MeshQuad2, ElementQuad2

from .geometry import Cap
from shell_adhesion.errors import InputError


@dataclass(frozen=True)
class MeshSpec:
    """Mesh density, lengths in units of R."""

    name: str
    h_apex: float        # element size along the outer surface at the apex
    growth: float        # size ratio of neighbouring elements along the outer surface
    h_max: float         # largest element size along the outer surface
    layer0: float        # first element size through the thickness, at the outer surface
    layer_growth: float  # size ratio of neighbouring layers
    layer_max: float     # largest layer size
    uniform: float = 0.0 # arc length from the apex meshed at h_apex before growth starts


# uniform out to 0.15 R (3 mm on the paper's shell): the pull-off radii (a*/R ~ 0.1) and
# the JKR/Hertz contact zones sit in elements of one size, so G converges there
_BASE = MeshSpec("default", h_apex=0.004, growth=1.08, h_max=0.08,
                 layer0=0.008, layer_growth=1.35, layer_max=0.08, uniform=0.15)


# the family: each level halves the sizes of the one before; 'coarser' only serves as the
# second mesh of the error estimate of 'coarse' (`coarser_mesh`), 'finer' as a reference
LEVELS = {"coarsest": -3, "coarser": -2, "coarse": -1, "default": 0, "fine": 1, "finer": 2}


def coarser_mesh(name: str) -> str:
    """The next coarser mesh of the family (the second mesh of the error estimate)."""
    level = LEVELS[name] - 1
    return next(n for n, v in LEVELS.items() if v == level)


def mesh_spec(name: str, uniform: float = None) -> MeshSpec:
    """The named mesh: 'coarse', 'default' or 'fine' (each halves the sizes of the last),
    evenly meshed out to `uniform` of arc / R from the apex (default: 0.15, the base
    shell's; `solver.request` sizes it to the contact radii a request needs)."""
    levels = LEVELS
    if name not in levels:
        raise InputError(f"mesh: {name!r} must be one of coarse, default, fine")
    f = 2.0 ** (-levels[name])
    b = _BASE
    return MeshSpec(name, b.h_apex * f, b.growth ** f, b.h_max * f,
                    b.layer0 * f, b.layer_growth ** f, b.layer_max * f,
                    b.uniform if uniform is None else float(uniform))


def uniform_arc(cap: Cap, spec: MeshSpec) -> float:
    """Arc length / R from the apex meshed at the apex size (at most the cap's own)."""
    return min(spec.uniform, cap.theta_outer)


def uniform_radius(cap: Cap, spec: MeshSpec) -> float:
    """Reference radius / R out to which the outer surface is meshed evenly.  Beyond it
    element sizes grow, and there the energy method's G carries a bias from the grading
    that the next coarser mesh of the family shares, so an error bar cannot see it
    (measured on t/R = 0.1 at gamma/(C10 R) = 0.005, a* = 0.23 R: P* 1.3 % higher with
    the contact edge in graded elements than in even ones on the default mesh, and the
    coarse mesh the same; 0.7 % on the fine mesh)."""
    return float(np.sin(uniform_arc(cap, spec)))


def graded(length, h0, growth, hmax, uniform=0.0):
    """Node positions 0..length: size h0 up to `uniform`, then h0*growth, ... capped at hmax."""
    sizes = []
    total, h = 0.0, h0
    while total < length * (1 - 1e-12):
        sizes.append(h)
        total += h
        if total >= uniform:
            h = min(h * growth, hmax)
    sizes = np.array(sizes)
    # the last element takes what is left; merge it if it would be a sliver
    excess = total - length
    if len(sizes) > 1 and sizes[-1] - excess < 0.5 * sizes[-2]:
        sizes = sizes[:-1]
    sizes *= length / sizes.sum()
    return np.concatenate([[0.0], np.cumsum(sizes)])


# a thin shell (the default level's graded layers fewer than THIN_LAYERS) has THIN_LAYERS
# layers on the default mesh, twice as many on each finer level and half as many on each
# coarser one (at least 1), so every step of the family refines through the thickness
THIN_LAYERS = 4


def _graded_layers(t, spec):
    return graded(t, spec.layer0, spec.layer_growth, min(spec.layer_max, t / 2))


def thin_shell(t: float) -> bool:
    """Whether a shell of thickness t / R takes the thin family of layers (the default
    level's graded layers number fewer than THIN_LAYERS: t / R below about 0.041)."""
    return t < 1.0 and len(_graded_layers(t, _BASE)) - 1 < THIN_LAYERS


def thickness_layers(t: float, spec: MeshSpec) -> np.ndarray:
    """Depths / R below the outer surface of the element-layer boundaries through a shell
    of thickness t / R (0 ... t).  Graded from the outer surface (`spec.layer0`, growing
    by `spec.layer_growth` up to `spec.layer_max` and t / 2); a thin shell (`thin_shell`)
    instead has THIN_LAYERS x 2^level layers (at least 1; level 0 default, -1 coarse, 1
    fine, from `spec.layer_max`), growing by `spec.layer_growth` from the outer surface:
    the graded rule keeps 1-2 layers on the coarse levels of a thin shell (t/R 0.02: 1, 1,
    2 on coarser, coarse, default), whose steps then refine the meridian only and measure
    no order (solver.error_bars.refines_through_thickness).  From t/R 0.041 (the shipped
    pull-off maps' grids start at 0.05) every mesh is the graded one, also where its
    coarse levels keep the layers (t/R 0.041-0.06: 2, 2, 4 on coarser, coarse, default:
    those bars take the assumed order)."""
    if not thin_shell(t):
        return _graded_layers(t, spec)
    level = np.log2(_BASE.layer_max / spec.layer_max)
    n = max(1, int(round(THIN_LAYERS * 2.0 ** level)))
    sizes = spec.layer_growth ** np.arange(n)
    return np.concatenate([[0.0], np.cumsum(sizes)]) * (t / sizes.sum())


def with_midpoints(x):
    """Q2 parameter positions: corners and midpoints."""
    out = np.empty(2 * len(x) - 1)
    out[0::2] = x
    out[1::2] = 0.5 * (x[:-1] + x[1:])
    return out


def _shell_block(cap, spec):
    theta = graded(cap.theta_outer, spec.h_apex, spec.growth, spec.h_max, uniform_arc(cap, spec))
    sigma = with_midpoints(theta / cap.theta_outer)
    depth = with_midpoints(thickness_layers(cap.t, spec))
    rho = 1.0 - depth
    th = sigma[:, None] * np.arccos((1.0 - cap.h) / rho)[None, :]
    return np.stack([rho * np.sin(th), 1.0 - rho * np.cos(th)], axis=-1)


def _segment(p, q, u):
    return p[None, :] + u[:, None] * (q - p)[None, :]


def _tfi(bottom, top, left, right):
    """Transfinite interpolation grid (ns, nt, 2) from four boundary point arrays."""
    u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(bottom, axis=0).T))])
    v = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(left, axis=0).T))])
    u, v = (u / u[-1])[:, None, None], (v / v[-1])[None, :, None]
    b, t = bottom[:, None, :], top[:, None, :]
    l, r = left[None, :, :], right[None, :, :]
    corners = ((1 - u) * (1 - v) * bottom[0] + u * (1 - v) * bottom[-1]
               + (1 - u) * v * top[0] + u * v * top[-1])
    return (1 - v) * b + v * t + (1 - u) * l + u * r - corners


def _solid_blocks(cap, spec):
    theta = graded(cap.theta_outer, spec.h_apex, spec.growth, spec.h_max, uniform_arc(cap, spec))
    k = int(np.argmin(np.abs(theta - min(0.6, 0.6 * cap.theta_outer))))
    th = with_midpoints(theta)
    arc = np.stack([np.sin(th), 1.0 - np.cos(th)], axis=-1)
    A, B, C = arc[0], arc[-1], np.array([0.0, cap.h])
    M_ab = arc[2 * k]
    M_ca = np.array([0.0, 0.4 * cap.h])
    M_bc = 0.5 * (B + C)
    G = 0.7 * (M_ab + M_ca - A) + 0.3 * (A + B + C) / 3.0
    ua = with_midpoints(theta[: k + 1] / theta[k])
    ub = with_midpoints((theta[k:] - theta[k]) / (theta[-1] - theta[k]))
    uc = with_midpoints(graded(M_ca[1], spec.layer0, spec.layer_growth, spec.layer_max) / M_ca[1])
    block1 = _tfi(arc[: 2 * k + 1], _segment(M_ca, G, ua), _segment(A, M_ca, uc), _segment(M_ab, G, uc))
    block2 = _tfi(arc[2 * k:], _segment(G, M_bc, ub), _segment(M_ab, G, uc), _segment(B, M_bc, uc))
    block3 = _tfi(_segment(M_ca, G, ua), _segment(C, M_bc, ua), _segment(M_ca, C, ub), _segment(G, M_bc, ub))
    return [block1, block2, block3]


@dataclass(frozen=True, eq=False)
class CapMesh:
    """A Q2 mesh of the cap with its boundary node sets (Q2 node indices)."""

    cap: Cap
    spec: MeshSpec
    mesh: MeshQuad2
    outer: np.ndarray        # outer-surface nodes, ordered from the apex toward the rim
    outer_corner: np.ndarray # True where the outer node is an element corner
    inner: np.ndarray
    rim: np.ndarray
    axis: np.ndarray

    @property
    def nodes(self) -> np.ndarray:
        return self.mesh.doflocs


def cap_mesh(cap: Cap, spec: MeshSpec) -> CapMesh:
    """Mesh the cross-section of `cap` (units of R) with density `spec`."""
    blocks = [_shell_block(cap, spec)] if not cap.solid else _solid_blocks(cap, spec)
    verts, cells, where = [], [], []
    offset = 0
    for b, grid in enumerate(blocks):
        corners = grid[::2, ::2]
        ns, nt = corners.shape[0] - 1, corners.shape[1] - 1
        idx = offset + np.arange(corners.shape[0] * corners.shape[1]).reshape(corners.shape[:2])
        verts.append(corners.reshape(-1, 2))
        i, j = np.meshgrid(np.arange(ns), np.arange(nt), indexing="ij")
        i, j = i.ravel(), j.ravel()
        cells.append(np.stack([idx[i, j], idx[i + 1, j], idx[i + 1, j + 1], idx[i, j + 1]]))
        where.append(np.stack([np.full_like(i, b), i, j]))
        offset += corners.shape[0] * corners.shape[1]
    verts = np.concatenate(verts)
    cells = np.concatenate(cells, axis=1)
    where = np.concatenate(where, axis=1)
    key = np.round(verts / 1e-10).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)
    renumber = np.empty_like(order)
    renumber[order] = np.arange(len(order))
    p = verts[first[order]].T
    t = renumber[inverse.ravel()][cells]
    m2 = MeshQuad2.from_mesh(MeshQuad1(np.ascontiguousarray(p), np.ascontiguousarray(t)))
    doflocs = np.array(m2.doflocs, order="C")
    loc = (2 * ElementQuad2.doflocs).astype(int)  # (9, 2) local Q2 grid offsets
    edofs = m2.dofs.element_dofs
    for b, grid in enumerate(blocks):
        sel = where[0] == b
        ii = 2 * where[1, sel][None, :] + loc[:, 0][:, None]
        jj = 2 * where[2, sel][None, :] + loc[:, 1][:, None]
        doflocs[:, edofs[:, sel]] = np.moveaxis(grid[ii, jj], -1, 0)
    mesh = MeshQuad2(np.ascontiguousarray(doflocs), m2.t)
    return _with_boundaries(cap, spec, mesh)


def _with_boundaries(cap, spec, mesh):
    r, z = mesh.doflocs
    tol = 1e-9
    rho = np.hypot(r, z - 1.0)
    outer = np.flatnonzero(np.abs(rho - 1.0) < tol)
    outer = outer[np.argsort(np.arctan2(r[outer], 1.0 - z[outer]))]
    inner = (np.flatnonzero(np.abs(rho - (1.0 - cap.t)) < tol) if not cap.solid
             else np.array([], dtype=int))
    rim = np.flatnonzero(np.abs(z - cap.h) < tol)
    axis = np.flatnonzero(r < tol)
    corner = outer < mesh.nvertices
    return CapMesh(cap, spec, mesh, outer, corner, inner, rim, axis)


def scaled(cm: CapMesh, length: float) -> CapMesh:
    """The same mesh with every coordinate multiplied by `length` (a dimensional mesh)."""
    mesh = MeshQuad2(np.ascontiguousarray(cm.mesh.doflocs * length), cm.mesh.t)
    return replace(cm, mesh=mesh)
