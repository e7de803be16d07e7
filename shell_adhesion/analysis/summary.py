"""The analysis of a results cube in a few lines of text (`analysis.txt` beside the tables,
`shell-adhesion analyse`): trends of |P*|, the eta fit, the free power law, the slope in
gamma and the ratio to JKR.
"""
import math

import xarray as xr

from shell_adhesion.cube import study_of
from shell_adhesion.theory import jkr_P_star_N

from .fits import eta_fit, gamma_slope, jkr_ratio, power_law_fit
from .results import R_mm, along, base_point, value_at
from .trends import trends


def summary(ds: xr.Dataset) -> str:
    """A few lines: trends of abs(P*), the eta fit, the slope in gamma, the JKR ratio."""
    s = study_of(ds)
    base = base_point(ds)
    lines = [f"study {s.get('name', '?')}: R = {R_mm(ds):g} mm, mesh {ds.attrs.get('mesh', '?')}, "
             f"interface {ds.attrs.get('interface', '?')}; base C10 = {base['C10']:g} MPa, "
             f"t/R = {base['t_over_R']:g}, h/R = {base['h_over_R']:g}, "
             f"gamma = {base['gamma']:g} J/m^2; {int((ds['status'] == 'ok').sum())} ok points"]
    for t in trends(ds):
        lines.append("trend: " + t.sentence)
    shells = ds["t_over_R"] < 1
    if int(((ds["status"] == "ok") & shells).sum()):
        f = eta_fit(ds, where=shells)
        ci = f"(95 %: {f.ci[0]:.3g} to {f.ci[1]:.3g})" if math.isfinite(f.ci[0]) else ""
        lines.append(f"eta of eq. 3 over {f.n} shell cases: {f.eta:.3g} {ci}, rms of log "
                     f"residuals {f.rms:.3f}")
        pl = power_law_fit(ds, where=shells)
        if pl.exponents:
            parts = [f"{k} {p:+.3f}" + (f" [{lo:+.3f}, {hi:+.3f}]" if math.isfinite(lo) else "")
                     + f" (eq. 3: {pl.expected[k]:+.3f})" for k, (p, (lo, hi)) in pl.exponents.items()]
            lines.append("free power law of |P*|: " + "; ".join(parts)
                         + (f"; eq. 3 outside the interval for {', '.join(pl.disagrees)}"
                            if pl.disagrees else ""))
    if along(ds, "P_star", "gamma").size >= 2:
        g = gamma_slope(ds)
        ci = f" (95 %: {g.ci[0]:.4g} to {g.ci[1]:.4g})" if math.isfinite(g.ci[0]) else ""
        lines.append(f"slope d|P*|/dgamma at the base: {g.slope:.4g} m{ci}, "
                     f"{g.ratio_to_jkr:.3f} of JKR's 1.5 pi R = {g.jkr:.4g} m; local slopes "
                     + ", ".join(f"{x:.4g}" for x in g.local) + " m")
    r = jkr_ratio(ds).where(ds["status"] == "ok")
    if int(r.notnull().sum()):
        at_base = value_at(ds, "P_star") / jkr_P_star_N(R_mm(ds), base["gamma"])
        lines.append(f"P* / JKR (-1.5 pi R gamma): {float(r.min()):.3f} to {float(r.max()):.3f}"
                     + (f", {at_base:.3f} at the base" if math.isfinite(at_base) else ""))
    return "\n".join(lines)
