"""Element quality of a converged state: inverted or distorted elements, the pointwise
volume ratio J of the incompressible material, and (a shell with a closed cavity) how far
its inner surface has passed the cavity's rigid lid (solver.lid: beyond LID_THROUGH the
lid's contact penalty did not hold it).

All measures are taken at the quadrature points of the displacement basis and are
dimensionless.  J = det F is the local volume ratio (hoop stretch included); the
mixed formulation enforces J = 1 only in the weak (Q1) sense, so the pointwise range of J
is the discretisation's own error indicator.  `detF_min` is the smallest determinant of
the in-plane (meridian) part of F: at or below zero an element is folded.  `distortion_min`
is, per element, the smallest over the largest in-plane det F among its quadrature points
(1 for an element deformed evenly, near 0 for one about to fold).

The inner corner of the rim (where the inner surface meets the held rim face) is a stress
singularity: pointwise J there worsens with refinement (0.852, 0.825, 0.789 on the coarse,
default and fine meshes of t/R = 0.15, h/R = 0.2 at delta = 0.047 R) while the elements
around it converge.  The elements with a node within RIM_CORNER * t of that corner are left
out of the J range (never out of the folding and distortion checks).

A thin shell pressed deep flattens onto the plane until its contact edge nears the clamped
rim; the strip between them is then squeezed and its elements leave the J range.  That
stop is the clamp's, not the mesh's (`clamp_squeeze` says so in the refusal).
"""
from dataclasses import dataclass, replace
from functools import lru_cache
import math

import numpy as np

from .forms import Discretisation, deformation
from .geometry import THIN_T
from .lid import LID_THROUGH, own_lid

# the refusal thresholds (DESIGN.md section 8): beyond them a result is not given
J_RANGE = (0.75, 4 / 3)    # pointwise J of an incompressible material (healthy states: +-12 %)
DISTORTION_MIN = 0.05      # smallest deformed-area ratio within one element
RIM_CORNER = 0.25          # radius / t of the inner rim corner's neighbourhood (J not checked)


@dataclass(frozen=True)
class Quality:
    """Worst quality measures of a state (or of several states, see `worst`)."""

    J_min: float = 1.0         # pointwise J outside the rim corner's neighbourhood
    J_max: float = 1.0
    detF_min: float = 1.0
    distortion_min: float = 1.0
    element: int = -1          # element of the worst measure
    hoop_min: float = 1.0      # smallest hoop stretch r / R_ref (<= 0: material crossed the axis)
    lid_penetration: float = 0.0   # deepest penetration / R of the cavity's lid (solver.lid)

    def as_dict(self) -> dict:
        return dict(J_min=self.J_min, J_max=self.J_max, detF_min=self.detF_min,
                    distortion_min=self.distortion_min)

    def problem(self, check_J: bool = True) -> str:
        """Why the state must be refused, or '' if it passes the thresholds (`check_J`:
        the pointwise J range counts)."""
        if not all(np.isfinite([self.J_min, self.J_max, self.detF_min, self.distortion_min,
                                self.hoop_min])):
            return "non-finite deformation"
        if self.lid_penetration > LID_THROUGH:
            return (f"the inner surface passed the cavity's lid by {self.lid_penetration:.3g} R "
                    f"(more than {LID_THROUGH:g} R: its contact penalty did not hold it)")
        if self.hoop_min <= 0:
            return (f"element {self.element} has crossed the axis (hoop stretch "
                    f"{self.hoop_min:.3g} <= 0)")
        if self.detF_min <= 0:
            return f"element {self.element} is inverted (det F = {self.detF_min:.3g})"
        if self.distortion_min < DISTORTION_MIN:
            return (f"element {self.element} is distorted (det F ratio {self.distortion_min:.3g}"
                    f" < {DISTORTION_MIN:g})")
        lo, hi = J_RANGE
        if check_J and not (lo <= self.J_min and self.J_max <= hi):
            return (f"pointwise J spans [{self.J_min:.3g}, {self.J_max:.3g}], outside "
                    f"[{lo:g}, {hi:g}] for an incompressible material")
        return ""


