"""Why a case's a0 (the contact radius of the equilibrium curve at P = 0) is undefined, and
the depth that answers it.

a0 lies well beyond the fixed-load pull-off a* (about 2.5 a* for the paper's base shell),
and a case's loading goes only as deep as its pull-offs need: the equilibrium curve then
ends at P < 0.  A loading to the domain's delta bound (`solver.geometry.delta_bound`: 0.25
R, or 0.9 h for thin shells) reaches larger contact radii; lengths in mm, forces in N.
"""
from shell_adhesion.solver.geometry import Cap, delta_bound

REACHED = 0.999     # a loading this close to a depth counts as having reached it


def a0_note(inp, provenance: dict, a_end_mm: float, P_end_N: float) -> str:
    """One line: where the equilibrium curve ends and the --delta-max (delta_max_mm) whose
    loading reaches further; or that the deepest loading did not reach P = 0."""
    R = inp.R_mm
    deepest = delta_bound(Cap(inp.t_mm / R, inp.h_mm / R)) * R
    reached = (provenance.get("loading_reached") or {}).get("delta_reached_mm")
    loaded = max(reached or 0.0, inp.delta_max_mm or 0.0)
    ends = (f"a0 undefined: the equilibrium curve ends at a = {a_end_mm:.4g} mm with P = "
            f"{P_end_N:.4g} N, short of P = 0")
    if loaded >= REACHED * deepest:
        return (f"{ends}, and the loading went to delta = {loaded:.4g} mm, the deepest for this "
                f"shell (delta_bound {deepest:.4g} mm): a0 lies beyond the contact radii it "
                "reaches")
    return (f"{ends} (the loading went to delta = {loaded:.4g} mm, as deep as the pull-off "
            f"needs); a deeper loading gives a0: add --delta-max {deepest:.4g} (delta_max_mm="
            f"{deepest:.4g} in Python), the deepest for this shell")