@lru_cache(maxsize=8)
def rim_corner_elements(capmesh) -> np.ndarray:
    """Mask of the elements with a node within RIM_CORNER * t of the inner rim corner
    (none for a solid cap, which has no inner surface)."""
    cap, mesh = capmesh.cap, capmesh.mesh
    if cap.solid:
        return np.zeros(mesh.nelements, dtype=bool)
    r, z = mesh.doflocs[:, mesh.t]
    dist = np.hypot(r - cap.rim_inner, z - cap.h).min(axis=0)
    return dist <= RIM_CORNER * cap.t * (1 + 1e-12)


def quality(d: Discretisation, x) -> Quality:
    """Quality measures of the state x (see the module docstring)."""
    f, _ = deformation(d, x)
    det2 = f[0] * f[3] - f[1] * f[2]               # (E, Q) in-plane det F
    J = det2 * f[4]
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = det2.min(axis=1) / det2.max(axis=1)
    ratio = np.where(det2.max(axis=1) > 0, ratio, -np.inf)
    e_det, e_ratio = int(np.argmin(det2.min(axis=1))), int(np.argmin(ratio))
    e_hoop = int(np.argmin(f[4].min(axis=1)))
    checked = np.flatnonzero(~rim_corner_elements(d.capmesh))
    J_in = J[checked]
    e_J = int(checked[np.argmax(np.abs(np.log(np.abs(J_in) + 1e-300)).max(axis=1))])
    lid = own_lid(d)
    q = Quality(float(J_in.min()), float(J_in.max()), float(det2.min()), float(ratio.min()),
                hoop_min=float(f[4].min()),
                lid_penetration=0.0 if lid is None else lid.penetration(x))
    element = (e_hoop if q.hoop_min <= 0 else e_det if q.detF_min <= 0
               else e_ratio if q.distortion_min < DISTORTION_MIN else e_J)
    return replace(q, element=element)


def clamp_squeeze(d: Discretisation, x, q: Quality, a: float) -> str:
    """Why the refused state x (quality q) of a thin shell (t < THIN_T) is the limit of its
    clamp, or '': a finite state off the lid whose contact edge (deformed radius a / R)
    lies within the bending length sqrt(R t) of the clamped rim, with the worst element
    (its deformed centroid) within that length of the edge or beyond it.  Measured
    (`python benchmarks/clamp.py`): the coarse and default meshes of t/R 0.02-0.1, h/R 0.2
    and 0.5 pressed to 0.9 h stop there, at deltas 1-10 % apart; the default and fine
    meshes of t/R 0.02, h/R 0.2 1.2 % apart."""
    cap, element = d.capmesh.cap, q.element
    finite = np.all(np.isfinite([q.J_min, q.J_max, q.detF_min, q.distortion_min]))
    if (cap.t >= THIN_T or element < 0 or not a > 0 or not finite
            or q.lid_penetration > LID_THROUGH):
        return ""
    ell, b = math.sqrt(cap.t), cap.rim_outer
    nodes = d.edofs[:9, element]                       # its Q2 nodes (= their u_r dofs)
    r = float(np.mean(d.capmesh.nodes[0, nodes] + x[d.ur(nodes)]))
    if not (b - a <= ell and r >= a - ell):
        return ""
    return (f"the shell is squeezed between the plane and its clamped rim: the contact edge "
            f"(a = {a:.4g} R) lies within the bending length sqrt(R t) = {ell:.3g} R of the "
            f"rim (b = {b:.4g} R), and the worst element (r = {r:.4g} R) lies by that edge; the "
            f"clamp limits this loading, not the mesh (a finer mesh stops near the same "
            f"delta)")


def worst(*qs: Quality) -> Quality:
    """The worst of each measure over several states."""
    qs = [q for q in qs if q is not None]
    if not qs:
        return Quality()
    key = min(qs, key=lambda q: (q.hoop_min > 0, q.detF_min > 0,
                                 q.distortion_min >= DISTORTION_MIN,
                                 -max(-np.log(max(q.J_min, 1e-300)), np.log(max(q.J_max, 1e-300)))))
    return Quality(min(q.J_min for q in qs), max(q.J_max for q in qs),
                   min(q.detF_min for q in qs), min(q.distortion_min for q in qs), key.element,
                   min(q.hoop_min for q in qs), max(q.lid_penetration for q in qs))
